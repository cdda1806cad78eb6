// The reference renderer's environment (radiance lookups and an importance sampler) and its
// counter-based random numbers, shared by the ground-truth integrators (reference.cpp, glints_gxd.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "inputs/env_kdtree.h"
#include "reference/reference.h"
#include "reference/reference_brdf.h"

namespace shadetwin::reference {

/// Counter-based random numbers: splitmix64 of (seed, pixel, sample, dimension).
struct Rng {
  uint64_t state;
  static uint64_t mix(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  Rng(uint64_t seed, uint64_t pixel, uint64_t sample) : state(mix(mix(mix(seed) ^ pixel) ^ sample)) {}
  double next() {
    state = mix(state);
    return double(state >> 11) * 0x1.0p-53;
  }
};

/// The environment as a radiance function and as a sampling distribution.
class Environment {
  static constexpr double kPi = std::numbers::pi;
 public:
  Environment(const EnvImage& img, double intensity) : img_(img), intensity_(intensity) {
    const uint32_t W = img.width, H = img.height;
    if (!W || !H || !img.rgba) throw std::invalid_argument("reference: empty environment image");
    // Texel weights: inputs/env_kdtree.h's envSamplingWeights (the largest non-negative luminance of
    // the texel's 3 x 3 neighbourhood, times sin(theta) of the row centre: the pdf then bounds the
    // bilinear radiance, no fireflies next to the sun), plus a floor of 1e-4 of the mean so every
    // direction keeps a positive pdf.
    cdfRow_.resize(H + 1);
    cdfCol_.resize(size_t(H) * (W + 1));
    const std::vector<double> w = envSamplingWeights(img.rgba, W, H);
    double total = 0;
    for (double v : w) total += v;
    const double floor = total > 0 ? 1e-4 * total / (double(W) * H) : 1.0;
    cdfRow_[0] = 0;
    for (uint32_t y = 0; y < H; ++y) {
      double* c = &cdfCol_[size_t(y) * (W + 1)];
      c[0] = 0;
      for (uint32_t x = 0; x < W; ++x) c[x + 1] = c[x] + w[size_t(y) * W + x] + floor * std::sin(kPi * (y + 0.5) / H);
      cdfRow_[y + 1] = cdfRow_[y] + c[W];
    }
    sum_ = cdfRow_[H];
  }

  /// Bilinear radiance (repeat in u, clamp in v), RGB, times the intensity.
  void radiance(D3 d, double out[3]) const {
    double u, v;
    uvOf(d, u, v);
    const int W = int(img_.width), H = int(img_.height);
    const double x = u * W - 0.5, y = v * H - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    out[0] = out[1] = out[2] = 0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int xi = ((x0 + i) % W + W) % W, yi = std::clamp(y0 + j, 0, H - 1);
        const double wgt = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
        const float* t = img_.rgba + 4 * (size_t(yi) * size_t(W) + size_t(xi));
        for (int k = 0; k < 3; ++k) out[k] += wgt * t[k];
      }
    for (int k = 0; k < 3; ++k) out[k] *= intensity_;
  }

  /// Texel by inversion (marginal rows, conditional columns), uniform inside it in (u, v).
  D3 sample(double u0, double u1, double u2, double u3) const {
    const uint32_t W = img_.width, H = img_.height;
    const double tr = u0 * sum_;
    uint32_t y = uint32_t(std::upper_bound(cdfRow_.begin(), cdfRow_.end(), tr) - cdfRow_.begin()) - 1;
    y = std::min(y, H - 1);
    const double* c = &cdfCol_[size_t(y) * (W + 1)];
    const double tc = u1 * c[W];
    uint32_t x = uint32_t(std::upper_bound(c, c + W + 1, tc) - c) - 1;
    x = std::min(x, W - 1);
    return dirOf((x + u2) / W, (y + u3) / H);
  }

  /// Solid-angle pdf of sample(): p_texel * W * H / (2 pi^2 sin(theta)).
  double pdf(D3 d) const {
    double u, v;
    uvOf(d, u, v);
    const uint32_t W = img_.width, H = img_.height;
    const uint32_t x = std::min(W - 1, uint32_t(u * W)), y = std::min(H - 1, uint32_t(v * H));
    const double* c = &cdfCol_[size_t(y) * (W + 1)];
    const double p = (c[x + 1] - c[x]) / sum_;
    const double s = std::sin(kPi * v);
    return s > 0 ? p * W * H / (2 * kPi * kPi * s) : 0.0;
  }

  // Same mapping as shade/shade_mirror.h equirectUv: u from the azimuth about +y (u = 1/2 looks
  // down -z), v = polar angle / pi.
  static void uvOf(D3 d, double& u, double& v) {
    u = std::atan2(d.x, -d.z) / (2 * kPi) + 0.5;
    v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
    u = u - std::floor(u);
  }
  static D3 dirOf(double u, double v) {
    const double phi = (u - 0.5) * 2 * kPi, theta = v * kPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
  }

 private:
  EnvImage img_;
  double intensity_;
  std::vector<double> cdfRow_, cdfCol_;
  double sum_ = 0;
};

}  // namespace shadetwin::reference
