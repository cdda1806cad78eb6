#include "inputs/glint_tables.h"

#include "inputs/glint_lighting.h"

#include <cmath>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "inputs/sh_legendre.h"

namespace shadetwin {

using reference::D3;

namespace {
constexpr double kPi = std::numbers::pi;
}

std::vector<double> shRealDouble(uint32_t order, D3 d) {
  const double s = std::sqrt(d.x * d.x + d.y * d.y);
  const std::vector<double> P = shLegendreDouble(order, d.z, s);
  const double cp = s > 0 ? d.x / s : 1.0, sp = s > 0 ? d.y / s : 0.0;
  std::vector<double> y(size_t(order + 1) * (order + 1));
  double c = 1, sn = 0;  // cos(m phi), sin(m phi)
  for (uint32_t m = 0; m <= order; ++m) {
    if (m > 0) {
      const double c2 = c * cp - sn * sp, s2 = sn * cp + c * sp;
      c = c2, sn = s2;
    }
    for (uint32_t l = m; l <= order; ++l) {
      const double p = P[size_t(l) * (l + 1) / 2 + m];
      const size_t base = size_t(l) * l + l;
      if (m == 0) y[base] = p;
      else y[base + m] = std::sqrt(2.0) * p * c, y[base - m] = std::sqrt(2.0) * p * sn;
    }
  }
  return y;
}

std::vector<double> glintLightingShDouble(const reference::Environment& env, D3 wo, uint32_t order, uint32_t nu, uint32_t nv) {
  const size_t n = size_t(order + 1) * (order + 1);
  struct Acc {
    std::vector<double> v;
  };
  const Acc total = tbb::parallel_reduce(
      tbb::blocked_range<uint32_t>(0, nv), Acc{std::vector<double>(3 * n, 0.0)},
      [&](const tbb::blocked_range<uint32_t>& r, Acc acc) {
        for (uint32_t j = r.begin(); j < r.end(); ++j) {
          const double v = (j + 0.5) / nv, dOmega = (2 * kPi / nu) * (kPi / nv) * std::sin(kPi * v);
          for (uint32_t i = 0; i < nu; ++i) {
            const D3 wi = reference::Environment::dirOf((i + 0.5) / nu, v);
            const D3 sum = wo + wi;
            const double len = std::sqrt(dot(sum, sum));
            if (len < 1e-9) continue;
            double L[3];
            env.radiance(wi, L);
            const std::vector<double> y = shRealDouble(order, sum * (1.0 / len));
            for (size_t k = 0; k < n; ++k)
              for (int c = 0; c < 3; ++c) acc.v[3 * k + size_t(c)] += L[c] * y[k] * dOmega;
          }
        }
        return acc;
      },
      [](Acc a, const Acc& b) {
        for (size_t k = 0; k < a.v.size(); ++k) a.v[k] += b.v[k];
        return a;
      });
  return total.v;
}

D3 ndfBinDirection(const NdfBinningSpec& bins, uint32_t ring, uint32_t sector) {
  const double th = (ring + 0.5) * double(bins.thetaMax) / bins.rings, ph = (sector + 0.5) * 2 * kPi / bins.sectors;
  return {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
}

std::array<double, 3> glintShDoubleProduct(const std::vector<double>& lightingSh, const std::vector<uint32_t>& counts,
                                           const NdfBinningSpec& bins, D3 t, D3 b, D3 n, double sigma, uint32_t order) {
  const std::vector<double> z = gaussianLobeZh(sigma, order);
  double total = 0;
  for (uint32_t c : counts) total += c;
  std::array<double, 3> out{0, 0, 0};
  if (total == 0) return out;
  for (uint32_t r = 0; r < bins.rings; ++r)
    for (uint32_t p = 0; p < bins.sectors; ++p) {
      const uint32_t c = counts[size_t(r) * bins.sectors + p];
      if (!c) continue;
      const D3 dt = ndfBinDirection(bins, r, p), d = t * dt.x + b * dt.y + n * dt.z;
      const std::vector<double> y = shRealDouble(order, d);
      for (uint32_t l = 0; l <= order; ++l) {
        const double k = z[l] * std::sqrt(4 * kPi / (2.0 * l + 1)) * (c / total);
        for (uint32_t i = l * l; i < (l + 1) * (l + 1); ++i)
          for (int ch = 0; ch < 3; ++ch) out[size_t(ch)] += k * lightingSh[3 * i + size_t(ch)] * y[i];
      }
    }
  return out;
}

emu::Texture glintLobeTable(uint32_t order, uint32_t rings, uint32_t sectors) {
  GlintLightingSpec spec;
  spec.order = order, spec.rings = rings, spec.sectors = sectors;
  const std::vector<float> dirs = glintViewDirections(spec);
  const uint32_t nc = (order + 1) * (order + 1), w = (nc + 3) / 4, views = rings * sectors;
  std::vector<float> t(size_t(w) * 4 * views, 0.0f);
  for (uint32_t v = 0; v < views; ++v) {
    const std::vector<double> y = shRealDouble(order, reference::D3{dirs[4 * v], dirs[4 * v + 1], dirs[4 * v + 2]});
    for (uint32_t i = 0; i < nc; ++i) t[size_t(v) * w * 4 + i] = float(y[i]);
  }
  return emu::floatTexture(emu::Format::RGBA32F, w, views, t.data());
}

}  // namespace shadetwin
