#include "inputs/sh_irradiance.h"

#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "passes/shade.h"
#include "passes/passes_vk.h"
#include "lanes/instantiate.h"
#include "model/counted.h"
#include "util/pass_log.h"
#include "vk/context.h"

namespace shadetwin {
namespace {
#include "sh_project_comp.inc"
#include "sh_reduce_comp.inc"

struct ProjectPush {
  int32_t width, height;
};
static_assert(sizeof(ProjectPush) == 8, "ProjectPush must match the push block of sh_project.comp");
struct ReducePush {
  uint32_t rowCount;
};
static_assert(sizeof(ReducePush) == 4, "ReducePush must match the push block of sh_reduce.comp");

void checkInput(const emu::Texture& env) {
  if (env.format() != emu::Format::RGBA32F) throw std::invalid_argument("SH irradiance: the environment must be RGBA32F");
  if (env.width() < 1 || env.height() < 1) throw std::invalid_argument("SH irradiance: empty environment");
}

using V3f = shade::V3<float>;

// The drivers over either pair of lane builds (8-lane projection, one-lane reduction): SIMD / scalar (the emulator)
// or the counting ones (the model).
#define SH_LANES(Name, NS8, NS1)                                                            \
  struct Name {                                                                             \
    using Int = shade::NS8::Int;                                                            \
    using F1 = shade::NS1::Float;                                                           \
    static auto project(auto&&... a) { return shade::NS8::shProjectRow(a...); }             \
    static auto add3(auto&&... a) { return shade::NS1::shAdd3(a...); }                      \
    static auto scale(auto&&... a) { return shade::NS1::shIrradianceScale(a...); }          \
  };
SH_LANES(EmuLanes, x8, scalar)
SH_LANES(CountedLanes, counted, counted1)
#undef SH_LANES

// The pairwise tree of sh_reduce.comp over `rows` (16 vec4 per row, in place), then the band scale.
template <class L>
ShIrradiance reduceRows(std::vector<float>& rows, uint32_t rowCount) {
  using V3 = shade::V3<typename L::F1>;
  using opcount::lane0;
  ShIrradiance r;
  for (uint32_t k = 0; k < 16; ++k) {
    for (uint32_t s = 1; s < rowCount; s *= 2)
      for (uint32_t i = 0; i + s < rowCount; i += 2 * s) {
        float* a = &rows[4 * (i * 16 + k)];
        const float* b = &rows[4 * ((i + s) * 16 + k)];
        const V3 c = L::add3(V3(a[0], a[1], a[2]), V3(b[0], b[1], b[2]));
        a[0] = lane0(c.x), a[1] = lane0(c.y), a[2] = lane0(c.z);
      }
    const float* t = &rows[4 * k];
    const V3 c = L::scale(k, V3(t[0], t[1], t[2]));
    float* o = k < 9 ? &r.c[3 * k] : &r.band3[3 * (k - 9)];
    o[0] = lane0(c.x), o[1] = lane0(c.y), o[2] = lane0(c.z);
  }
  return r;
}
template <class L>
ShIrradiance shIrradianceLanes(const emu::Texture& env, const emu::DeviceProfile& dev, const std::function<void()>& between) {
  using I = typename L::Int;
  const int32_t w = int32_t(env.width()), h = int32_t(env.height());
  std::vector<float> rows(size_t(h) * 16 * 4, 0.0f);
  const shade::Sampler2D s = environmentSampler(env, dev, true);  // texelFetch ignores the sampler state
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, (h + 7) / 8, 1), [&](const tbb::blocked_range<int32_t>& r) {
    emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
    for (int32_t b = r.begin(); b != r.end(); ++b) {
      I y;
      for (int l = 0; l < 8; ++l) y.set(l, std::min(b * 8 + l, h - 1));  // tail lanes repeat the last row
      const auto row = L::project(s, y, w, h);
      const auto& c = row.low;
      const auto& hb = row.high;
      const std::decay_t<decltype(c.c0)> cs[16] = {c.c0,   c.c1,   c.c2,   c.c3,   c.c4,   c.c5,   c.c6,   c.c7,
                                             c.c8,   hb.c9,  hb.c10, hb.c11, hb.c12, hb.c13, hb.c14, hb.c15};
      for (int l = 0; l < 8 && b * 8 + l < h; ++l)
        for (int k = 0; k < 16; ++k) {
          float* o = &rows[4 * (size_t(b * 8 + l) * 16 + size_t(k))];
          o[0] = cs[k].x[l], o[1] = cs[k].y[l], o[2] = cs[k].z[l];
        }
    }
  });
  if (between) between();
  emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
  return reduceRows<L>(rows, uint32_t(h));
}
}  // namespace

ShIrradiance shIrradianceEmu(const emu::Texture& env, const emu::DeviceProfile& dev) {
  checkInput(env);
  notePass("sh-project");
  return shIrradianceLanes<EmuLanes>(env, dev, [] { notePass("sh-reduce"); });
}

ShIrradiance shIrradianceCounted(const emu::Texture& env, const emu::DeviceProfile& dev, const std::function<void()>& between) {
  checkInput(env);
  return shIrradianceLanes<CountedLanes>(env, dev, between);
}

ShIrradiance shIrradianceVulkan(vk::Context& ctx, const emu::Texture& env) {
  checkInput(env);
  const uint32_t w = env.width(), h = env.height();
  vk::Image img(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, w, h, 1, env.levels(), 16, VK_IMAGE_VIEW_TYPE_2D);
  vk::Sampler sampler(ctx, environmentSamplerInfo(true));  // texelFetch ignores the sampler state
  vk::Buffer rows(ctx, size_t(h) * 16 * 16), out(ctx, 16 * 16);
  static constexpr VkDescriptorType kProject[2] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  static constexpr VkDescriptorType kReduce[2] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel project(ctx, vk::Stage::Compute, kSpv_sh_project_comp, kProject, sizeof(ProjectPush));
  vk::Kernel reduce(ctx, vk::Stage::Compute, kSpv_sh_reduce_comp, kReduce, sizeof(ReducePush));
  const ProjectPush pp{int32_t(w), int32_t(h)};
  const vk::Binding bp[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, img.view(), sampler.handle()},
                             {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rows.handle()}};
  project.run(bp, &pp, h);
  const ReducePush rp{h};
  const vk::Binding br[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rows.handle()}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out.handle()}};
  reduce.run(br, &rp, 16);
  ShIrradiance r;
  const float* o = out.as<float>();
  for (int k = 0; k < 9; ++k) std::memcpy(&r.c[3 * size_t(k)], o + 4 * k, 12);
  for (int k = 9; k < 16; ++k) std::memcpy(&r.band3[3 * size_t(k - 9)], o + 4 * k, 12);
  return r;
}

std::array<float, 3> shIrradianceAt(const ShIrradiance& sh, const std::array<float, 3>& n) {
  V3f c[9];
  for (int k = 0; k < 9; ++k) c[k] = V3f(sh.c[3 * size_t(k)], sh.c[3 * size_t(k) + 1], sh.c[3 * size_t(k) + 2]);
  const V3f e = shade::scalar::shIrradiance(shade::scalar::ShRgb{c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]},
                                            V3f(n[0], n[1], n[2]));
  return {e.x, e.y, e.z};
}

}  // namespace shadetwin
