#include "inputs/env_sampling_speed.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

#include "passes/shade.h"
#include "passes/passes_vk.h"
#include "util/timer.h"
#include "vk/context.h"

namespace shadetwin {
namespace {
#include "env_sampling_speed_comp.inc"

template <class F>
double bestMs(int repeats, F&& f) {
  f();  // warm-up
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) best = std::min(best, timeMs(f));
  return best;
}
}  // namespace

SamplerSpeed envSamplerSpeed(const EnvSamplingTables& T, const emu::DeviceProfile& dev, vk::Context* ctx,
                             uint32_t streams, uint32_t perStream, int repeats) {
  SamplerSpeed r;
  const shade::Sampler2D table = environmentSampler(*T.table, dev, false),
                         texels = environmentSampler(*T.texels, dev, false);
  const EnvSamplingUniforms& u = T.uniforms;
  const double total = double(streams) * perStream;
  std::vector<float> out(streams);
  {
    const auto es = toEnvSampling<shade::scalar::EnvSampling>(u);
    const double ms = bestMs(repeats, [&] {
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, streams, 64), [&](const tbb::blocked_range<uint32_t>& b) {
        for (uint32_t i = b.begin(); i != b.end(); ++i)
          out[i] = shade::scalar::envSamplingChecksum(table, texels, es, i, perStream, 1u);
      });
    });
    r.scalar = total / (ms * 1e-3);
    for (float v : out) r.checksumScalar += v;
  }
  {
    const auto es = toEnvSampling<shade::x8::EnvSampling>(u);
    const double ms = bestMs(repeats, [&] {
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, (streams + 7) / 8, 8),
                        [&](const tbb::blocked_range<uint32_t>& b) {
                          for (uint32_t g = b.begin(); g != b.end(); ++g) {
                            emu::U32<8> idx;
                            for (int l = 0; l < 8; ++l) idx.set(l, std::min(g * 8 + uint32_t(l), streams - 1));
                            const emu::F32<8> s = shade::x8::envSamplingChecksum(table, texels, es, idx, perStream, 1u);
                            for (int l = 0; l < 8 && g * 8 + uint32_t(l) < streams; ++l)
                              out[g * 8 + uint32_t(l)] = s[l];
                          }
                        });
    });
    r.simd = total / (ms * 1e-3);
    for (float v : out) r.checksumSimd += v;
  }
  r.vulkan = NAN;
  if (ctx) {
    const auto tImg = dataTextureImage(*ctx, *T.table), xImg = dataTextureImage(*ctx, *T.texels);
    const vk::Sampler sampler(*ctx, dataTextureSamplerInfo());
    vk::Buffer settings(*ctx, sizeof(EnvSamplingUniforms)), sums(*ctx, size_t(streams) * 4);
    std::memcpy(settings.data(), &u, sizeof u);
    const VkDescriptorType layout[4] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                        VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    vk::Kernel k(*ctx, vk::Stage::Compute, kSpv_env_sampling_speed_comp, layout, 16);
    const vk::Binding b[4] = {
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, tImg->view(), sampler.handle()},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, xImg->view(), sampler.handle()},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, settings.handle()},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, sums.handle()}};
    const uint32_t push[4] = {streams, perStream, 1u, 0u};
    const double ms = bestMs(repeats, [&] { k.run(b, push, streams); });
    r.vulkan = total / (ms * 1e-3);
    const float* s = sums.as<float>();
    for (uint32_t i = 0; i < streams; ++i) r.checksumVulkan += s[i];
  }
  return r;
}

}  // namespace shadetwin
