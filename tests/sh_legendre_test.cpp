// High-order real SH (shade/sh_legendre.h, inputs/sh_legendre.*): the float recurrences against
// double to degree 300, the double ones against the standard library, orthonormality, agreement with
// sh16, what a flushing stage does, and the Gaussian lobe's zonal coefficients against quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "emu/device_profile.h"
#include "emu/fpenv.h"
#include "inputs/sh_legendre.h"
#include "lanes/instantiate.h"
#include "passes/shade.h"

namespace sc = shadetwin::shade::scalar;
using F3 = shadetwin::shade::V3<float>;

namespace {

constexpr double kPi = std::numbers::pi;

const emu::Texture& coefTexture() {
  static const emu::Texture t = shadetwin::shLegendreCoefficients(300);
  return t;
}
const shadetwin::shade::Sampler2D& coef() {
  static const shadetwin::shade::Sampler2D s = shadetwin::environmentSampler(coefTexture(), emu::lavapipeProfile(), false);
  return s;
}

// Pbar_l^m(cos theta) of the float recurrences, index l (l + 1) / 2 + m.
std::vector<float> legendreFloat(uint32_t L, float z, float sinT) {
  std::vector<float> out(size_t(L + 1) * (L + 2) / 2);
  sc::ShLeg seed = sc::shLegSeed0();
  for (int m = 0; m <= int(L); ++m) {
    if (m > 0) seed = sc::shLegSeedNext(seed, coef(), m, sinT);
    sc::ShLeg s = seed;
    out[size_t(m) * (m + 1) / 2 + m] = sc::shLegValue(s);
    for (int l = m + 1; l <= int(L); ++l) {
      s = sc::shLegNext(s, coef(), l, m, z);
      out[size_t(l) * (l + 1) / 2 + m] = sc::shLegValue(s);
    }
  }
  return out;
}

// Every real Y_l^m of degree <= L at d, in sh16 order (band l: m = -l .. l).
std::vector<float> shFloat(uint32_t L, F3 d) {
  const sc::ShPolar pol = sc::shPolar(d);
  const std::vector<float> P = legendreFloat(L, pol.z, pol.sinT);
  std::vector<float> y(size_t(L + 1) * (L + 1));
  sc::ShAzimuth a{1.0f, 0.0f};
  for (int m = 0; m <= int(L); ++m) {
    if (m > 0) a = sc::shAzimuthNext(a, pol.cosP, pol.sinP);
    for (int l = m; l <= int(L); ++l) {
      const float p = P[size_t(l) * (l + 1) / 2 + m];
      if (m == 0) y[size_t(l) * l + l] = p;
      else {
        y[size_t(l) * l + l + m] = 1.41421356f * p * a.c;
        y[size_t(l) * l + l - m] = 1.41421356f * p * a.s;
      }
    }
  }
  return y;
}

}  // namespace

TEST(ShLegendre, FloatRecurrencesMatchDoubleToDegree300AtEveryAngle) {
  // Every value finite. The error, relative to the degree's scale sqrt((2l + 1) / 4 pi) (the size of
  // Pbar_l^0 at the pole): below 2e-5 to degree 60 (the orders glints run) and below 3e-4 to 300,
  // including next to the poles where the seeds are far below float's range. Near the poles the
  // error grows like l^2 eps (the recurrence's two solutions merge at z = 1); so does the values'
  // sensitivity to z itself: moving z by one float ulp changes them by more than 3x the error, so the
  // float recurrence is as accurate as a float input allows.
  const double thetas[] = {0.0, 1e-7, 1e-4, 1e-3, 0.01, 0.1, 0.4, 1.0, kPi / 2, 2.0, 3.0, kPi - 1e-3, kPi - 1e-6, kPi};
  double worst60 = 0, worst = 0, sensitivity = 0;
  size_t tinyButNonzero = 0;
  for (double th : thetas) {
    const float z = float(std::cos(th)), s = float(std::sin(th));
    const std::vector<float> f = legendreFloat(300, z, s);
    // The reference from the same z and sin(theta) (a reference at the angle itself would measure
    // the inputs' rounding).
    const std::vector<double> d = shadetwin::shLegendreDouble(300, double(z), double(s));
    const float zn = std::nextafter(z, 0.0f);
    const std::vector<double> dn = shadetwin::shLegendreDouble(300, double(zn), std::sqrt(std::max(0.0, 1.0 - double(zn) * zn)));
    double worstHere = 0, moveHere = 0;
    for (uint32_t l = 0; l <= 300; ++l)
      for (uint32_t m = 0; m <= l; ++m) {
        const size_t i = size_t(l) * (l + 1) / 2 + m;
        const float v = f[i];
        ASSERT_TRUE(std::isfinite(v)) << l << " " << m << " " << th;
        const double scale = std::sqrt((2.0 * l + 1) / (4 * kPi)), e = std::fabs(double(v) - d[i]) / scale;
        worstHere = std::max(worstHere, e);
        if (l <= 60) worst60 = std::max(worst60, e);
        if (m == 0) moveHere = std::max(moveHere, std::fabs(dn[i] - d[i]) / scale);
        tinyButNonzero += v != 0.0f && std::fabs(v) < 1e-30f;
      }
    worst = std::max(worst, worstHere);
    if (std::fabs(z) > 0.99f) {
      EXPECT_GT(moveHere, 3.0 * worstHere) << th;
      sensitivity = std::max(sensitivity, moveHere);
    }
  }
  EXPECT_LT(worst60, 2e-5);
  EXPECT_LT(worst, 3e-4);
  EXPECT_GT(tinyButNonzero, 0u);  // values far below 2^-32 survive (the scaled seeds)
  RecordProperty("worst60", std::to_string(worst60));
  RecordProperty("worst300", std::to_string(worst));
}

