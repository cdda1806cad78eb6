// SH visibility (issue 16): the host's regularised pseudo-inverse (inputs/visibility.h) and the shared
// per-pixel fit (shade/visibility.h visFit) on synthetic maps, in the scalar and 8-lane builds.
// Emulator vs lavapipe on real scenes is the ctest `verify_visibility_*`.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <numbers>
#include <random>
#include <sstream>

#include "inputs/environment.h"
#include "inputs/visibility.h"
#include "lanes/instantiate.h"
#include "passes/shade.h"
#include "passes/visibility.h"
#include "reference/reference.h"
#include "scene/scene.h"

namespace {

using shadetwin::Vec3;
const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }

shadetwin::Scene bunny() {
  return shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/bunny.json");
}

// M = sum_k y y^T of the directions, row-major 16 x 16.
std::array<double, 256> normalMatrix(const std::vector<Vec3>& dirs) {
  std::array<double, 256> m{};
  for (const Vec3& d : dirs) {
    const auto y = shadetwin::sh16BasisDouble(d);
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) m[size_t(16 * i + j)] += y[size_t(i)] * y[size_t(j)];
  }
  return m;
}
std::array<double, 256> mul(const std::array<double, 256>& a, const std::array<double, 256>& b) {
  std::array<double, 256> r{};
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 16; ++k)
      for (int j = 0; j < 16; ++j) r[size_t(16 * i + j)] += a[size_t(16 * i + k)] * b[size_t(16 * k + j)];
  return r;
}

// The scalar fit of one point with explicit maps: `depth(k)` fills map k (S x S) uniformly.
shadetwin::shade::scalar::Sh16 fitPoint(const shadetwin::VisibilitySetup& v, const emu::Texture& maps, Vec3 p, Vec3 n) {
  namespace sc = shadetwin::shade::scalar;
  const auto mapS = shadetwin::environmentSampler(maps, dev(), false), dataS = shadetwin::environmentSampler(*v.data, dev(), false);
  const sc::VisSettings s{maps.layers(), maps.width(), v.settings.fitCosine ? sc::kVisFitVCos : sc::kVisFitV, v.biasConst, v.biasSlope};
  return sc::visFit(mapS, dataS, s, shadetwin::shade::V3<float>(p[0], p[1], p[2]), shadetwin::shade::V3<float>(n[0], n[1], n[2]));
}
emu::Texture uniformMaps(uint32_t K, uint32_t S, float depth) {
  std::vector<std::vector<uint8_t>> level(1, std::vector<uint8_t>(size_t(S) * S * K * 4));
  for (size_t i = 0; i < size_t(S) * S * K; ++i) std::memcpy(level[0].data() + 4 * i, &depth, 4);
  return emu::Texture(emu::Format::R32F, S, S, K, std::move(level));
}
std::array<float, 16> flat(const shadetwin::shade::scalar::Sh16& c) {
  return {c.a.x, c.a.y, c.a.z, c.a.w, c.b.x, c.b.y, c.b.z, c.b.w, c.c.x, c.c.y, c.c.z, c.c.w, c.d.x, c.d.y, c.d.z, c.d.w};
}
// A setup whose directions are given (the data table is rebuilt through visibilitySetup's layout by
// placing a constant environment... simpler: an environment texture with one bright texel per
// direction is not needed: visibilitySetup falls back to uniform directions for a black map).
shadetwin::VisibilitySetup uniformSetup(uint32_t K, bool cosine, const shadetwin::Scene& scene) {
  const float black[4] = {0, 0, 0, 1};
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, 1, 1, black);
  shadetwin::VisibilitySettings s;
  s.maps = K;
  s.size = 4096;  // the bias (in texels of this size) stays small; the synthetic maps are 16^2
  s.fitCosine = cosine;
  return shadetwin::visibilitySetup(scene, env, s);
}

TEST(Visibility, BasisIsOrthonormal) {
  // sum over a dense uniform set of y_i y_j dw = delta_ij.
  const auto dirs = shadetwin::sphereDirections(20000);
  const auto m = normalMatrix(dirs);
  const double dw = 4 * std::numbers::pi / double(dirs.size());
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) EXPECT_NEAR(m[size_t(16 * i + j)] * dw, i == j ? 1.0 : 0.0, 2e-3) << i << "," << j;
}

