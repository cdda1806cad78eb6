// The glints ground truth (reference/glints_gxd.*): its NDF sum with pruning and wrap-around, and
// its Monte Carlo estimate against deterministic quadratures of the same integral.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "reference/glints_gxd.h"

using shadetwin::GlintPixel;
using shadetwin::reference::D3;

namespace {

constexpr double kPi = std::numbers::pi;

shadetwin::NormalMap gen(shadetwin::NormalMapKind k, uint32_t size, uint32_t seed, float spread) {
  shadetwin::NormalMapSpec s;
  s.kind = k, s.size = size, s.seed = seed, s.spread = spread, s.cells = std::max(1u, size / 8);
  return shadetwin::generateNormalMap(s);
}

struct Env {
  std::vector<float> rgba;
  shadetwin::EnvImage img;
  std::unique_ptr<shadetwin::reference::Environment> env;
  Env(uint32_t w, uint32_t h, float value) : rgba(size_t(w) * h * 4, value) {
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 1.0f;
    img = {w, h, rgba.data()};
  }
  const shadetwin::reference::Environment& get() {
    if (!env) env = std::make_unique<shadetwin::reference::Environment>(img, 1.0);
    return *env;
  }
};

double fresnel(double c, double n, double k) {
  const double c2 = c * c, s2 = 1 - c2, t0 = n * n - k * k - s2, a2b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k);
  const double a = std::sqrt(0.5 * (a2b2 + t0)), t1 = a2b2 + c2, t2 = 2 * a * c, rs = (t1 - t2) / (t1 + t2);
  const double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
  return 0.5 * (rs + rs * (t3 - t4) / (t3 + t4));
}
double g1(double c, double alpha) {
  if (c <= 0) return 0;
  const double a = c / (alpha * std::sqrt(1 - c * c));
  return a > 30 ? 1.0 : 2.0 / (1.0 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(kPi)));
}

// The estimator's integral by quadrature over h in the frame of the lobe's axis `axis` (world):
// L_o = integral L(wi) F(wi.h) G1(wo) G1(wi) D_P(h) (wo.h) / cos_o dh over h with wo.h > 0, wi.n > 0.
double quadrature(const GlintPixel& px, const shadetwin::reference::Environment& env, D3 axis, int channel) {
  const D3 helper = std::fabs(axis.x) < 0.9 ? D3{1, 0, 0} : D3{0, 1, 0};
  const D3 e1 = normalize(cross(helper, axis)), e2 = cross(axis, e1);
  const double cosO = dot(px.wo, px.n), alpha = std::sqrt(2.0) * px.sigma, tmax = std::min(kPi, 9 * px.sigma);
  const int nt = 1500, np = 720;
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    const double th = (i + 0.5) * tmax / nt, dth = tmax / nt;
    for (int j = 0; j < np; ++j) {
      const double ph = (j + 0.5) * 2 * kPi / np;
      const D3 h = e1 * (std::sin(th) * std::cos(ph)) + e2 * (std::sin(th) * std::sin(ph)) + axis * std::cos(th);
      const double oh = dot(px.wo, h);
      if (oh <= 0) continue;
      const D3 wi = h * (2 * oh) - px.wo;
      const double ci = dot(wi, px.n);
      if (ci <= 0) continue;
      double L[3];
      env.radiance(wi, L);
      const double D = shadetwin::glintFootprintNdf(px, h);
      const double fg = fresnel(dot(wi, h), px.eta[channel], px.k[channel]) * g1(cosO, alpha) * g1(ci, alpha);
      sum += L[channel] * fg * D * oh / cosO * std::sin(th) * dth * (2 * kPi / np);
    }
  }
  return sum;
}

}  // namespace