TEST(ShLegendre, DoubleRecurrencesMatchTheStandardLibrary) {
  // std::sph_legendre(l, m, theta) = (-1)^m Pbar_l^m (it carries the Condon-Shortley phase), l < 128.
  for (double th : {0.05, 0.3, 1.0, 1.5, 2.5, 3.1}) {
    const std::vector<double> d = shadetwin::shLegendreDouble(127, th);
    for (uint32_t l = 0; l <= 127; ++l)
      for (uint32_t m = 0; m <= l; ++m) {
        const double ref = ((m & 1) ? -1.0 : 1.0) * std::sph_legendre(l, m, th);
        const double v = d[size_t(l) * (l + 1) / 2 + m];
        if (std::fabs(ref) < 1e-250) continue;
        EXPECT_NEAR(v, ref, 1e-10 * std::sqrt((2.0 * l + 1) / (4 * kPi))) << l << " " << m << " " << th;
      }
  }
}

TEST(ShLegendre, RealShAreOrthonormalAndExtendSh16) {
  // Degree <= 12 on a product grid (Gauss-Legendre in z, uniform in phi: exact for these degrees).
  const uint32_t L = 12, nz = 32, nphi = 64;
  std::vector<double> zs(nz), ws(nz);
  for (uint32_t i = 0; i < nz; ++i) {  // Gauss-Legendre nodes by Newton on P_nz
    double x = std::cos(kPi * (i + 0.75) / (nz + 0.5));
    for (int it = 0; it < 50; ++it) {
      double p0 = 1, p1 = x;
      for (uint32_t k = 2; k <= nz; ++k) std::tie(p0, p1) = std::pair{p1, ((2.0 * k - 1) * x * p1 - (k - 1.0) * p0) / k};
      const double dp = nz * (x * p1 - p0) / (x * x - 1);
      x -= p1 / dp;
      if (it == 49) ws[i] = 2 / ((1 - x * x) * dp * dp);
    }
    zs[i] = x;
  }
  const size_t n = size_t(L + 1) * (L + 1);
  std::vector<double> gram(n * n, 0.0);
  for (uint32_t i = 0; i < nz; ++i)
    for (uint32_t j = 0; j < nphi; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / nphi, s = std::sqrt(1 - zs[i] * zs[i]);
      const std::vector<float> y = shFloat(L, F3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(zs[i])));
      const double w = ws[i] * 2 * kPi / nphi;
      for (size_t a = 0; a < n; ++a)
        for (size_t b = 0; b < n; ++b) gram[a * n + b] += w * double(y[a]) * y[b];
    }
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b) EXPECT_NEAR(gram[a * n + b], a == b ? 1.0 : 0.0, 2e-6) << a << " " << b;
  // Bands 0-3 are sh16's functions in sh16's order.
  for (const F3 d : {F3(0.0f, 0.0f, 1.0f), F3(0.6f, 0.0f, 0.8f), F3(0.36f, -0.48f, 0.8f), F3(-0.2f, 0.9f, -0.3873f)}) {
    const std::vector<float> y = shFloat(3, d);
    const sc::Sh16 b = sc::sh16Basis(d);
    const float ref[16] = {b.a.x, b.a.y, b.a.z, b.a.w, b.b.x, b.b.y, b.b.z, b.b.w, b.c.x, b.c.y, b.c.z, b.c.w, b.d.x, b.d.y, b.d.z, b.d.w};
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(y[size_t(i)], ref[i], 2e-6) << i;
  }
}

