// Pieces of the glints technique (shade/glints.h): footprints and the FG term.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lanes/instantiate.h"

namespace sc = shadetwin::shade::scalar;

TEST(Glints, FootprintIsTheConservativeBoxOfThePixelsParallelogram) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(-2.0f, 3.0f), D(-0.004f, 0.004f);
  for (int i = 0; i < 20000; ++i) {
    const float u = U(rng), v = U(rng), texels = i % 2 ? 1024.0f : 256.0f * 3.0f;  // map size x tiling scale
    const sc::Float4 duv(D(rng), D(rng), D(rng), D(rng));
    const sc::GlintBox b = sc::glintFootprint(u, v, duv, texels);
    if (b.cut) continue;
    // Every corner of the parallelogram uv +- duv/dx / 2 +- duv/dy / 2 lies in a texel of the box.
    for (float a : {-0.5f, 0.5f})
      for (float c : {-0.5f, 0.5f}) {
        const double pu = (double(u) + a * duv.x + c * duv.z) * texels, pv = (double(v) + a * duv.y + c * duv.w) * texels;
        EXPECT_LE(b.x0, int(std::floor(pu)) + (std::fabs(pu - std::round(pu)) < 1e-3 ? 1 : 0));
        EXPECT_GE(b.x1, int(std::floor(pu)) - (std::fabs(pu - std::round(pu)) < 1e-3 ? 1 : 0));
        EXPECT_LE(b.y0, int(std::floor(pv)) + (std::fabs(pv - std::round(pv)) < 1e-3 ? 1 : 0));
        EXPECT_GE(b.y1, int(std::floor(pv)) - (std::fabs(pv - std::round(pv)) < 1e-3 ? 1 : 0));
      }
    // ... and the box is no larger than the parallelogram's box, rounded out to texels.
    const double hu = 0.5 * (std::fabs(duv.x) + std::fabs(duv.z)) * texels, hv = 0.5 * (std::fabs(duv.y) + std::fabs(duv.w)) * texels;
    EXPECT_LE(b.x1 - b.x0, int(std::ceil(2 * hu)) + 1);
    EXPECT_LE(b.y1 - b.y0, int(std::ceil(2 * hv)) + 1);
  }
  // No derivative: the texel under uv, across the tile seam too (coordinates are not wrapped).
  const sc::GlintBox one = sc::glintFootprint(-0.001f, 1.25f, sc::Float4(0.0f), 1024.0f);
  EXPECT_EQ(one.x0, -2);
  EXPECT_EQ(one.x1, -2);
  EXPECT_EQ(one.y0, 1280);
  EXPECT_EQ(one.y1, 1280);
  EXPECT_FALSE(one.cut);
  // A footprint longer than 255 texels along u: that axis cut to the 255 texels around the centre.
  const sc::GlintBox big = sc::glintFootprint(0.5f, 0.5f, sc::Float4(0.5f, 0.001f, 0.0f, 0.001f), 1024.0f);
  EXPECT_TRUE(big.cut);
  EXPECT_EQ(big.x1 - big.x0, 254);
  EXPECT_EQ(big.x0, 512 - 127);
  EXPECT_LE(big.y1 - big.y0, 3);
  EXPECT_LT((big.x1 - big.x0 + 1) * (big.y1 - big.y0 + 1), 65536);
}

namespace {
double fresnelDouble(double c, double n, double k) {
  const double c2 = c * c, s2 = 1 - c2, t0 = n * n - k * k - s2, a2b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k);
  const double a = std::sqrt(0.5 * (a2b2 + t0)), t1 = a2b2 + c2, t2 = 2 * a * c, rs = (t1 - t2) / (t1 + t2);
  const double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2, rp = rs * (t3 - t4) / (t3 + t4);
  return 0.5 * (rs + rp);
}
}  // namespace

TEST(Glints, ConductorFresnelMatchesDoubleAndItsLimits) {
  // Gold, copper, aluminium (n, k at 650 / 550 / 450 nm, approximately), and a dielectric-like k = 0.
  const float metals[][6] = {{0.143f, 0.374f, 1.442f, 3.983f, 2.385f, 1.603f},
                             {0.200f, 0.924f, 1.102f, 3.912f, 2.452f, 2.142f},
                             {1.657f, 0.880f, 0.521f, 9.224f, 6.270f, 4.837f},
                             {1.5f, 1.5f, 1.5f, 0.0f, 0.0f, 0.0f}};
  double worst = 0;
  for (const auto& m : metals)
    for (int i = 0; i <= 2000; ++i) {
      const float c = float(i) / 2000.0f;
      const sc::Float3 f = sc::fresnelConductor(c, sc::Float3(m[0], m[1], m[2]), sc::Float3(m[3], m[4], m[5]));
      const float fc[3] = {f.x, f.y, f.z};
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_TRUE(std::isfinite(fc[ch]));
        worst = std::max(worst, std::fabs(fc[ch] - fresnelDouble(c, m[ch], m[3 + ch])));
      }
    }
  EXPECT_LT(worst, 2e-6);
  for (const auto& m : metals) {
    const double n = m[0], k = m[3];
    EXPECT_NEAR(sc::fresnelConductor1(1.0f, m[0], m[3]), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-6);
    EXPECT_NEAR(sc::fresnelConductor1(0.0f, m[0], m[3]), 1.0, 1e-6);  // grazing
  }
}

TEST(Glints, SmithG1RationalApproximationFollowsTheExactBeckmannMasking) {
  // Exact Beckmann Smith G1 = 2 / (1 + erf(a) + exp(-a^2) / (a sqrt(pi))), a = cot / alpha.
  double worst = 0;
  for (float alpha : {0.02f, 0.1f, 0.3f, 0.7f})
    for (int i = 1; i <= 4000; ++i) {
      const float c = float(i) / 4000.0f;
      const double s = std::sqrt(1.0 - double(c) * c), a = c / (alpha * std::max(s, 1e-30));
      const double exact = a > 30 ? 1.0 : 2.0 / (1.0 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(std::numbers::pi)));
      const float g = sc::smithG1Beckmann(c, alpha);
      ASSERT_GE(g, 0.0f);
      ASSERT_LE(g, 1.0f + 1e-6f);
      worst = std::max(worst, std::fabs(double(g) - exact));
    }
  EXPECT_LT(worst, 4e-3);  // Walter et al.: the rational form is within a few thousandths
  EXPECT_GT(worst, 1e-4);  // it is an approximation, not the exact function
  EXPECT_EQ(sc::smithG1Beckmann(0.0f, 0.2f), 0.0f);
  EXPECT_EQ(sc::smithG1Beckmann(-0.3f, 0.2f), 0.0f);
  EXPECT_EQ(sc::smithG1Beckmann(1.0f, 0.2f), 1.0f);
}
