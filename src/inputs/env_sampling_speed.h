// Throughput of the environment samplers (issue 5, item 5): directions drawn per second, each with
// the pdf lookup of its direction (what one MIS sample pair asks of the sampler), by the C++ scalar
// and 8-lane builds of shade/env_sampling.h (TBB over every core) and by a Vulkan device
// (src/shaders/env_sampling_speed.comp), so their ratios come from one run on one machine.
#pragma once
#include <cstdint>

#include "emu/device_profile.h"
#include "inputs/env_sampling.h"

namespace shadetwin {
namespace vk {
class Context;
}

struct SamplerSpeed {
  double scalar = 0, simd = 0, vulkan = 0;                          // samples per second (vulkan: NaN without a device)
  double checksumScalar = 0, checksumSimd = 0, checksumVulkan = 0;  // the sum of the probe's outputs
};

/// `streams` independent streams of `perStream` samples each; best of `repeats` timed runs after a
/// warm-up. ctx may be null.
SamplerSpeed envSamplerSpeed(const EnvSamplingTables& T, const emu::DeviceProfile& dev, vk::Context* ctx,
                             uint32_t streams, uint32_t perStream, int repeats = 3);

}  // namespace shadetwin