TEST(ShLegendre, AFlushingStageReturnsZeroWhereTheValueIsDenormal) {
  // Near the pole the high-order values fall below 2^-126: a preserving stage returns them as
  // denormals, a flushing one (FTZ/DAZ, the profile's fragment or compute stage) as 0; every value
  // at or above 2^-126 is the same in both; none is NaN or infinite.
  const float z = float(std::cos(0.02)), s = float(std::sin(0.02));
  std::vector<float> keep, flush;
  {
    emu::DenormalScope d(false);
    keep = legendreFloat(300, z, s);
  }
  {
    emu::DenormalScope d(true);
    flush = legendreFloat(300, z, s);
  }
  size_t denormal = 0;
  for (size_t i = 0; i < keep.size(); ++i) {
    ASSERT_TRUE(std::isfinite(flush[i]));
    if (std::fabs(keep[i]) < 1.17549435e-38f && keep[i] != 0.0f) {
      ++denormal;
      EXPECT_EQ(flush[i], 0.0f) << i;
    } else {
      EXPECT_EQ(keep[i], flush[i]) << i;
    }
  }
  EXPECT_GT(denormal, 0u);
}

TEST(ShLegendre, GaussianLobeZonalCoefficientsMatchQuadrature) {
  // z_l = integral g Y_l^0 by composite Gauss-Legendre in theta (panels graded towards the lobe's
  // peak), against the Bessel-ratio recurrence.
  for (double sigma : {0.02, 0.05, 0.1, 0.3, 1.0, 3.0}) {
    const uint32_t L = 80;
    const std::vector<double> z = shadetwin::gaussianLobeZh(sigma, L);
    const double lam = 1 / (sigma * sigma), N = 2 * kPi * (1 - std::exp(-2 * lam)) / lam;
    std::vector<double> q(L + 1, 0.0);
    const double gx[5] = {-0.906179845938664, -0.538469310105683, 0.0, 0.538469310105683, 0.906179845938664};
    const double gw[5] = {0.236926885056189, 0.478628670499366, 0.568888888888889, 0.478628670499366, 0.236926885056189};
    const int panels = 4000;
    for (int p = 0; p < panels; ++p) {
      // theta = pi u^3: fine panels near theta = 0
      for (int k = 0; k < 5; ++k) {
        const double u = (p + 0.5 + 0.5 * gx[k]) / panels, th = kPi * u * u * u, dth = 3 * kPi * u * u / panels;
        const double t = std::cos(th), w = gw[k] * 0.5 * dth * 2 * kPi * std::sin(th) * std::exp(lam * (t - 1)) / N;
        double p0 = 1, p1 = t;
        for (uint32_t l = 0; l <= L; ++l) {
          const double P = l == 0 ? 1.0 : p1;
          q[l] += w * std::sqrt((2.0 * l + 1) / (4 * kPi)) * P;
          if (l >= 1) std::tie(p0, p1) = std::pair{p1, ((2.0 * l + 1) * t * p1 - l * p0) / (l + 1)};
        }
      }
    }
    for (uint32_t l = 0; l <= L; ++l) EXPECT_NEAR(z[l], q[l], 1e-9 * std::sqrt((2.0 * l + 1) / (4 * kPi))) << sigma << " " << l;
  }
  // sigma -> 0: towards a delta, z_l -> sqrt((2l + 1) / 4 pi) exp(-l (l + 1) sigma^2 / 2) (the
  // large-argument limit of i_l / i_0), to degree 300.
  for (double sigma : {1e-2, 1e-3, 1e-4}) {
    const std::vector<double> d = shadetwin::gaussianLobeZh(sigma, 300);
    for (uint32_t l = 0; l <= 300; ++l) {
      const double r = d[l] / std::sqrt((2.0 * l + 1) / (4 * kPi)), a = std::exp(-0.5 * l * (l + 1.0) * sigma * sigma);
      EXPECT_NEAR(r, a, 2.0 * sigma * sigma * a + 1e-300) << sigma << " " << l;
    }
  }
  // Band limits (eps 1e-6, the paper's): the ratio is ~exp(-l (l + 1) sigma^2 / 2), so L ~ sqrt(2 ln 1e6) / sigma.
  for (double sigma : {0.05, 0.1, 0.2}) {
    const uint32_t L = shadetwin::gaussianLobeBandLimit(sigma, 1e-6, 400);
    EXPECT_NEAR(double(L), std::sqrt(2 * std::log(1e6)) / sigma, 3.0) << sigma;
  }
  EXPECT_GT(shadetwin::gaussianLobeBandLimit(0.05, 1e-6, 400), shadetwin::gaussianLobeBandLimit(0.1, 1e-6, 400));
  EXPECT_EQ(shadetwin::gaussianLobeBandLimit(1e-4, 1e-6, 300), 300u);  // capped
}