TEST(Visibility, PseudoInverseOfFullRankAndDeficientSets) {
  for (uint32_t K : {1u, 4u, 9u, 15u, 16u, 17u, 64u}) {
    const auto dirs = shadetwin::sphereDirections(K);
    uint32_t rank = 0;
    const auto P = shadetwin::sh16PseudoInverse(dirs, 1e-10, &rank);
    for (double x : P) ASSERT_TRUE(std::isfinite(x)) << K;
    EXPECT_LE(rank, std::min<uint32_t>(K, 16)) << K;
    // Moore-Penrose identity M P M = M (mu -> 0).
    const auto M = normalMatrix(dirs), MPM = mul(mul(M, P), M);
    double err = 0, scale = 0;
    for (size_t i = 0; i < 256; ++i) err = std::max(err, std::fabs(MPM[i] - M[i])), scale = std::max(scale, std::fabs(M[i]));
    EXPECT_LT(err, 1e-6 * scale) << K;
  }
  // 64 spread directions: full rank, P = M^-1.
  uint32_t rank = 0;
  shadetwin::sh16PseudoInverse(shadetwin::sphereDirections(64), 1e-4, &rank);
  EXPECT_EQ(rank, 16u);
}

TEST(Visibility, UnoccludedFitApproachesTheClampedCosineProjection) {
  // Nothing occludes (maps at depth 1): the fit is the prior, the SH projection of max(0, y) for
  // n = +y (c0 = pi Y00 = 0.8862, c1 (y) = 2 pi/3 Y1 = 1.0233, band 3 zero), checked against the
  // double-precision quadrature of the same basis.
  const shadetwin::Scene scene = bunny();
  const auto v = uniformSetup(256, true, scene);
  const auto maps = uniformMaps(256, 16, 1.0f);
  const Vec3 n{0, 1, 0}, p{0, 0.2f, 0};
  const auto c = flat(fitPoint(v, maps, p, n));
  // Quadrature of max(0, y) y_i over 200k uniform directions.
  const auto dense = shadetwin::sphereDirections(200000);
  std::array<double, 16> proj{};
  for (const Vec3& d : dense) {
    const auto y = shadetwin::sh16BasisDouble(d);
    for (int i = 0; i < 16; ++i) proj[size_t(i)] += std::max(0.0, double(d[1])) * y[size_t(i)];
  }
  for (double& x : proj) x *= 4 * std::numbers::pi / double(dense.size());
  EXPECT_NEAR(proj[0], 0.8862, 1e-3);
  EXPECT_NEAR(proj[1], 1.0233, 1e-3);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(c[size_t(i)], proj[size_t(i)], 2e-3) << i;  // band 3: 0 (A_3 = 0)
}

TEST(Visibility, OpenPixelFitsThePriorExactlyAndBlockedPixelFitsZero) {
  // Regularised towards the unoccluded transfer t: a pixel no map occludes gets exactly t (every
  // residual is 0), bit for bit; a pixel every map occludes, with 64 spread directions (full rank),
  // gets a fit that is ~0 at every sampled direction (the least-squares residual).
  const shadetwin::Scene scene = bunny();
  for (bool cosine : {true, false}) {
    const auto v = uniformSetup(64, cosine, scene);
    const Vec3 n{0, 1, 0};
    const auto open = flat(fitPoint(v, uniformMaps(64, 16, 1.0f), {0, 0.2f, 0}, n));
    const double pi = std::numbers::pi;
    const auto y = shadetwin::sh16BasisDouble(n);
    for (int i = 0; i < 16; ++i) {
      const double band = i == 0 ? pi : i < 4 ? 2 * pi / 3 : i < 9 ? pi / 4 : 0.0;
      const double t = cosine ? band * y[size_t(i)] : (i == 0 ? 2 * std::sqrt(pi) : 0.0);
      EXPECT_NEAR(open[size_t(i)], t, 1e-6) << cosine << " " << i;
    }
    const auto blocked = flat(fitPoint(v, uniformMaps(64, 16, 0.0f), {0, 0.2f, 0}, n));
    double worst = 0;
    for (const Vec3& d : v.directions) {
      const auto yd = shadetwin::sh16BasisDouble(d);
      double f = 0;
      for (int i = 0; i < 16; ++i) f += double(blocked[size_t(i)]) * yd[size_t(i)];
      worst = std::max(worst, std::fabs(f));
    }
    // V alone: the residual -1 is in the span (Y00), fitted exactly; V max(0, n.w): the residual
    // -max(0, n.w) is not band-limited, so the least-squares fit leaves a small residual (0.003 here).
    EXPECT_LT(worst, cosine ? 0.01 : 1e-4) << cosine;
  }
}

