// The deferred shading pass, emulated: the technique's shared source (src/shade/shade_*.h) in its
// 8-lane C++ build over the G-buffer, compute stage, TBB over blocks of pixels. The Vulkan side of the
// same pass is ShadePassVk (passes/passes_vk.h, passes/shade_vk.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "emu/device_profile.h"
#include "emu/texture.h"
#include "inputs/shade_inputs.h"
#include "lanes/sampler_bridge.h"
#include "passes/gbuffer.h"
#include "scene/scene.h"

namespace shadetwin {

struct VisibilityImage;  // passes/visibility.h

/// Camera basis for primary rays (shade/shade_mirror.h cameraRay), from the scene on the host.
struct CameraRays {
  float eye[3], fwd[3], right[3], down[3];
};
CameraRays cameraRays(const Scene& scene);

/// Emulated deferred shading pass: compute stage, 8 lanes per device vector (SIMD build of the
/// technique's shared source), TBB over blocks. Returns RGBA floats per pixel. `in`: what the
/// technique reads from the environment (inputs/shade_inputs.h), built by either build.
/// vis: the frame's SH visibility fit of this G-buffer (passes/visibility.h) for fis with a
/// "visibility" block; nullptr shades without visibility.
std::vector<float> shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
                            const VisibilityImage* vis = nullptr);
/// Same, into `out` (resized to 4 floats per pixel, storage reused).
void shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
              std::vector<float>& out, const VisibilityImage* vis = nullptr);

/// Emulated sampler of an environment texture: trilinear, clamp in v, repeat (equirectangular map) or
/// clamp (paraboloid atlas) in u; the emulator's side of environmentSamplerInfo (passes/passes_vk.h).
shade::Sampler2D environmentSampler(const emu::Texture& tex, const emu::DeviceProfile& dev, bool repeatU);
/// Emulated sampler of the material maps (inputs/material.h): trilinear, repeat in u and v; the
/// emulator's side of materialMapSamplerInfo (passes/shade_vk.cpp).
shade::Sampler2D materialMapSampler(const emu::Texture& tex, const emu::DeviceProfile& dev);

/// Mode of the FIS pass for the scene's technique (kFisFiltered / kFisUnfiltered / kFisStochastic).
uint32_t fisMode(const Scene& scene);

/// The glints pass's uniform settings (shade/shade_glints.h GlintSettings, field for field; the
/// start of the push block of shade_glints.comp).
struct GlintUniforms {
  uint32_t order, rings, sectors, mapW, mapH;
  float invW, invH;
  uint32_t viewRings, viewSectors;
  uint32_t lobeRings, lobeSectors;
};
static_assert(sizeof(GlintUniforms) == 44, "GlintUniforms must match shade_glints.h GlintSettings (std430, binding 4 of shade_glints.comp)");
GlintUniforms glintUniforms(const GlintInputs& in);

/// log2(K w h / N) of the FIS level formula for the scene's settings (w h = S^2 texels per face).
float fisLevelConstant(const Scene& scene);

}  // namespace shadetwin
