#include "inputs/glint_lighting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "inputs/sh_legendre.h"
#include "lanes/instantiate.h"
#include "model/counted.h"
#include "util/pass_log.h"
#include "passes/passes_vk.h"
#include "passes/shade.h"
#include "vk/context.h"

namespace shadetwin {
namespace {
#include "glint_lighting_comp.inc"

constexpr double kPi = std::numbers::pi;

struct LightingPush {
  int32_t envW, y0, y1, level, order;
  uint32_t views, count;
};
static_assert(sizeof(LightingPush) == 28, "LightingPush must match the push block of glint_lighting.comp");

void check(const emu::Texture& env, const GlintLightingSpec& s) {
  if (env.format() != emu::Format::RGBA32F) throw std::invalid_argument("glint lighting: the environment must be RGBA32F");
  if (s.order > 64) throw std::invalid_argument("glint lighting: order " + std::to_string(s.order) + " above 64");
  if (s.rings < 2 || s.sectors < 1) throw std::invalid_argument("glint lighting: need at least 2 x 1 view directions");
  if (s.level >= env.levelCount())
    throw std::invalid_argument("glint lighting: environment level " + std::to_string(s.level) + " (it has " +
                                std::to_string(env.levelCount()) + ")");
}

// Column m of view v from the kernel's output into the table: stored for the first band, added for
// the next ones (band order, the same on both builds).
template <class Get>
void storeColumn(GlintLightingTable& t, uint32_t view, uint32_t m, bool first, Get get) {
  auto put = [&](float* c, uint32_t i) {
    for (int ch = 0; ch < 3; ++ch) c[ch] = first ? get(i + uint32_t(ch)) : c[ch] + get(i + uint32_t(ch));
  };
  for (uint32_t l = m; l <= t.spec.order; ++l) {
    put(&t.rgba[(size_t(view) * t.coeffs + l * l + l + m) * 4], 6 * (l - m));
    if (m > 0) put(&t.rgba[(size_t(view) * t.coeffs + l * l + l - m) * 4], 6 * (l - m) + 3);
  }
}

uint32_t bandRowsOf(const GlintLightingSpec& s, uint32_t h) { return s.bandRows == 0 ? h : std::min(h, s.bandRows); }

}  // namespace

uint32_t glintBandRows(uint32_t loopLimit, uint32_t w, uint32_t h, uint32_t order) {
  if (loopLimit == 0) return 0;
  // Measured on lavapipe (the boundary of texels x (order + a) at the limit: a = 4..6; the exact-math
  // loops of fixed count are unrolled and take none): order + 8 per texel, with a margin.
  const uint64_t fixed = 6 * uint64_t(order + 1) + 400, perRow = uint64_t(w) * (order + 8) + 2;
  if (loopLimit <= fixed + perRow) return 1;
  return uint32_t(std::min<uint64_t>(h, (loopLimit - fixed) / perRow));
}

std::vector<uint32_t> glintLightBandLimits(const GlintLightingTable& t, double eps) {
  const uint32_t views = t.spec.rings * t.spec.sectors;
  std::vector<uint32_t> lim(views, 0);
  for (uint32_t v = 0; v < views; ++v)
    for (int c = 0; c < 3; ++c) {
      const double a0 = std::fabs(double(t.at(v, 0)[c]));
      if (a0 == 0) continue;
      for (uint32_t l = t.spec.order; l > lim[v]; --l) {
        double e = 0;
        for (uint32_t i = l * l; i < (l + 1) * (l + 1); ++i) e += double(t.at(v, i)[c]) * t.at(v, i)[c];
        if (std::sqrt((2.0 * l + 1) * e) >= eps * a0) {
          lim[v] = l;
          break;
        }
      }
    }
  return lim;
}

std::vector<float> glintViewDirections(const GlintLightingSpec& s) {
  std::vector<float> d(size_t(s.rings) * s.sectors * 4, 0.0f);
  for (uint32_t j = 0; j < s.rings; ++j)
    for (uint32_t k = 0; k < s.sectors; ++k) {
      const double u = double(k) / s.sectors, v = double(j) / (s.rings - 1), th = v * kPi, a = 2 * kPi * u;
      float* o = &d[(size_t(j) * s.sectors + k) * 4];
      o[0] = float(-std::sin(th) * std::sin(a)), o[1] = float(std::cos(th)), o[2] = float(std::sin(th) * std::cos(a));
    }
  return d;
}

emu::Texture glintEnvDirections(uint32_t w, uint32_t h) {
  std::vector<float> t(size_t(w) * h * 4);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double u = (x + 0.5) / w, v = (y + 0.5) / h, th = v * kPi, a = 2 * kPi * u;
      float* o = &t[(size_t(y) * w + x) * 4];
      o[0] = float(-std::sin(th) * std::sin(a)), o[1] = float(std::cos(th)), o[2] = float(std::sin(th) * std::cos(a));
      o[3] = float((2 * kPi / w) * (kPi / h) * std::sin(th));
    }
  return emu::floatTexture(emu::Format::RGBA32F, w, h, t.data());
}