TEST(Visibility, FewAndCoincidentDirectionsStayFinite) {
  // K < 16 (rank-deficient normal equations) and a single-texel sun (all K directions equal, rank 1).
  const shadetwin::Scene scene = bunny();
  std::vector<float> sun(64 * 32 * 4, 0.0f);
  for (size_t i = 3; i < sun.size(); i += 4) sun[i] = 1.0f;
  sun[4 * (10 * 64 + 20)] = sun[4 * (10 * 64 + 20) + 1] = sun[4 * (10 * 64 + 20) + 2] = 30000.0f;
  const emu::Texture sunEnv = emu::floatTexture(emu::Format::RGBA32F, 64, 32, sun.data());
  for (uint32_t K : {1u, 3u, 8u, 16u}) {
    shadetwin::VisibilitySettings s;
    s.maps = K;
    s.size = 4096;
    s.fitCosine = false;
    const auto v = shadetwin::visibilitySetup(scene, sunEnv, s);
    EXPECT_FALSE(v.uniformFallback);
    EXPECT_EQ(v.rank, 1u) << K;  // all directions are the sun's texel
    for (size_t k = 1; k < v.directions.size(); ++k) EXPECT_EQ(v.directions[k], v.directions[0]);
    const auto c = fitPoint(v, uniformMaps(K, 16, 1.0f), {0, 0.2f, 0}, {0, 1, 0});
    for (float x : flat(c)) EXPECT_TRUE(std::isfinite(x)) << K;
    // The fit reproduces the sample at the sampled direction: V(sun) = 1.
    const auto y = shadetwin::sh16BasisDouble(v.directions[0]);
    double at = 0;
    const auto f = flat(c);
    for (int i = 0; i < 16; ++i) at += f[size_t(i)] * y[size_t(i)];
    EXPECT_NEAR(at, 1.0, 1e-3) << K;
    // Uniform directions, K = 4: rank 4, still finite.
    const auto u = uniformSetup(K, false, scene);
    for (float x : flat(fitPoint(u, uniformMaps(K, 16, 0.5f), {0, 0.2f, 0}, {0, 1, 0}))) EXPECT_TRUE(std::isfinite(x));
  }
}

