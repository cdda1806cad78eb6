// The dual-paraboloid environment atlas of filtered importance sampling (shade/paraboloid.h): the
// equirectangular map resampled by one shared kernel, on the emulator or on a Vulkan device (same
// bits), then its MIP chain by the shared downsampling kernel (src/passes/mips.h). Rebuilt whenever the
// environment changes.
#pragma once
#include <cstdint>
#include <vector>

#include "emu/device_profile.h"
#include "emu/texture.h"

namespace shadetwin {
namespace vk { class Context; }

/// Level 0 of the atlas (2S x S float4 texels, rows) resampled from `env` (RGBA32F with its MIP
/// chain) on the emulator (8-lane SIMD build, TBB rows). Sampler: repeat in u, clamp in v, trilinear.
std::vector<float> paraboloidAtlasEmu(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize);
/// The same driver over the counting lane types (model/pass_counts.h): the same bits, operations counted on the
/// calling thread's counters (the caller keeps it on one thread).
std::vector<float> paraboloidAtlasCounted(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize);

/// The same kernel (src/shaders/paraboloid_resample.comp) on a Vulkan device.
std::vector<float> paraboloidAtlasVulkan(vk::Context& ctx, const emu::Texture& env, uint32_t faceSize);

/// The whole atlas (level 0 and its MIP chain, RGBA32F) built by the emulator (SIMD build) ...
emu::Texture paraboloidTextureEmu(const emu::Texture& env, const emu::DeviceProfile& dev, uint32_t faceSize);

/// ... and by the Vulkan device: resampling kernel and MIP chain on the GPU (the same bits).
emu::Texture paraboloidTextureVulkan(vk::Context& ctx, const emu::Texture& env, uint32_t faceSize);

}  // namespace shadetwin