TEST(GlintsGxd, PruningAndWrapAroundLeaveTheNdfUnchanged) {
  const shadetwin::NormalMap m = gen(shadetwin::NormalMapKind::Flakes, 100, 7, 0.2f);
  const shadetwin::NormalBounds nb = shadetwin::normalBounds(m);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  uint64_t withLobes = 0, withoutLobes = 0;
  for (int i = 0; i < 300; ++i) {
    GlintPixel px;
    px.map = &m;
    px.sigma = i % 2 ? 0.02 : 0.1;
    px.x0 = int64_t(U(rng) * 300), px.y0 = int64_t(U(rng) * 300);
    px.x1 = px.x0 + (i % 3 == 0 ? 0 : int64_t(40 + 100 * (U(rng) + 1))), px.y1 = px.y0 + int64_t(30 + 80 * (U(rng) + 1));
    const D3 h = normalize(D3{0.8 * U(rng), 0.8 * U(rng), 1.0});
    uint64_t a = 0, b = 0;
    const double plain = shadetwin::glintFootprintNdf(px, h, &a);
    px.bounds = &nb;
    const double pruned = shadetwin::glintFootprintNdf(px, h, &b);
    if (i % 2) withoutLobes += a, withLobes += b;  // narrow lobes: most blocks are out of reach
    const double texels = double(px.x1 - px.x0 + 1) * double(px.y1 - px.y0 + 1);
    EXPECT_NEAR(pruned, plain, 1e-12 * plain + std::exp(-40.0) / shadetwin::glintLobeNorm(px.sigma) + 0 * texels) << i;
    // A whole period further along either axis: the same footprint of the tiled map.
    GlintPixel moved = px;
    moved.x0 += 100, moved.x1 += 100, moved.y0 -= 200, moved.y1 -= 200;
    EXPECT_NEAR(shadetwin::glintFootprintNdf(moved, h), pruned, 1e-12 * pruned) << i;
  }
  EXPECT_LT(withLobes, withoutLobes / 2);  // the hierarchy skips most texels
  RecordProperty("visited_fraction", std::to_string(double(withLobes) / double(withoutLobes)));
  // Exactly 3 x 2 periods: the whole map's NDF.
  GlintPixel all;
  all.map = &m, all.bounds = &nb, all.sigma = 0.1, all.x0 = -37, all.y0 = 5, all.x1 = -37 + 299, all.y1 = 5 + 199;
  GlintPixel one = all;
  one.x0 = 0, one.y0 = 0, one.x1 = 99, one.y1 = 99;
  const D3 h = normalize(D3{0.1, -0.05, 1.0});
  EXPECT_NEAR(shadetwin::glintFootprintNdf(all, h), shadetwin::glintFootprintNdf(one, h), 1e-12);
}

TEST(GlintsGxd, MonteCarloMatchesQuadratureOnAFlatMapAndOnAFlake) {
  // A flat map (the smooth Gaussian microfacet) under a uniform environment of radiance 1, at three
  // view angles; and one tilted flake under an environment with a bright region (a 32 x 16 map
  // with a 100x texel block). The estimate lies within 4 standard errors (plus 0.3% for the
  // quadrature) of the quadrature of the same integral.
  const shadetwin::NormalMap flat = gen(shadetwin::NormalMapKind::Flat, 8, 1, 0.0f);
  Env uniform(16, 8, 1.0f);
  for (double viewDeg : {0.0, 40.0, 70.0}) {
    GlintPixel px;
    px.map = &flat;
    px.x0 = 0, px.y0 = 0, px.x1 = 1, px.y1 = 2;  // 6 texels of the flat map
    px.sigma = 0.1;
    const double v = viewDeg * kPi / 180;
    px.wo = D3{std::sin(v), 0, std::cos(v)};
    // The environment's frame: y up; the surface's normal along +z of the environment is fine for
    // a uniform environment.
    const shadetwin::GxdResult r = shadetwin::glintGxd(px, uniform.get(), 4000, 5);
    for (int c = 0; c < 3; ++c) {
      const double q = quadrature(px, uniform.get(), px.n, c);
      EXPECT_NEAR(r.rgb[c], q, 4 * r.stdErr[c] + 3e-3 * q) << viewDeg << " " << c;
      EXPECT_LT(r.stdErr[c], 0.02 * q) << viewDeg;
    }
  }
  // One flake tilted 0.25 rad about x, footprint one texel, narrow lobe, light from a bright block.
  shadetwin::NormalMap flake;
  flake.width = flake.height = 1;
  flake.n = {0.0f, float(-std::sin(0.25)), float(std::cos(0.25))};
  Env spot(32, 16, 0.2f);
  for (int y = 3; y < 6; ++y)
    for (int x = 12; x < 20; ++x)
      for (int c = 0; c < 3; ++c) spot.rgba[4 * (size_t(y) * 32 + x) + size_t(c)] = 20.0f;
  GlintPixel px;
  px.map = &flake;
  px.sigma = 0.08;
  px.t = D3{1, 0, 0}, px.b = D3{0, 0, 1}, px.n = D3{0, 1, 0};  // surface facing +y (the environment's up)
  px.wo = normalize(D3{0.0, 1.0, 0.6});
  const D3 axis = normalize(px.t * double(flake.n[0]) + px.b * double(flake.n[1]) + px.n * double(flake.n[2]));
  const shadetwin::GxdResult r = shadetwin::glintGxd(px, spot.get(), 20000, 9);
  for (int c = 0; c < 3; ++c) {
    const double q = quadrature(px, spot.get(), axis, c);
    EXPECT_NEAR(r.rgb[c], q, 4 * r.stdErr[c] + 3e-3 * q) << c;
    EXPECT_GT(q, 0.0);
  }
  // F G outside the integral (the technique's model) differs, but only by the FG approximation.
  GlintPixel out = px;
  out.fgOutside = true;
  const shadetwin::GxdResult ro = shadetwin::glintGxd(out, spot.get(), 20000, 9);
  EXPECT_NE(ro.rgb[0], r.rgb[0]);
  EXPECT_NEAR(ro.rgb[0], r.rgb[0], 0.2 * r.rgb[0]);
}
