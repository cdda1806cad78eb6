// The glints lighting table (shade/glint_lighting.h, inputs/glint_lighting.*) on the emulator against
// the same sum in double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "emu/device_profile.h"
#include "inputs/glint_lighting.h"
#include "inputs/glint_tables.h"
#include "inputs/glints.h"
#include "inputs/sh_legendre.h"
#include "model/pass_counts.h"

namespace {
constexpr double kPi = std::numbers::pi;
}

TEST(GlintLighting, TableMatchesTheDoubleSumOverTheLevelsTexels) {
  // A 64 x 32 environment with a smooth part, negative texels and a one-texel sun of 30,000; 9 x 16
  // views, degree 20: every coefficient within 2e-5 of the double sum relative to the largest
  // coefficient of its view (float: h = wo + wi cancels where wi is nearly opposite wo, and a
  // degree-20 value moves ~20x its direction's error; measured 5e-6 at the sun), all finite; the
  // view grid's poles and seam are where they should be.
  const uint32_t W = 64, H = 32;
  std::vector<float> px(size_t(W) * H * 4);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      float* p = &px[4 * (size_t(y) * W + x)];
      p[0] = 0.5f + 0.4f * std::sin(float(x) * 0.3f), p[1] = 0.3f + 0.01f * float(y) - (x == 3 ? 0.5f : 0.0f);
      p[2] = (x == 20 && y == 8) ? 30000.0f : 0.2f, p[3] = 1.0f;
    }
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, W, H, px.data());
  shadetwin::GlintLightingSpec s;
  s.order = 20, s.rings = 9, s.sectors = 16;
  const shadetwin::GlintLightingTable t = shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), s);
  ASSERT_EQ(t.coeffs, 21u * 21u);
  const std::vector<float> vd = shadetwin::glintViewDirections(s);
  const emu::Texture dirs = shadetwin::glintEnvDirections(W, H);
  EXPECT_FLOAT_EQ(vd[1], 1.0f);                                  // view (0, 0): +y
  EXPECT_FLOAT_EQ(vd[(size_t(8) * 16) * 4 + 1], -1.0f);          // last ring: -y
  EXPECT_NEAR(vd[(size_t(4) * 16) * 4 + 2], 1.0, 1e-7);          // equator, u = 0: +z (the map's seam side)
  for (uint32_t v = 0; v < s.rings * s.sectors; ++v) {
    std::vector<double> acc(3 * size_t(t.coeffs), 0.0);
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        // The same float directions and solid angles the kernel reads (so the comparison measures
        // its arithmetic, not the inputs' rounding, which moves degree-20 values by ~20 ulps).
        const emu::Texel4 q = dirs.loadFloat(0, 0, x, y);
        const shadetwin::reference::D3 wi{q.r, q.g, q.b};
        const double dO = q.a;
        const shadetwin::reference::D3 h{vd[4 * v] + wi.x, vd[4 * v + 1] + wi.y, vd[4 * v + 2] + wi.z};
        const double len = std::sqrt(dot(h, h));
        if (len < 1e-6) continue;
        const std::vector<double> y2 = shadetwin::shRealDouble(s.order, h * (1.0 / len));
        for (uint32_t k = 0; k < t.coeffs; ++k)
          for (int c = 0; c < 3; ++c) acc[3 * k + size_t(c)] += double(px[4 * (size_t(y) * W + x) + size_t(c)]) * dO * y2[k];
      }
    double scale = 0;
    for (double a : acc) scale = std::max(scale, std::fabs(a));
    for (uint32_t k = 0; k < t.coeffs; ++k)
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(t.at(v, k)[c]));
        EXPECT_NEAR(t.at(v, k)[c], acc[3 * k + size_t(c)], 2e-5 * scale) << "view " << v << " coefficient " << k << " channel " << c;
      }
  }
  EXPECT_THROW(shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), shadetwin::GlintLightingSpec{65, 9, 16, 0}), std::invalid_argument);
  EXPECT_THROW(shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), shadetwin::GlintLightingSpec{8, 9, 16, 3}), std::invalid_argument);
}