namespace {
// What both drivers start from: the empty table, the view directions, the level's quadrature table
// and the recurrence coefficients.
struct Prepared {
  GlintLightingTable t;
  uint32_t views, ew, eh;
  std::vector<float> vd;
  emu::Texture dirs, coef;
};
Prepared prepare(const emu::Texture& env, const GlintLightingSpec& spec) {
  check(env, spec);
  GlintLightingTable t;
  t.spec = spec, t.coeffs = (spec.order + 1) * (spec.order + 1);
  const uint32_t views = spec.rings * spec.sectors, ew = env.levelWidth(spec.level), eh = env.levelHeight(spec.level);
  t.rgba.assign(size_t(views) * t.coeffs * 4, 0.0f);
  return {std::move(t), views, ew, eh, glintViewDirections(spec), glintEnvDirections(ew, eh), shLegendreCoefficients(spec.order)};
}
}  // namespace

namespace {
// The driver over either lane build (an instantiation namespace): the SIMD build (the emulator) or the counting one
// (the model).
#define GLINT_LIGHTING_LANES(Name, NS)                                                      \
  struct Name {                                                                             \
    using Float = shade::NS::Float;                                                         \
    static auto column(auto&&... a) { return shade::NS::glintLightingColumn(a...); }        \
  };
GLINT_LIGHTING_LANES(X8Lanes, x8)
GLINT_LIGHTING_LANES(CountedLanes, counted)
#undef GLINT_LIGHTING_LANES

template <class L>
GlintLightingTable glintLightingLanes(const emu::Texture& env, const emu::DeviceProfile& dev, const GlintLightingSpec& spec) {
  const auto t0 = std::chrono::steady_clock::now();
  Prepared pr = prepare(env, spec);
  GlintLightingTable& t = pr.t;
  const uint32_t views = pr.views, ew = pr.ew, eh = pr.eh;
  const std::vector<float>& vd = pr.vd;
  const emu::Texture &dirs = pr.dirs, &coef = pr.coef;
  const shade::Sampler2D es = environmentSampler(env, dev, true), ds = environmentSampler(dirs, dev, false),
                         cs = environmentSampler(coef, dev, false);
  using F = typename L::Float;
  const uint32_t blocks = (views + 7) / 8;
  // Lanes: 8 consecutive views of one column m (a device vector of the compute kernel, whose
  // invocations run m-major), tail lanes repeat the last view.
  const uint32_t rows = bandRowsOf(spec, eh);
  for (uint32_t y0 = 0; y0 < eh; y0 += rows) {  // bands in order, each added into the table
    const uint32_t y1 = std::min(eh, y0 + rows);
    tbb::parallel_for(tbb::blocked_range2d<uint32_t>(0, spec.order + 1, 1, 0, blocks, 4), [&](const tbb::blocked_range2d<uint32_t>& r) {
      emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
      for (uint32_t m = r.rows().begin(); m < r.rows().end(); ++m)
        for (uint32_t b = r.cols().begin(); b < r.cols().end(); ++b) {
          shade::V3<F> wo;
          for (int l = 0; l < 8; ++l) {
            const uint32_t v = std::min(views - 1, b * 8 + uint32_t(l));
            wo.x.set(l, vd[4 * v]), wo.y.set(l, vd[4 * v + 1]), wo.z.set(l, vd[4 * v + 2]);
          }
          const auto col = L::column(es, ds, cs, int(ew), int(y0), int(y1), int(spec.level), int(spec.order),
                                                          int(m), wo);
          for (int l = 0; l < 8 && b * 8 + uint32_t(l) < views; ++l)
            storeColumn(t, b * 8 + uint32_t(l), m, y0 == 0, [&](uint32_t i) { return col.c[i][l]; });
        }
    });
  }
  t.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return std::move(t);
}

}  // namespace

