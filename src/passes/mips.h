// MIP chain generation with the shared kernel (src/shade/mip.h): on the CPU (scalar or SIMD build)
// and on a Vulkan device (src/shaders/mip_downsample.glsl). Both produce the same bits, so an
// emulated texture and the GPU's texture hold the same chain.
#pragma once
#include <cstdint>
#include <vector>

#include "emu/texture.h"

namespace shadetwin {
namespace vk { class Context; }

/// Float4 texels (layer-major, rows) of level 0 -> every level down to 1x1 (levels[0] = the input).
/// lanes = 1: scalar build; 8: SIMD build; 0: the SIMD driver over the counting lane types (model/pass_counts.h,
/// the same bits, operations counted on the calling thread). Throws std::invalid_argument on zero sizes or a wrong size.
std::vector<std::vector<float>> mipChainCpu(const std::vector<float>& level0, uint32_t width, uint32_t height,
                                            uint32_t layers, int lanes = 8);
std::vector<std::vector<float>> mipChainGpu(vk::Context& ctx, const std::vector<float>& level0, uint32_t width,
                                            uint32_t height, uint32_t layers);

/// Packs float4 levels into a texture of the given format (conversion on the host, exact and defined:
/// f16 round-to-nearest-even, unorm8 = rint(clamp(x, 0, 1) * 255) with NaN -> 0, r32f takes red).
emu::Texture packTexture(emu::Format format, uint32_t width, uint32_t height, uint32_t layers,
                         const std::vector<std::vector<float>>& levels);

}  // namespace shadetwin
