#include "reference/glints_gxd.h"

#include "inputs/ndf_histogram.h"
#include "lanes/instantiate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "inputs/glints.h"
#include "passes/shade.h"

namespace shadetwin {

using reference::D3;

namespace {

constexpr double kPi = std::numbers::pi;

double fresnelConductor(double c, double n, double k) {
  c = std::clamp(c, 0.0, 1.0);
  const double c2 = c * c, s2 = 1 - c2, t0 = n * n - k * k - s2, a2b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k);
  const double a = std::sqrt(std::max(0.0, 0.5 * (a2b2 + t0))), t1 = a2b2 + c2, t2 = 2 * a * c, rs = (t1 - t2) / (t1 + t2);
  const double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2, rp = rs * (t3 - t4) / (t3 + t4);
  return 0.5 * (rs + rp);
}

// Smith's Beckmann masking, exact: 2 / (1 + erf(a) + exp(-a^2) / (a sqrt(pi))), a = cot / alpha.
double smithG1(double c, double alpha) {
  if (c <= 0) return 0.0;
  const double s = std::sqrt(std::max(0.0, 1 - c * c));
  if (s == 0) return 1.0;
  const double a = c / (alpha * s);
  if (a > 30) return 1.0;
  return 2.0 / (1.0 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(kPi)));
}

D3 toTangent(const GlintPixel& px, D3 w) { return {dot(w, px.t), dot(w, px.b), dot(w, px.n)}; }
D3 toWorld(const GlintPixel& px, D3 v) { return px.t * v.x + px.b * v.y + px.n * v.z; }

}  // namespace

NormalBounds normalBounds(const NormalMap& map) {
  NormalBounds nb;
  nb.width = map.width, nb.height = map.height;
  const uint32_t sizes[2] = {8, 64};
  for (int L = 0; L < 2; ++L) {
    auto& lv = nb.level[L];
    lv.block = sizes[L];
    lv.bw = (map.width + lv.block - 1) / lv.block, lv.bh = (map.height + lv.block - 1) / lv.block;
    lv.lo.assign(size_t(lv.bw) * lv.bh * 3, 2.0f);
    lv.hi.assign(size_t(lv.bw) * lv.bh * 3, -2.0f);
    for (uint32_t y = 0; y < map.height; ++y)
      for (uint32_t x = 0; x < map.width; ++x) {
        const size_t b = size_t(y / lv.block) * lv.bw + x / lv.block;
        for (int c = 0; c < 3; ++c) {
          lv.lo[3 * b + c] = std::min(lv.lo[3 * b + c], map.at(x, y)[c]);
          lv.hi[3 * b + c] = std::max(lv.hi[3 * b + c], map.at(x, y)[c]);
        }
      }
  }
  return nb;
}

std::array<double, 3> glintFgOutside(const GlintPixel& px) {
  const double cosO = dot(px.wo, px.n), alpha = std::sqrt(2.0) * px.sigma;
  const D3 refl = px.n * (2 * cosO) - px.wo;
  std::array<double, 3> fg{};
  for (int c = 0; c < 3; ++c)
    fg[size_t(c)] = fresnelConductor(cosO, px.eta[c], px.k[c]) * smithG1(cosO, alpha) * smithG1(dot(refl, px.n), alpha);
  return fg;
}

double glintLobeNorm(double sigma) {
  const double s2 = sigma * sigma;
  return 2 * kPi * s2 * -std::expm1(-2.0 / s2);
}