TEST(Visibility, EightLaneFitEqualsScalarAndTheBunnyShadowsThePlinth) {
  // The real scene at 128 x 128 with 16 maps of 256^2 from forest's luminance: the 8-lane pass equals
  // the scalar build bit for bit at every pixel, and the plinth next to the bunny (r < 0.4) is in
  // its shadow for more of the sampled directions than the open plinth (r > 0.55): the fitted
  // function's mean over the K directions is lower.
  shadetwin::Scene scene = bunny();
  scene.width = scene.height = 128;
  std::ostringstream quiet;
  const shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(scene.environment, quiet);
  shadetwin::VisibilitySettings s;
  s.maps = 16;
  s.size = 256;
  const auto v = shadetwin::visibilitySetup(scene, *env.texture, s);
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(scene, dev());
  const emu::Texture maps = shadetwin::shadowMapArray(shadetwin::shadowEmu(scene, v.directions, s.size, dev()));
  const shadetwin::VisibilityImage img = shadetwin::visibilityFitEmu(g, maps, v, dev());
  // The fitted function's mean over the K sampled directions (what the fit reproduces), per pixel.
  std::vector<std::array<double, 16>> Y;
  for (const Vec3& d : v.directions) Y.push_back(shadetwin::sh16BasisDouble(d));
  auto meanFit = [&](const float* c) {
    double m = 0;
    for (const auto& y : Y)
      for (int i = 0; i < 16; ++i) m += double(c[i]) * y[size_t(i)];
    return m / double(Y.size());
  };
  size_t same = 0, geometry = 0, nearN = 0, farN = 0;
  double nearSum = 0, farSum = 0;
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      const float* t = g.at(x, y);
      if (t[3] == 0.0f) continue;
      ++geometry;
      const auto c = flat(fitPoint(v, maps, {t[0], t[1], t[2]}, {t[4], t[5], t[6]}));
      same += std::memcmp(c.data(), img.at(x, y), 64) == 0;
      if (!(std::fabs(t[1]) < 1e-3f && t[5] > 0.99f)) continue;  // the plinth's top at y = 0
      const double r = std::hypot(double(t[0]), double(t[2])), m = meanFit(img.at(x, y));
      if (r < 0.4) nearSum += m, ++nearN;
      if (r > 0.55) farSum += m, ++farN;
    }
  EXPECT_GT(geometry, 1000u);
  EXPECT_EQ(same, geometry);
  ASSERT_GT(nearN, 20u);
  ASSERT_GT(farN, 20u);
  EXPECT_LT(nearSum / nearN, 0.8 * (farSum / farN)) << nearSum / nearN << " vs " << farSum / farN;
}

TEST(Visibility, FilterAveragesTheSurfaceAndStopsAtEdges) {
  // A synthetic 12 x 8 G-buffer: the left half a plane at depth z = 0 facing +z, the right half a
  // plane at z = -1 (a depth step), one background pixel; coefficient c0 = 1 on the left, 3 on the
  // right, c1 = the pixel's x. Box (radius 1): a left pixel next to the step mixes both sides; the
  // edge-aware filter keeps it at 1; the background pixel keeps its own coefficients; 8 lanes equal
  // the scalar build; a constant image stays constant.
  shadetwin::GBuffer g;
  g.width = 12, g.height = 8;
  g.texels.assign(size_t(12) * 8 * shadetwin::kGbufFloats, 0.0f);
  shadetwin::VisibilityImage img;
  img.width = 12, img.height = 8;
  img.coeffs.assign(size_t(12) * 8 * 16, 0.0f);
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 12; ++x) {
      float* t = &g.texels[(size_t(y) * 12 + x) * shadetwin::kGbufFloats];
      const bool right = x >= 6;
      t[0] = float(x) * 0.1f, t[1] = float(y) * 0.1f, t[2] = right ? -1.0f : 0.0f, t[3] = 1.0f;
      t[4] = 0, t[5] = 0, t[6] = 1;
      float* c = &img.coeffs[(size_t(y) * 12 + x) * 16];
      c[0] = right ? 3.0f : 1.0f;
      c[1] = float(x);
    }
  g.texels[(size_t(7) * 12 + 0) * shadetwin::kGbufFloats + 3] = 0.0f;  // (0, 7): background
  img.coeffs[(size_t(7) * 12 + 0) * 16] = 42.0f;
  const shadetwin::Scene scene = bunny();
  shadetwin::VisibilitySetup v = uniformSetup(4, true, scene);
  v.settings.filterRadius = 1;
  v.planeTolerance = 0.05f;
  auto at = [&](const shadetwin::VisibilityImage& i, uint32_t x, uint32_t y, int k) { return i.coeffs[(size_t(y) * 12 + x) * 16 + size_t(k)]; };
  v.settings.filterEdgeAware = false;
  const auto box = shadetwin::visibilityFilterEmu(g, img, v, dev());
  EXPECT_FLOAT_EQ(at(box, 5, 3, 0), (6.0f * 1 + 3.0f * 3) / 9.0f);  // 3 x 3 around x = 5 includes x = 6
  EXPECT_FLOAT_EQ(at(box, 2, 3, 1), 2.0f);                          // mean of x = 1, 2, 3
  EXPECT_EQ(at(box, 0, 7, 0), 42.0f);                               // background keeps its own
  v.settings.filterEdgeAware = true;
  const auto edge = shadetwin::visibilityFilterEmu(g, img, v, dev());
  EXPECT_FLOAT_EQ(at(edge, 5, 3, 0), 1.0f);
  EXPECT_FLOAT_EQ(at(edge, 6, 3, 0), 3.0f);
  EXPECT_FLOAT_EQ(at(edge, 5, 3, 1), 4.5f);  // x = 4, 5 only (x = 6 is behind the step)
  // The scalar build of visFilter gives the same bits as the 8-lane pass at every pixel.
  namespace sc = shadetwin::shade::scalar;
  const emu::Texture ct = shadetwin::visibilityCoeffTexture(img), gt = shadetwin::gbufferPositionNormalTexture(g);
  const auto cs = shadetwin::environmentSampler(ct, dev(), false), gs = shadetwin::environmentSampler(gt, dev(), false);
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 12; ++x) {
      const auto c = flat(sc::visFilter(cs, gs, int32_t(x), int32_t(y), 12, 8, 1, sc::kVisFilterEdge, 0.05f));
      EXPECT_EQ(0, std::memcmp(c.data(), &edge.coeffs[(size_t(y) * 12 + x) * 16], 64)) << x << "," << y;
    }
}

