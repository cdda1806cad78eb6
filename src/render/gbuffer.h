// The G-buffer pass, both builds: the emulator (emu/raster.h + the C++ instantiation of
// shade/gbuffer.h) and the Vulkan graphics pipeline (src/shaders/gbuffer.vert/.frag).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "emu/device_profile.h"
#include "emu/raster.h"
#include "emu/texture.h"
#include "render/shade_inputs.h"
#include "shade/sampler_bridge.h"
#include "scene/scene.h"

namespace shadetwin {

inline constexpr int kGbufAttachments = 4;
inline constexpr int kGbufFloats = 4 * kGbufAttachments;  // floats per pixel
inline constexpr int kGbufVaryings = 12;                  // world pos 3, normal 3, tangent 4, uv 2

struct GBuffer {
  uint32_t width = 0, height = 0;
  std::vector<float> texels;  // kGbufFloats per pixel: G0 G1 G2 G3, rows top to bottom
  std::vector<float> depth;   // D32F
  const float* at(uint32_t x, uint32_t y) const { return texels.data() + (size_t(y) * width + x) * kGbufFloats; }
};

/// Per-object data as the GPU reads it (std430): model and normal matrices, material id.
struct ObjectGpu {
  float model[16];
  float normal[16];
  float materialId;
  float pad[3];
};
static_assert(sizeof(ObjectGpu) == 144, "ObjectGpu must match the std430 layout of gbuffer.vert");

/// Interleaved vertex as the GPU reads it: position, normal, tangent, uv.
struct VertexGpu {
  float pos[3], normal[3], tangent[4], uv[2];
};
static_assert(sizeof(VertexGpu) == 48, "VertexGpu must match the vertex input layout of gbuffer.vert");

std::vector<VertexGpu> interleave(const Mesh& m);
ObjectGpu objectGpu(const Object& o);

struct GbufferStats {
  emu::RasterStats raster;
  double vertexMs = 0, rasterMs = 0;
};

/// Emulated G-buffer pass (every object one draw, in scene order) into `target`, whose storage is
/// reused when it is large enough (cleared like a GPU's attachments).
void gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GBuffer& target, GbufferStats* stats = nullptr);
GBuffer gbufferEmu(const Scene& scene, const emu::DeviceProfile& dev, GbufferStats* stats = nullptr);

/// Camera basis for primary rays (shade/shade_mirror.h cameraRay), from the scene on the host.
struct CameraRays {
  float eye[3], fwd[3], right[3], down[3];
};
CameraRays cameraRays(const Scene& scene);

/// Emulated deferred shading pass: compute stage, 8 lanes per device vector (SIMD build of the
/// technique's shared source), TBB over blocks. Returns RGBA floats per pixel. `in`: what the
/// technique reads from the environment (render/shade_inputs.h), built by either build.
std::vector<float> shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev);
/// Same, into `out` (resized to 4 floats per pixel, storage reused).
void shadeEmu(const Scene& scene, const GBuffer& g, const ShadeInputs& in, const emu::DeviceProfile& dev,
              std::vector<float>& out);

/// Emulated sampler of an environment texture: trilinear, clamp in v, repeat (equirectangular map) or
/// clamp (paraboloid atlas) in u; the emulator's side of environmentSamplerInfo (render/passes_vk.h).
shade::Sampler2D environmentSampler(const emu::Texture& tex, const emu::DeviceProfile& dev, bool repeatU);
/// Emulated sampler of the material maps (render/material.h): trilinear, repeat in u and v; the
/// emulator's side of materialMapSamplerInfo (render/shade_vk.cpp).
shade::Sampler2D materialMapSampler(const emu::Texture& tex, const emu::DeviceProfile& dev);

/// Mode of the FIS pass for the scene's technique (kFisFiltered / kFisUnfiltered / kFisStochastic).
uint32_t fisMode(const Scene& scene);

/// log2(K w h / N) of the FIS level formula for the scene's settings (w h = S^2 texels per face).
float fisLevelConstant(const Scene& scene);

}  // namespace shadetwin