double glintFootprintNdf(const GlintPixel& px, D3 h, uint64_t* lobes) {
  const NormalMap& m = *px.map;
  const D3 ht = toTangent(px, h);
  const double inv = 1.0 / (px.sigma * px.sigma), thr = 1.0 - 40.0 * px.sigma * px.sigma;
  auto bound = [&](const std::vector<float>& lo, const std::vector<float>& hi, size_t b) {
    const double c[3] = {ht.x, ht.y, ht.z};
    double d = 0;
    for (int k = 0; k < 3; ++k) d += std::max(c[k] * lo[3 * b + k], c[k] * hi[3 * b + k]);
    return d;  // no normal of the block has a larger dot with h
  };
  TileSpan xs[3], ys[3];
  const int nx = tileSpans(px.x0, px.x1, m.width, xs), ny = tileSpans(px.y0, px.y1, m.height, ys);
  double acc = 0;
  uint64_t count = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const TileSpan &sx = xs[i], &sy = ys[j];
      double part = 0;
      auto texels = [&](int64_t xa, int64_t xb, int64_t ya, int64_t yb) {
        for (int64_t y = ya; y <= yb; ++y)
          for (int64_t x = xa; x <= xb; ++x) {
            const float* n = m.at(uint32_t(x), uint32_t(y));
            const double d = ht.x * n[0] + ht.y * n[1] + ht.z * n[2];
            ++count;
            if (d < thr) continue;
            part += std::exp((d - 1.0) * inv);
          }
      };
      if (!px.bounds) {
        texels(sx.lo, sx.hi, sy.lo, sy.hi);
      } else {
        const auto &L1 = px.bounds->level[1], &L0 = px.bounds->level[0];
        for (int64_t by = sy.lo / L1.block; by <= sy.hi / L1.block; ++by)
          for (int64_t bx = sx.lo / L1.block; bx <= sx.hi / L1.block; ++bx) {
            if (bound(L1.lo, L1.hi, size_t(by) * L1.bw + size_t(bx)) < thr) continue;
            const int64_t ya = std::max(sy.lo, by * L1.block), yb = std::min(sy.hi, by * L1.block + L1.block - 1);
            const int64_t xa = std::max(sx.lo, bx * L1.block), xb = std::min(sx.hi, bx * L1.block + L1.block - 1);
            for (int64_t cy = ya / L0.block; cy <= yb / L0.block; ++cy)
              for (int64_t cx = xa / L0.block; cx <= xb / L0.block; ++cx) {
                if (bound(L0.lo, L0.hi, size_t(cy) * L0.bw + size_t(cx)) < thr) continue;
                texels(std::max(xa, cx * L0.block), std::min(xb, cx * L0.block + L0.block - 1), std::max(ya, cy * L0.block),
                       std::min(yb, cy * L0.block + L0.block - 1));
              }
          }
      }
      acc += part * double(sx.mult * sy.mult);
    }
  if (lobes) *lobes += count;
  const double area = double(px.x1 - px.x0 + 1) * double(px.y1 - px.y0 + 1);
  return acc / (area * glintLobeNorm(px.sigma));
}

GlintPixel glintPixelOf(const float* t, const float eye[3], const Material& m, const NormalMap& map, const NormalBounds* bounds,
                        uint64_t pixel) {
  GlintPixel px;
  px.map = &map, px.bounds = bounds, px.pixel = pixel;
  px.n = normalize(D3{t[4], t[5], t[6]});
  const D3 tg{t[8], t[9], t[10]};
  D3 tp = tg - px.n * dot(px.n, tg);
  if (dot(tp, tp) <= 1e-12) tp = std::fabs(px.n.x) < 0.9 ? D3{0, -px.n.z, px.n.y} : D3{-px.n.z, 0, px.n.x};
  px.t = normalize(tp);
  px.b = cross(px.n, px.t) * (t[3] < 0 ? -1.0 : 1.0);
  px.wo = normalize(D3{eye[0] - t[0], eye[1] - t[1], eye[2] - t[2]});
  const shade::scalar::GlintBox box =
      shade::scalar::glintFootprint(t[7], t[11], shade::V4<float>(t[12], t[13], t[14], t[15]), float(double(map.width) * m.glintScale));
  px.x0 = box.x0, px.y0 = box.y0, px.x1 = box.x1, px.y1 = box.y1;
  px.sigma = m.glintSigma;
  for (int c = 0; c < 3; ++c) px.eta[c] = m.glintEta[size_t(c)], px.k[c] = m.glintK[size_t(c)];
  return px;
}

