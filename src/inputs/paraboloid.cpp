#include "inputs/paraboloid.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "passes/mips.h"
#include "lanes/instantiate.h"
#include "model/counted.h"
#include "util/pass_log.h"
#include "passes/shade.h"
#include "passes/passes_vk.h"
#include "vk/context.h"

namespace shadetwin {
namespace {
#include "paraboloid_resample_comp.inc"

struct ResamplePush {
  float envW, envH;
  int32_t faceSize;
  uint32_t count;
};
static_assert(sizeof(ResamplePush) == 16, "ResamplePush must match the push block of paraboloid_resample.comp");

void checkInputs(const emu::Texture& env, uint32_t faceSize) {
  if (env.format() != emu::Format::RGBA32F) throw std::invalid_argument("paraboloid atlas: the environment must be RGBA32F");
  if (faceSize < 4 || faceSize > 8192)
    throw std::invalid_argument("paraboloid atlas: face size " + std::to_string(faceSize) + " outside [4, 8192]");
}

// The emulator's driver over either lane build (an instantiation namespace of lanes/instantiate.h or
// model/counted.h): the SIMD build (the emulator) or the counting one (the model).
#define PARABOLOID_LANES(Name, NS)                                                          \
  struct Name {                                                                             \
    using Float = shade::NS::Float;                                                         \
    using Int = shade::NS::Int;                                                             \
    static auto resample(auto&&... a) { return shade::NS::paraboloidResample(a...); }       \
  };
PARABOLOID_LANES(X8Lanes, x8)
PARABOLOID_LANES(CountedLanes, counted)
#undef PARABOLOID_LANES

template <class L>
std::vector<float> paraboloidAtlasLanes(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize) {
  using F = typename L::Float;
  using I = typename L::Int;
  const size_t w = 2 * size_t(faceSize), n = w * faceSize;
  std::vector<float> out(4 * n);
  const shade::Sampler2D s = environmentSampler(env, dev, true);
  const F ew(float(env.width())), eh(float(env.height()));
  const size_t blocks = (n + 7) / 8;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks, 64), [&](const tbb::blocked_range<size_t>& r) {
    emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      I xi, yi;
      for (int l = 0; l < 8; ++l) {
        const size_t p = std::min(b * 8 + size_t(l), n - 1);  // tail lanes repeat the last texel, as the GPU
        xi.set(l, int32_t(p % w));
        yi.set(l, int32_t(p / w));
      }
      const shade::V4<F> c = L::resample(s, ew, eh, xi, yi, I(int32_t(faceSize)));
      for (int l = 0; l < 8 && b * 8 + size_t(l) < n; ++l) {
        float* o = &out[4 * (b * 8 + size_t(l))];
        o[0] = c.x[l], o[1] = c.y[l], o[2] = c.z[l], o[3] = c.w[l];
      }
    }
  });
  return out;
}

}  // namespace

std::vector<float> paraboloidAtlasEmu(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize) {
  checkInputs(env, faceSize);
  notePass("paraboloid");
  return paraboloidAtlasLanes<X8Lanes>(env, dev, faceSize);
}

std::vector<float> paraboloidAtlasCounted(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize) {
  checkInputs(env, faceSize);
  return paraboloidAtlasLanes<CountedLanes>(env, dev, faceSize);
}

std::vector<float> paraboloidAtlasVulkan(vk::Context& ctx, const emu::Texture& env, uint32_t faceSize) {
  checkInputs(env, faceSize);
  const size_t n = 2 * size_t(faceSize) * faceSize;
  vk::Image img(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, env.width(), env.height(), 1, env.levels(), 16, VK_IMAGE_VIEW_TYPE_2D);
  vk::Sampler sampler(ctx, environmentSamplerInfo(true));
  vk::Buffer out(ctx, n * 16);
  static constexpr VkDescriptorType kLayout[2] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel kernel(ctx, vk::Stage::Compute, kSpv_paraboloid_resample_comp, kLayout, sizeof(ResamplePush));
  ResamplePush push{float(env.width()), float(env.height()), int32_t(faceSize), uint32_t(n)};
  const vk::Binding b[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, img.view(), sampler.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out.handle()}};
  kernel.run(b, &push, uint32_t(n));
  std::vector<float> texels(4 * n);
  std::memcpy(texels.data(), out.data(), texels.size() * 4);
  return texels;
}

emu::Texture paraboloidTextureEmu(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize) {
  const std::vector<float> level0 = paraboloidAtlasEmu(env, dev, faceSize);
  notePass("mips");  // a device pass on the Vulkan build (mipChainGpu)
  const auto chain = mipChainCpu(level0, 2 * faceSize, faceSize, 1, 8);
  return packTexture(emu::Format::RGBA32F, 2 * faceSize, faceSize, 1, chain);
}

emu::Texture paraboloidTextureVulkan(vk::Context& ctx, const emu::Texture& env, uint32_t faceSize) {
  const auto chain = mipChainGpu(ctx, paraboloidAtlasVulkan(ctx, env, faceSize), 2 * faceSize, faceSize, 1);
  return packTexture(emu::Format::RGBA32F, 2 * faceSize, faceSize, 1, chain);
}

}  // namespace shadetwin
