#include "inputs/env_lights.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include "lanes/instantiate.h"

namespace shadetwin {

EnvLights envLights(const emu::Texture& env, uint32_t n) {
  if (env.format() != emu::Format::RGBA32F) throw std::invalid_argument("env lights: the environment must be RGBA32F");
  const uint32_t W = env.width(), H = env.height();
  std::vector<float> t(size_t(W) * H * 4);
  std::memcpy(t.data(), env.levels()[0].data(), t.size() * 4);
  const double pi = std::numbers::pi;
  // Texel weights max(lum, 0) sin(theta), row CDFs and the marginal CDF over rows.
  std::vector<double> cdf(size_t(W) * H), rowCdf(H);
  double total = 0;
  for (uint32_t y = 0; y < H; ++y) {
    const double s = std::sin(pi * (y + 0.5) / H);
    double row = 0;
    for (uint32_t x = 0; x < W; ++x) {
      const float* p = &t[4 * (size_t(y) * W + x)];
      const double lum = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      row += std::isfinite(lum) ? std::max(lum, 0.0) * s : 0.0;
      cdf[size_t(y) * W + x] = row;
    }
    total += row;
    rowCdf[y] = total;
  }
  EnvLights L;
  if (!(total > 0) || n == 0) return L;
  L.data.reserve(size_t(n) * 8);
  for (uint32_t i = 0; i < n; ++i) {
    // Hammersley point i of n: ((i + 1/2) / n, the shared 24-bit radical inverse of shade/sampling.h).
    const double u1 = (i + 0.5) / n, u2 = shade::scalar::radicalInverse2(i);
    const uint32_t y = uint32_t(std::upper_bound(rowCdf.begin(), rowCdf.end(), u1 * total) - rowCdf.begin());
    const uint32_t yy = std::min(y, H - 1);
    const double rowStart = yy ? rowCdf[yy - 1] : 0.0, rowSum = rowCdf[yy] - rowStart;
    const double* c = &cdf[size_t(yy) * W];
    const uint32_t x = std::min(uint32_t(std::upper_bound(c, c + W, u2 * rowSum) - c), W - 1);
    const double pTexel = (c[x] - (x ? c[x - 1] : 0.0)) / total;
    const double theta = pi * (yy + 0.5) / H, u = (x + 0.5) / W, st = std::sin(theta);
    const double pdf = pTexel * double(W) * H / (2 * pi * pi * st);  // solid angle
    const float* p = &t[4 * (size_t(yy) * W + x)];
    const double k = pdf > 0 ? 1.0 / (n * pdf) : 0.0;
    const float light[8] = {float(-st * std::sin(2 * pi * u)), float(std::cos(theta)), float(st * std::cos(2 * pi * u)), 0.0f,
                            float(p[0] * k), float(p[1] * k), float(p[2] * k), 0.0f};
    L.data.insert(L.data.end(), light, light + 8);
  }
  L.count = n;
  return L;
}

}  // namespace shadetwin