// A 192^2 scene with `objects` (a JSON array) under forest, seen from above the front, written next to
// the build (relative asset paths) and loaded.
shadetwin::Scene testScene(const std::string& name, const std::string& objects) {
  const auto dir = std::filesystem::path(SHADETWIN_SOURCE_DIR) / "build-test-scenes";
  std::filesystem::create_directories(dir);
  const auto p = dir / name;
  std::ofstream(p) << R"({"image": {"width": 192, "height": 192},
    "camera": {"eye": [0, 1.6, 1.6], "target": [0, 0, 0], "fov": 45, "near": 0.5, "far": 6},
    "environment": {"file": "../assets/hdri/forest.exr"}, "objects": )" + objects + "}";
  return shadetwin::loadScene(p.string());
}

// A sphere of radius 0.3 resting on a plane.
shadetwin::Scene sphereOnPlane() {
  return testScene("sphere_on_plane.json", R"([{"mesh": "plane", "scale": 1.0}, {"mesh": "sphere", "fit": 0.6}])");
}

// 64 uniform directions (a black environment), 1024^2 maps of `scene`, its G-buffer, and whether
// map k leaves a point lit (the shared visResidual, V fit, the default bias).
struct MapTests {
  shadetwin::VisibilitySetup v;
  shadetwin::GBuffer g;
  emu::Texture maps;
  explicit MapTests(const shadetwin::Scene& scene)
      : v(setup(scene)), g(shadetwin::gbufferEmu(scene, dev())),
        maps(shadetwin::shadowMapArray(shadetwin::shadowEmu(scene, v.directions, v.settings.size, dev()))) {}
  static shadetwin::VisibilitySetup setup(const shadetwin::Scene& scene) {
    const float black[4] = {0, 0, 0, 1};
    const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, 1, 1, black);
    shadetwin::VisibilitySettings vs;
    vs.maps = 64;
    vs.size = 1024;
    vs.fitCosine = false;
    return shadetwin::visibilitySetup(scene, env, vs);
  }
  bool lit(uint32_t k, shadetwin::shade::V3<float> p, shadetwin::shade::V3<float> n) const {
    namespace sc = shadetwin::shade::scalar;
    const auto mapS = shadetwin::environmentSampler(maps, dev(), false), dataS = shadetwin::environmentSampler(*v.data, dev(), false);
    const sc::VisSettings s{maps.layers(), maps.width(), sc::kVisFitV, v.biasConst, v.biasSlope};
    return sc::visResidual(mapS, dataS, s, int(k), p, n) == 0.0f;
  }
};