TEST(GlintLighting, InputsNameTheMaterialWhoseMapCannotJoinTheArray) {
  // Every map of a scene goes into one texture array: a second size is an error naming the material;
  // the material rows carry the lobes' zonal factors, zero beyond each lobe's band limit.
  shadetwin::Scene scene;
  scene.technique = "glints";
  scene.glintOrder = 24, scene.glintViewRings = 3, scene.glintViewSectors = 4;
  shadetwin::Material a, b;
  a.name = "wide", b.name = "narrow";
  a.glints = b.glints = true;
  a.glintMap = "bumps", a.glintMapSize = 32, a.glintSigma = 0.3f;
  b.glintMap = "flakes", b.glintMapSize = 32, b.glintSigma = 0.1f;
  scene.materials = {a, b};
  std::vector<float> px(16 * 8 * 4, 1.0f);
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, 16, 8, px.data());
  const shadetwin::GlintInputs in = shadetwin::glintInputsEmu(scene, env, emu::lavapipeProfile());
  EXPECT_EQ(in.maps, 2u);
  EXPECT_EQ(in.order, std::min(24u, shadetwin::gaussianLobeBandLimit(0.1, 1e-6, 24)));
  const uint32_t limWide = shadetwin::gaussianLobeBandLimit(0.3, 1e-6, 24);
  ASSERT_LT(limWide, in.order);
  EXPECT_GT(in.materials->loadFloat(0, 0, 6 + limWide, 0).r, 0.0f);
  EXPECT_EQ(in.materials->loadFloat(0, 0, 6 + limWide + 1, 0).r, 0.0f);  // beyond the wide lobe's band limit
  EXPECT_GT(in.materials->loadFloat(0, 0, 6 + in.order, 1).r, 0.0f);
  scene.materials[1].glintMapSize = 64;
  try {
    shadetwin::glintInputsEmu(scene, env, emu::lavapipeProfile());
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("material 'narrow'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("64x64"), std::string::npos) << e.what();
  }
}

TEST(GlintLighting, BandsKeepEveryInvocationBelowTheDevicesLoopLimit) {
  // lavapipe's loop limiter (emu::DeviceProfile::loopIterationLimit = 65535): a band's estimated
  // back-edges stay below it, no limit means one band, and the banded table is the unbanded one up to
  // float reassociation (the bands' sums are added in order).
  EXPECT_EQ(emu::lavapipeProfile().loopIterationLimit, 65535u);
  EXPECT_EQ(shadetwin::glintBandRows(0, 1024, 512, 16), 0u);
  for (uint32_t w : {16u, 64u, 128u, 1024u})
    for (uint32_t order : {0u, 8u, 16u, 32u, 64u}) {
      const uint32_t rows = shadetwin::glintBandRows(65535, w, w / 2, order);
      ASSERT_GE(rows, 1u);
      ASSERT_LE(rows, w / 2);
      if (rows > 1) EXPECT_LE(uint64_t(rows) * w * (order + 8) + 6 * (order + 1) + 400, 65535u) << w << " " << order;
    }
  EXPECT_EQ(shadetwin::glintBandRows(65535, 64, 32, 16), 32u);  // the scenes' default: one band
  const uint32_t W = 32, H = 16;
  std::vector<float> px(size_t(W) * H * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = (i % 4 == 3) ? 1.0f : float(1 + (i * 37) % 11);
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, W, H, px.data());
  shadetwin::GlintLightingSpec one{10, 5, 8, 0, 0}, banded{10, 5, 8, 0, 3};
  const auto a = shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), one);
  const auto b = shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), banded);
  const auto c = shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), banded);
  size_t same = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    EXPECT_NEAR(a.rgba[i], b.rgba[i], 1e-4f * (1.0f + std::fabs(a.rgba[i])));
    same += std::memcmp(&a.rgba[i], &b.rgba[i], 4) == 0;
    ASSERT_EQ(std::memcmp(&b.rgba[i], &c.rgba[i], 4), 0);  // deterministic
  }
  EXPECT_LT(same, a.rgba.size());  // the bands reassociate the sums: not the same bits
  emu::DeviceProfile p = emu::lavapipeProfile();
  emu::setProfileField(p, "loopIterationLimit", "1000");
  EXPECT_EQ(p.loopIterationLimit, 1000u);
}

TEST(GlintLighting, LightBandLimitIsTheLastBandWhoseRelativeAmplitudeReachesEpsilon) {
  // A hand-made degree-6 table of three views: rho_l = sqrt(2l + 1) |Lambda_l| / |Lambda_00| per
  // channel, the limit the largest l with rho_l >= eps in any channel; a black view has limit 0.
  shadetwin::GlintLightingTable t;
  t.spec.order = 6, t.spec.rings = 3, t.spec.sectors = 1, t.coeffs = 49;
  t.rgba.assign(size_t(3) * 49 * 4, 0.0f);
  auto set = [&](uint32_t v, uint32_t i, int c, float x) { t.rgba[(size_t(v) * 49 + i) * 4 + size_t(c)] = x; };
  // View 0: red band 3 at rho 2e-6 (one coefficient, 2e-6 / sqrt(7) of Lambda_00 = 2), band 5 at
  // rho 0.5e-6: limit 3 at 1e-6, 5 at 1e-7, 0 at 1e-5.
  set(0, 0, 0, 2.0f);
  set(0, 9 + 3 + 1, 0, float(2.0 * 2e-6 / std::sqrt(7.0)));
  set(0, 25 + 5 - 2, 0, float(2.0 * 0.5e-6 / std::sqrt(11.0)));
  // View 1: red has band 2 at rho 0.22, blue band 6 at rho 3.6e-3 (the channel reaching eps decides).
  set(1, 0, 0, 1.0f), set(1, 4, 0, 0.1f), set(1, 0, 2, 1.0f), set(1, 36 + 6, 2, 1e-3f);
  // View 2: black.
  std::vector<uint32_t> lim = shadetwin::glintLightBandLimits(t, 1e-6);
  EXPECT_EQ(lim, (std::vector<uint32_t>{3, 6, 0}));
  EXPECT_EQ(shadetwin::glintLightBandLimits(t, 1e-7)[0], 5u);
  EXPECT_EQ(shadetwin::glintLightBandLimits(t, 1e-5)[0], 0u);
  EXPECT_EQ(shadetwin::glintLightBandLimits(t, 0.5)[1], 0u);   // red rho_2 = sqrt(5) 0.1 = 0.22, blue rho_6 = 3.6e-3
  EXPECT_EQ(shadetwin::glintLightBandLimits(t, 0.05)[1], 2u);
}

