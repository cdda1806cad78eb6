// What a technique's shading pass reads besides the G-buffer, built from the environment by one
// build (emulator or Vulkan device): mirror reads the equirectangular map itself; fis reads the
// dual-paraboloid atlas (inputs/paraboloid.h) and the SH irradiance (inputs/sh_irradiance.h); env
// reads the equirectangular map (background) and its light list (inputs/env_lights.h); the MIS
// techniques read the map and their sampler's tables (inputs/env_sampling.h).
// A technique's inputs are built only when it needs them.
#pragma once
#include <cstdint>
#include <memory>

#include "emu/device_profile.h"
#include "emu/texture.h"
#include "inputs/env_lights.h"
#include "inputs/env_sampling.h"
#include "inputs/glints.h"
#include "inputs/sh_irradiance.h"
#include "inputs/visibility.h"
#include "scene/scene.h"

namespace shadetwin {
namespace vk { class Context; }

struct ShadeInputs {
  const emu::Texture* environment = nullptr;  // equirectangular, RGBA32F with its MIP chain
  std::shared_ptr<const emu::Texture> atlas;  // fis: dual-paraboloid atlas with its MIP chain
  ShIrradiance sh;                            // fis: E/pi coefficients
  EnvLights lights;                           // env: directional lights (host-sampled, the same for both builds)
  std::shared_ptr<const EnvSamplingTables> envTables;  // *-mis: the environment sampler's tables (host-built)
  std::shared_ptr<const emu::Texture> maps;   // fis, env: material maps (inputs/material.h), a 1x1 white layer if none
  std::shared_ptr<const VisibilitySetup> visibility;  // fis with a "visibility" block: directions, matrices, fit weights
  std::array<float, 48> visLighting{};        // ... and the raw order-4 lighting SH (inputs/visibility.h)
  std::shared_ptr<const GlintInputs> glints;  // glints: SATs, bins, material rows, lighting table (inputs/glints.h)
  double atlasMs = 0, shMs = 0;               // build times (0 when not built)
  /// The texture the shading kernel samples: the atlas for fis, else the environment.
  const emu::Texture& texture() const { return atlas ? *atlas : *environment; }
};

ShadeInputs shadeInputsEmu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev);
ShadeInputs shadeInputsVulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env);

/// What the technique inputs depend on: the environment's level-0 texels (FNV-1a over their bytes),
/// its size, and the scene settings that shape them (technique, intensity-free: face size, sample
/// count of env's lights, map files). Equal keys give bit-identical inputs.
uint64_t shadeInputsKey(const Scene& scene, const emu::Texture& env);

/// Technique inputs across frames: rebuilt (atlas with its MIP chain, SH, lights, maps) on the frame
/// whose environment or settings changed, reused otherwise. One per build.
class ShadeInputsCache {
 public:
  const ShadeInputs& emu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev);
  const ShadeInputs& vulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env);
  uint32_t builds() const { return builds_; }     // rebuilds so far
  bool lastRebuilt() const { return rebuilt_; }   // did the last call rebuild?

 private:
  template <class Build> const ShadeInputs& get(const Scene& scene, const emu::Texture& env, Build build);
  bool have_ = false, rebuilt_ = false;
  uint64_t key_ = 0;
  uint32_t builds_ = 0;
  ShadeInputs in_;
};

}  // namespace shadetwin