TEST(Visibility, BiasAvoidsAcneAndKeepsContactShadows) {
  // 64 uniform directions, 1024^2 maps, the default bias (1 texel + 1.5 texels x tan theta). Acne: no
  // map may shadow an open pixel of the plane (farther than 0.8 from the sphere's axis: outside the
  // shadow the sphere (radius 0.3, centre 0.3 up) casts from 45 degrees or higher, whose far edge is
  // at 0.3 / tan + 0.3 / sin = 0.72) for a direction at least 45 degrees up, nor a sphere pixel for a
  // direction above the horizon and at least 25 degrees above its tangent plane (a convex surface
  // does not shadow itself there). Peter-panning: the plane right around the contact point (within
  // 0.22 of the axis, inside the disk the sphere shades from above) is shadowed from the direction
  // nearest straight up (64 uniform directions: about 10 degrees off; the disk moves 0.05).
  const shadetwin::Scene scene = sphereOnPlane();
  const MapTests T(scene);
  const shadetwin::VisibilitySetup& v = T.v;
  const shadetwin::GBuffer& g = T.g;
  const uint32_t maps = v.settings.maps;
  size_t openTests = 0, acne = 0, sphereTests = 0, selfShadow = 0, contact = 0, contactShadowed = 0;
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      const float* t = g.at(x, y);
      if (t[3] == 0.0f) continue;
      const shadetwin::shade::V3<float> p(t[0], t[1], t[2]);
      const float nl = std::sqrt(t[4] * t[4] + t[5] * t[5] + t[6] * t[6]);
      const shadetwin::shade::V3<float> n(t[4] / nl, t[5] / nl, t[6] / nl);
      const double r = std::hypot(double(t[0]), double(t[2]));
      const bool plane = std::fabs(t[1]) < 1e-4f && n.y > 0.999f;
      for (uint32_t k = 0; k < maps; ++k) {
        const Vec3& w = v.directions[k];
        const double c = n.x * w[0] + n.y * w[1] + n.z * w[2];
        const bool lit = T.lit(k, p, n);
        if (plane && r > 0.8 && c > std::sin(45 * std::numbers::pi / 180)) ++openTests, acne += !lit;
        if (!plane && w[1] > 0.0f && c > std::sin(25 * std::numbers::pi / 180)) ++sphereTests, selfShadow += !lit;
      }
      if (plane && r < 0.22) {
        ++contact;
        // The direction of the 64 nearest +y.
        size_t up = 0;
        for (size_t k = 1; k < v.directions.size(); ++k)
          if (v.directions[k][1] > v.directions[up][1]) up = k;
        contactShadowed += !T.lit(uint32_t(up), p, n);
      }
    }
  ASSERT_GT(openTests, 1000u);
  ASSERT_GT(sphereTests, 1000u);
  EXPECT_EQ(acne, 0u) << acne << " of " << openTests;
  EXPECT_EQ(selfShadow, 0u) << selfShadow << " of " << sphereTests;
  ASSERT_GT(contact, 0u);
  EXPECT_EQ(contactShadowed, contact);
}

TEST(Visibility, EmbreeShFitOfAnOpenPixelIsTheClampedCosineProjection) {
  // The per-pixel Embree fit (reference/reference.h, the SH-order baseline): for the open plane of the
  // sphere scene (no occluder above a pixel far from the sphere) it is the projection of max(0, n.w),
  // the prior t of the shared fit (pi Y00, 2 pi/3 Y1(n), pi/4 Y2(n), band 3 zero), up to the sphere's
  // remaining ~0.26 sr low above the horizon (c0 0.878 vs 0.886) and the quadrature of 4096 stratified
  // rays; near the sphere, c0 drops by more than 20%.
  const shadetwin::Scene scene = sphereOnPlane();
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(scene, dev());
  const std::vector<float> c = shadetwin::referenceVisibilitySh(scene, g.texels, g.width, g.height, 4096, true);
  const auto yUp = shadetwin::sh16BasisDouble({0, 1, 0});
  const double pi = std::numbers::pi;
  size_t open = 0, near = 0;
  double nearC0 = 0;
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      const float* t = g.at(x, y);
      if (t[3] == 0.0f || std::fabs(t[1]) > 1e-4f || t[5] < 0.999f) continue;  // the plane's top only
      const double r = std::hypot(double(t[0]), double(t[2]));
      const float* p = &c[(size_t(y) * g.width + x) * 16];
      if (r > 0.95 && open < 50) {
        ++open;
        for (int i = 0; i < 16; ++i) {
          const double band = i == 0 ? pi : i < 4 ? 2 * pi / 3 : i < 9 ? pi / 4 : 0.0;
          EXPECT_NEAR(p[i], band * yUp[size_t(i)], 0.03) << i;
        }
      }
      if (r < 0.35) ++near, nearC0 += p[0];
    }
  ASSERT_GT(open, 10u);
  ASSERT_GT(near, 10u);
  EXPECT_LT(nearC0 / double(near), 0.8 * pi * yUp[0]);
}