TEST(GlintLighting, HalfVectorLightingOfAConstantSkyIsNotBandLimited) {
  // Measured (docs/RESULTS.md, Glints): Lambda(wh; wo) = L(wi) 4 (wo.wh) [wo.wh > 0] has a kink where
  // wh leaves wo's hemisphere, so even a constant environment's half-vector lighting keeps rho_l far
  // above 1e-6 (about 0.05 at l = 16): M_light is the table's degree at every view, and the adaptive
  // band limit is decided by the lobes (M_NDF).
  std::vector<float> px(size_t(64) * 32 * 4, 1.0f);
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, 64, 32, px.data());
  shadetwin::GlintLightingSpec s;
  s.order = 12, s.rings = 5, s.sectors = 8;
  const shadetwin::GlintLightingTable t = shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), s);
  for (uint32_t lim : shadetwin::glintLightBandLimits(t, 1e-6)) EXPECT_EQ(lim, 12u);
  for (uint32_t lim : shadetwin::glintLightBandLimits(t, 1e-2)) EXPECT_GE(lim, 8u);
}

TEST(GlintLighting, CountedRunCountsEveryPrivateArrayAccessOfTheKernel) {
  // The kernel keeps its column and the recurrence's entries in local arrays read and written at loop-variable indices
  // (arrayGet / arraySet: what lavapipe runs as a load per lane and a masked store per lane). Per 8-lane vector of views
  // of column m, per band of T texels: the column's 390 zeroes, m seed factors and 2 (O - m) entries written, then per
  // texel m + 2 (O - m) entries and 6 (O - m + 1) column values read and those 6 (O - m + 1) written. The counted
  // table keeps the emulator's bits.
  const uint32_t W = 12, H = 7;
  std::vector<float> px(size_t(W) * H * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = (i % 4 == 3) ? 1.0f : float(1 + (i * 29) % 13) * 0.25f;
  const emu::Texture env = emu::floatTexture(emu::Format::RGBA32F, W, H, px.data());
  for (uint32_t order : {0u, 3u, 7u})
    for (uint32_t bandRows : {0u, 3u})
      for (uint32_t sectors : {5u, 9u}) {
        const shadetwin::GlintLightingSpec spec{order, 2, sectors, 0, bandRows};
        shadetwin::GlintLightingTable counted;
        const auto ticks = shadetwin::model::countedTicks(
            [&] { counted = shadetwin::glintLightingCounted(env, emu::lavapipeProfile(), spec); });
        const uint64_t vectors = (2 * sectors + 7) / 8;
        uint64_t reads = 0, writes = 0;
        for (uint32_t y0 = 0; y0 < H; y0 += bandRows ? bandRows : H) {
          const uint64_t texels = uint64_t(W) * (std::min(H, y0 + (bandRows ? bandRows : H)) - y0);
          for (uint64_t m = 0; m <= order; ++m) {
            const uint64_t col = 6 * (order - m + 1), entries = m + 2 * (order - m);
            reads += vectors * texels * (entries + col);
            writes += vectors * (390 + entries + texels * col);
          }
        }
        EXPECT_EQ(ticks[opcount::kPrivRead], reads) << order << " " << bandRows << " " << sectors;
        EXPECT_EQ(ticks[opcount::kPrivWrite], writes) << order << " " << bandRows << " " << sectors;
        const auto emu = shadetwin::glintLightingEmu(env, emu::lavapipeProfile(), spec);
        ASSERT_EQ(counted.rgba.size(), emu.rgba.size());
        EXPECT_EQ(std::memcmp(counted.rgba.data(), emu.rgba.data(), emu.rgba.size() * 4), 0);
      }
}