GxdResult glintGxd(const GlintPixel& px, const reference::Environment& env, uint32_t samples, uint64_t seed) {
  if (!px.map || px.x1 < px.x0 || px.y1 < px.y0 || samples == 0) throw std::invalid_argument("glintGxd: empty footprint or no samples");
  const double cosO = dot(px.wo, px.n);
  GxdResult r;
  if (cosO <= 0) return r;
  const double alpha = std::sqrt(2.0) * px.sigma, lambda = 1.0 / (px.sigma * px.sigma);
  const std::array<double, 3> fgOut = glintFgOutside(px);
  const int64_t w = px.x1 - px.x0 + 1, h = px.y1 - px.y0 + 1;
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  // f cos / (pA + pB) L for one direction wi (0 below the macro surface).
  auto contribution = [&](D3 wi, double pA, double out[3]) {
    out[0] = out[1] = out[2] = 0;
    const double cosI = dot(wi, px.n);
    if (cosI <= 0) return;
    const D3 hv = normalize(px.wo + wi);
    const double oh = dot(px.wo, hv);
    if (oh <= 0) return;
    const double D = glintFootprintNdf(px, hv, &r.texelLobes);
    const double pB = D / (4 * oh);
    if (pA + pB <= 0) return;
    double L[3];
    env.radiance(wi, L);
    for (int c = 0; c < 3; ++c) {
      const double fg = px.fgOutside ? fgOut[size_t(c)]
                                     : fresnelConductor(dot(wi, hv), px.eta[c], px.k[c]) * smithG1(cosO, alpha) * smithG1(cosI, alpha);
      out[c] = L[c] * fg * D / (4 * cosO) / (pA + pB);
    }
  };
  for (uint32_t s = 0; s < samples; ++s) {
    reference::Rng rng(seed, px.pixel, s);
    double pair[3] = {0, 0, 0}, v[3];
    // Environment strategy.
    const double e0 = rng.next(), e1 = rng.next(), e2 = rng.next(), e3 = rng.next();
    const D3 wa = env.sample(e0, e1, e2, e3);
    contribution(wa, env.pdf(wa), v);
    for (int c = 0; c < 3; ++c) pair[c] += v[c];
    // NDF strategy: a texel of the footprint, h from its lobe, wi the reflection.
    const int64_t tx = px.x0 + std::min(w - 1, int64_t(rng.next() * double(w)));
    const int64_t ty = px.y0 + std::min(h - 1, int64_t(rng.next() * double(h)));
    const float* nt = px.map->at(uint32_t(((tx % px.map->width) + px.map->width) % px.map->width),
                                 uint32_t(((ty % px.map->height) + px.map->height) % px.map->height));
    const double u1 = rng.next(), u2 = rng.next();
    const double ct = std::clamp(1.0 + std::log1p(-u1 * -std::expm1(-2 * lambda)) / lambda, -1.0, 1.0);
    const double st = std::sqrt(std::max(0.0, 1 - ct * ct)), phi = 2 * kPi * u2;
    const D3 nn = normalize(D3{nt[0], nt[1], nt[2]});
    const D3 helper = std::fabs(nn.x) < 0.9 ? D3{1, 0, 0} : D3{0, 1, 0};
    const D3 e1t = normalize(cross(helper, nn)), e2t = cross(nn, e1t);
    const D3 hb = toWorld(px, e1t * (st * std::cos(phi)) + e2t * (st * std::sin(phi)) + nn * ct);
    const double oh = dot(px.wo, hb);
    if (oh > 0) {
      const D3 wb = hb * (2 * oh) - px.wo;
      contribution(wb, env.pdf(wb), v);
      for (int c = 0; c < 3; ++c) pair[c] += v[c];
    }
    for (int c = 0; c < 3; ++c) sum[c] += pair[c], sum2[c] += pair[c] * pair[c];
  }
  for (int c = 0; c < 3; ++c) {
    r.rgb[c] = sum[c] / samples;
    const double var = std::max(0.0, sum2[c] / samples - r.rgb[c] * r.rgb[c]);
    r.stdErr[c] = std::sqrt(var / samples);
  }
  return r;
}

std::vector<float> glintGxdImage(const Scene& scene, const float* gbuffer, uint32_t width, uint32_t height,
                                 const reference::Environment& env, const GlintGxdOptions& opts) {
  std::vector<NormalMap> maps;
  std::vector<NormalBounds> bounds;
  for (const Material& m : scene.materials) {
    if (!m.glints) throw std::invalid_argument("glints-gxd: material '" + m.name + "' has no glints block");
    try {
      maps.push_back(glintMaterialMap(m));
    } catch (const std::exception& e) {
      throw std::invalid_argument("material '" + m.name + "': glints map: " + e.what());
    }
  }
  bounds.reserve(maps.size());
  for (const NormalMap& m : maps) bounds.push_back(normalBounds(m));
  // The camera ray through a pixel centre (shade_mirror.h cameraRay's basis, the ray in double).
  const CameraRays cam = cameraRays(scene);
  const size_t n = size_t(width) * height;
  std::vector<float> img(4 * n, 0.0f);
  tbb::parallel_for(size_t(0), n, [&](size_t p) {
    img[4 * p + 3] = 1.0f;
    if (opts.only && !(*opts.only)[p]) return;
    const float* g = gbuffer + p * 16;
    double rgb[3];
    if (g[3] == 0.0f) {
      const double nx = ((double(p % width) + 0.5) / width) * 2 - 1, ny = ((double(p / width) + 0.5) / height) * 2 - 1;
      auto axis = [&](int k) { return double(cam.fwd[k]) + double(cam.right[k]) * nx + double(cam.down[k]) * ny; };
      env.radiance(normalize(reference::D3{axis(0), axis(1), axis(2)}), rgb);
    } else {
      const uint32_t slot = shade::scalar::materialSlot(g[3], uint32_t(scene.materials.size()));
      GlintPixel px = glintPixelOf(g, cam.eye, scene.materials[slot], maps[slot], &bounds[slot], p);
      px.fgOutside = opts.fgOutside;
      const GxdResult r = glintGxd(px, env, opts.samples, opts.seed);
      for (int c = 0; c < 3; ++c) rgb[c] = r.rgb[c];
    }
    for (int c = 0; c < 3; ++c) img[4 * p + size_t(c)] = float(rgb[c]);
  });
  return img;
}

}  // namespace shadetwin