TEST(Visibility, ThinPlateAboveTheFloor) {
  // Thin geometry: a zero-thickness plate (0.6 x 0.6) 0.03 above the floor. Its top is lit for every
  // direction at least 20 degrees above it (the floor 0.03 below must not shadow it, nor the plate
  // itself), and the open floor 0.1 or more outside the plate's edge is lit for directions 60 degrees
  // up or higher (the plate's shadow reaches 0.017 beyond its edge there).
  const shadetwin::Scene scene = testScene(
      "thin_plate.json", R"([{"mesh": "plane", "scale": 1.0}, {"mesh": "plane", "scale": 0.3, "translate": [0, 0.03, 0]}])");
  const MapTests T(scene);
  const shadetwin::VisibilitySetup& v = T.v;
  const shadetwin::GBuffer& g = T.g;
  const uint32_t maps = v.settings.maps;
  size_t plateTests = 0, plateShadowed = 0, floorTests = 0, floorShadowed = 0;
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      const float* t = g.at(x, y);
      if (t[3] == 0.0f || t[5] < 0.999f) continue;
      const shadetwin::shade::V3<float> p(t[0], t[1], t[2]), n(0.0f, 1.0f, 0.0f);
      const bool plate = std::fabs(t[1] - 0.03f) < 1e-4f;
      const bool open = std::fabs(t[1]) < 1e-4f && std::max(std::fabs(t[0]), std::fabs(t[2])) > 0.4f;
      for (uint32_t k = 0; k < maps; ++k) {
        const float up = v.directions[k][1];
        const bool lit = T.lit(k, p, n);
        if (plate && up > std::sin(20 * std::numbers::pi / 180)) ++plateTests, plateShadowed += !lit;
        if (open && up > std::sin(60 * std::numbers::pi / 180)) ++floorTests, floorShadowed += !lit;
      }
    }
  ASSERT_GT(plateTests, 1000u);
  ASSERT_GT(floorTests, 1000u);
  EXPECT_EQ(plateShadowed, 0u) << plateShadowed << " of " << plateTests;
  EXPECT_EQ(floorShadowed, 0u) << floorShadowed << " of " << floorTests;
}

}  // namespace

TEST(Visibility, FramePassesReportTheirImagesBytes) {
  // visibilityEmu = the shadow maps, the fit and the filter of the stages run alone, and its stats
  // count the bytes of what it allocated: K maps of size^2 floats, their array copy, 16 floats per
  // pixel for the coefficients and again for the filter's output (none when the filter is off).
  shadetwin::Scene scene = bunny();
  scene.width = 96, scene.height = 64;
  std::ostringstream quiet;
  const shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(scene.environment, quiet);
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(scene, dev());
  for (const uint32_t radius : {0u, 2u}) {
    shadetwin::VisibilitySettings s;
    s.maps = 5;
    s.size = 128;
    s.filterRadius = radius;
    const auto v = shadetwin::visibilitySetup(scene, *env.texture, s);
    shadetwin::VisibilityStats st;
    const shadetwin::VisibilityImage img = shadetwin::visibilityEmu(scene, g, v, dev(), &st);
    const emu::Texture maps = shadetwin::shadowMapArray(shadetwin::shadowEmu(scene, v.directions, s.size, dev()));
    const shadetwin::VisibilityImage alone =
        shadetwin::visibilityFilterEmu(g, shadetwin::visibilityFitEmu(g, maps, v, dev()), v, dev());
    ASSERT_EQ(img.coeffs.size(), alone.coeffs.size());
    EXPECT_EQ(std::memcmp(img.coeffs.data(), alone.coeffs.data(), img.coeffs.size() * 4), 0) << radius;
    EXPECT_EQ(st.mapBytes, size_t(5) * 128 * 128 * 4);
    EXPECT_EQ(st.mapArrayBytes, size_t(5) * 128 * 128 * 4);
    EXPECT_EQ(st.coeffBytes, size_t(96) * 64 * 64);
    EXPECT_EQ(st.filteredBytes, radius ? size_t(96) * 64 * 64 : 0u);
    EXPECT_GT(st.shadowMs, 0.0);
    EXPECT_GT(st.fitMs, 0.0);
  }
}

