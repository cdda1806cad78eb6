// Order-3 SH irradiance of an environment (shade/sh_irradiance.h): the projection kernel (one
// invocation per row) and the pairwise-tree reduction, on the emulator or on a Vulkan device, with
// the same bits. The result is what the fis shading pass reads for its diffuse term.
#pragma once
#include <array>
#include <functional>

#include "emu/device_profile.h"
#include "emu/texture.h"

namespace shadetwin {
namespace vk { class Context; }

/// E/pi coefficients: c[3 k + channel], k in the order of shade/sh_irradiance.h (Y00, Y1-1, Y10,
/// Y11, Y2-2, Y2-1, Y20, Y21, Y22), band scale A_l / pi already applied.
struct ShIrradiance {
  std::array<float, 27> c{};
  std::array<float, 21> band3{};  // raw radiance L_3m, band3[3 (k - 9) + channel], k = 9..15 (shade/sh16.h)
};

/// On the emulator: rows in 8-lane vectors (SIMD build), TBB over vectors, then the tree (scalar
/// build) in the device's compute-stage denormal mode. `env`: RGBA32F, level 0 is read.
ShIrradiance shIrradianceEmu(const emu::Texture& env, const emu::DeviceProfile& dev);
/// The same drivers over the counting lane types (model/pass_counts.h): the same bits, operations counted on the
/// calling thread; `between` runs after the projection pass, before the reduction.
ShIrradiance shIrradianceCounted(const emu::Texture& env, const emu::DeviceProfile& dev, const std::function<void()>& between);

/// On a Vulkan device: src/shaders/sh_project.comp then src/shaders/sh_reduce.comp.
ShIrradiance shIrradianceVulkan(vk::Context& ctx, const emu::Texture& env);

/// E(n)/pi (clamped at 0) for a unit normal, scalar build of the shading pass's evaluation.
std::array<float, 3> shIrradianceAt(const ShIrradiance& sh, const std::array<float, 3>& n);

}  // namespace shadetwin