GlintLightingTable glintLightingEmu(const emu::Texture& env, const emu::DeviceProfile& dev, const GlintLightingSpec& spec) {
  notePass("glint-lighting");
  return glintLightingLanes<X8Lanes>(env, dev, spec);
}

GlintLightingTable glintLightingCounted(const emu::Texture& env, const emu::DeviceProfile& dev, const GlintLightingSpec& spec) {
  return glintLightingLanes<CountedLanes>(env, dev, spec);
}

GlintLightingTable glintLightingVulkan(vk::Context& ctx, const emu::Texture& env, const GlintLightingSpec& spec) {
  const auto t0 = std::chrono::steady_clock::now();
  Prepared pr = prepare(env, spec);
  GlintLightingTable& t = pr.t;
  const uint32_t views = pr.views, ew = pr.ew, eh = pr.eh;
  const std::vector<float>& vd = pr.vd;
  const emu::Texture &dirs = pr.dirs, &coef = pr.coef;
  vk::Image envImg(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, env.width(), env.height(), 1, env.levels(), 16, VK_IMAGE_VIEW_TYPE_2D);
  vk::Image dirImg(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, dirs.width(), dirs.height(), 1, dirs.levels(), 16, VK_IMAGE_VIEW_TYPE_2D);
  vk::Image coefImg(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, coef.width(), coef.height(), 1, coef.levels(), 16, VK_IMAGE_VIEW_TYPE_2D);
  vk::Sampler sampler(ctx, dataTextureSamplerInfo());
  const uint32_t count = views * (spec.order + 1), col = 6 * (spec.order + 1);
  vk::Buffer viewBuf(ctx, vd.size() * 4), out(ctx, size_t(count) * col * 4);
  std::memcpy(viewBuf.as<float>(), vd.data(), vd.size() * 4);
  static constexpr VkDescriptorType kLayout[5] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                  VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                  VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel kernel(ctx, vk::Stage::Compute, kSpv_glint_lighting_comp, kLayout, sizeof(LightingPush));
  const vk::Binding b[5] = {{kLayout[0], VK_NULL_HANDLE, envImg.view(), sampler.handle()},
                            {kLayout[1], VK_NULL_HANDLE, dirImg.view(), sampler.handle()},
                            {kLayout[2], VK_NULL_HANDLE, coefImg.view(), sampler.handle()},
                            {kLayout[3], viewBuf.handle()},
                            {kLayout[4], out.handle()}};
  const uint32_t rows = bandRowsOf(spec, eh);
  for (uint32_t y0 = 0; y0 < eh; y0 += rows) {  // one dispatch per band, added in order
    const uint32_t y1 = std::min(eh, y0 + rows);
    const LightingPush push{int32_t(ew), int32_t(y0), int32_t(y1), int32_t(spec.level), int32_t(spec.order), views, count};
    kernel.run(b, &push, count);
    const float* o = out.as<float>();
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t m = i / views, v = i % views;
      storeColumn(t, v, m, y0 == 0, [&](uint32_t k) { return o[size_t(i) * col + k]; });
    }
  }
  t.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return std::move(t);
}

}  // namespace shadetwin