TEST(Visibility, ConstantEnvironmentSpreadsDirectionsOverTheSphere) {
  // A constant environment: luminance x sin(theta) is uniform in solid angle, so the K directions
  // cover the sphere, about half of them below the horizon (they still count: V max(0, n.w) = 0
  // there for an upward normal), and the normal matrix has full rank once K >= 16.
  const shadetwin::Scene scene = bunny();
  std::vector<float> one(64 * 32 * 4, 1.0f);
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, 64, 32, one.data());
  for (uint32_t K : {16u, 64u, 256u}) {
    shadetwin::VisibilitySettings s;
    s.maps = K;
    s.size = 4096;
    const auto v = shadetwin::visibilitySetup(scene, env, s);
    EXPECT_FALSE(v.uniformFallback);
    EXPECT_EQ(v.rank, 16u) << K;
    size_t below = 0;
    double mean[3] = {0, 0, 0};
    for (const Vec3& d : v.directions) {
      below += d[1] < 0.0f;
      for (int k = 0; k < 3; ++k) mean[k] += double(d[size_t(k)]) / K;
    }
    EXPECT_GT(double(below), 0.3 * K) << K;
    EXPECT_LT(double(below), 0.7 * K) << K;
    for (double m : mean) EXPECT_LT(std::fabs(m), K >= 64 ? 0.1 : 0.25) << K;  // no preferred side
    // A pixel whose every direction is blocked: after the documented clamps the glossy visibility is
    // in [0, 1] for every direction and 0 along the normal, and the diffuse term under a constant
    // radiance 1 (L = 2 sqrt(pi) Y00, E = pi) is in [0, E] and near 0: no negative radiance from
    // the truncated series' ringing.
    namespace sc = shadetwin::shade::scalar;
    using F3 = shadetwin::shade::V3<float>;
    const F3 n(0, 1, 0);
    const sc::Sh16 c = fitPoint(v, uniformMaps(K, 16, 0.0f), {0, 0.2f, 0}, {0, 1, 0});
    for (float x : flat(c)) EXPECT_TRUE(std::isfinite(x)) << K;
    std::mt19937 rng(K);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    for (int i = 0; i < 500; ++i) {
      float w[3] = {U(rng), std::fabs(U(rng)) + 1e-3f, U(rng)};
      const float l = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      const float at = sc::visAt(sc::kFisVisCos, c, n, F3(w[0] / l, w[1] / l, w[2] / l));
      EXPECT_GE(at, 0.0f);
      EXPECT_LE(at, 1.0f);
    }
    EXPECT_EQ(sc::visAt(sc::kFisVisCos, c, n, n), 0.0f) << K;
    const float l00 = 2.0f * std::sqrt(float(std::numbers::pi)), E = float(std::numbers::pi);
    const sc::Sh16 L0{sc::Float4(l00, 0, 0, 0), sc::Float4(0.0f), sc::Float4(0.0f), sc::Float4(0.0f)};
    const F3 e = sc::visIrradiance(sc::kFisVisCos, sc::VisLighting{L0, L0, L0}, c, F3(E, E, E), n);
    EXPECT_GE(e.x, 0.0f) << K;
    EXPECT_LE(e.x, 0.1f * E) << K;
    for (float x : flat(fitPoint(v, uniformMaps(K, 16, 0.5f), {0, 0.2f, 0}, {0, 1, 0}))) EXPECT_TRUE(std::isfinite(x));
  }
}
