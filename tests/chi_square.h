// Pearson's chi-square goodness-of-fit test shared by the sampler tests (brdf_test, env_sampling_test).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

namespace shadetwin::test {

// Upper tail of the chi-square distribution (Wilson-Hilferty normal approximation, fine for dof > 30).
inline double chiSquareTail(double x, int dof) {
  const double k = dof, z = (std::cbrt(x / k) - (1 - 2 / (9 * k))) / std::sqrt(2 / (9 * k));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

struct ChiSquare {
  double pValue = 0;
  int dof = 0;
};

// `observed` counts of n draws against bin probabilities `prob`, bins pooled in order until each pooled
// bin expects >= 5; the remainder is a last bin (counts where nothing is expected make it fail).
inline ChiSquare pooledChiSquare(const std::vector<double>& prob, const std::vector<double>& observed, double n) {
  double chi = 0, eAcc = 0, oAcc = 0;
  int pooled = 0;
  for (size_t i = 0; i < prob.size(); ++i) {
    eAcc += prob[i] * n, oAcc += observed[i];
    if (eAcc >= 5) chi += (oAcc - eAcc) * (oAcc - eAcc) / eAcc, ++pooled, eAcc = 0, oAcc = 0;
  }
  if (oAcc > 0 || eAcc > 0) chi += (oAcc - eAcc) * (oAcc - eAcc) / std::max(eAcc, 1e-9), ++pooled;
  return {chiSquareTail(chi, pooled - 1), pooled - 1};
}

}  // namespace shadetwin::test
