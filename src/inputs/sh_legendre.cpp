#include "inputs/sh_legendre.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shadetwin {

emu::Texture shLegendreCoefficients(uint32_t maxOrder) {
  if (maxOrder > 4096) throw std::invalid_argument("SH order " + std::to_string(maxOrder) + " above 4096");
  const uint32_t n = maxOrder + 1;
  std::vector<float> t(size_t(n) * n * 4, 0.0f);
  for (uint32_t m = 0; m <= maxOrder; ++m)
    for (uint32_t l = m; l <= maxOrder; ++l) {
      float* c = &t[(size_t(m) * n + l) * 4];
      const double L = l, M = m;
      if (l == m) c[0] = m == 0 ? 0.0f : float(std::sqrt((2 * M + 1) / (2 * M)));
      else if (l == m + 1) c[0] = float(std::sqrt(2 * M + 3));
      else {
        c[0] = float(std::sqrt((4 * L * L - 1) / (L * L - M * M)));
        c[1] = float(std::sqrt(((L - 1) * (L - 1) - M * M) / (4 * (L - 1) * (L - 1) - 1)));
      }
    }
  return emu::floatTexture(emu::Format::RGBA32F, n, n, t.data());
}

std::vector<double> shLegendreDouble(uint32_t maxOrder, double theta) {
  return shLegendreDouble(maxOrder, std::cos(theta), std::fabs(std::sin(theta)));
}

std::vector<double> shLegendreDouble(uint32_t maxOrder, double z, double s) {
  std::vector<double> out(size_t(maxOrder + 1) * (maxOrder + 2) / 2, 0.0);
  double mant = 1.0 / std::sqrt(4 * std::numbers::pi);
  int e = 0;  // seed = mant 2^e
  for (uint32_t m = 0; m <= maxOrder; ++m) {
    if (m > 0) {
      mant *= std::sqrt((2.0 * m + 1) / (2.0 * m)) * s;
      int de = 0;
      mant = std::frexp(mant, &de);
      e += de;
    }
    // Along l: values carried as p 2^e2, renormalised whenever |p| leaves [2^-500, 2^500].
    double p = mant, q = 0.0;
    int e2 = e;
    out[size_t(m) * (m + 1) / 2 + m] = std::ldexp(p, e2);
    for (uint32_t l = m + 1; l <= maxOrder; ++l) {
      const double L = l, M = m;
      double next;
      if (l == m + 1) next = std::sqrt(2 * M + 3) * z * p;
      else
        next = std::sqrt((4 * L * L - 1) / (L * L - M * M)) *
               (z * p - std::sqrt(((L - 1) * (L - 1) - M * M) / (4 * (L - 1) * (L - 1) - 1)) * q);
      q = p, p = next;
      if (std::fabs(p) > 0x1p500 || (std::fabs(p) < 0x1p-500 && p != 0.0)) {
        int de = 0;
        std::frexp(p, &de);
        p = std::ldexp(p, -de), q = std::ldexp(q, -de), e2 += de;
      }
      out[size_t(l) * (l + 1) / 2 + m] = std::ldexp(p, e2);
    }
  }
  return out;
}

std::vector<double> gaussianLobeZh(double sigma, uint32_t maxOrder) {
  if (!(sigma > 0.0)) throw std::invalid_argument("Gaussian lobe: sigma must be positive");
  const double x = 1.0 / (sigma * sigma);
  // Ratios r_l = i_l(x) / i_{l-1}(x) from the backward recurrence 1 / r_l = (2l + 1) / x + r_{l+1},
  // started far enough above maxOrder (the functions decay like exp(-l^2 / 2x) there) at the
  // asymptotic ratio x / (l + 1/2 + sqrt((l + 1/2)^2 + x^2)).
  const uint32_t start = maxOrder + 64 + uint32_t(std::min(1e7, 12.0 * std::sqrt(x)));
  std::vector<double> r(size_t(maxOrder) + 1, 0.0);
  double rn = x / (start + 0.5 + std::sqrt((start + 0.5) * (start + 0.5) + x * x));
  for (uint32_t l = start; l >= 1; --l) {
    rn = 1.0 / ((2.0 * l + 1) / x + rn);  // r_l
    if (l <= maxOrder) r[l] = rn;
  }
  std::vector<double> z(size_t(maxOrder) + 1);
  double ratio = 1.0;  // i_l / i_0
  for (uint32_t l = 0; l <= maxOrder; ++l) {
    if (l > 0) ratio *= r[l];
    z[l] = std::sqrt((2.0 * l + 1) / (4 * std::numbers::pi)) * ratio;
  }
  return z;
}

uint32_t gaussianLobeBandLimit(double sigma, double eps, uint32_t maxOrder) {
  const std::vector<double> z = gaussianLobeZh(sigma, maxOrder);
  uint32_t L = 0;
  for (uint32_t l = 0; l <= maxOrder; ++l)
    if (std::fabs(z[l]) * std::sqrt(4 * std::numbers::pi / (2.0 * l + 1)) >= eps) L = l;
  return L;
}

}  // namespace shadetwin
