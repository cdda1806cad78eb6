// The G-buffer pass, both builds: the emulator (emu/raster.h + the C++ instantiation of
// shade/gbuffer.h) and the Vulkan graphics pipeline (src/shaders/gbuffer.vert/.frag).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "emu/device_profile.h"
#include "emu/raster.h"
#include "emu/texture.h"
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
/// The same pass over the counting lane types (model/pass_counts.h): the same bits, operations counted on the calling
/// thread (which must keep the work on itself: the stages run through tbb::parallel_for).
GBuffer gbufferCounted(const Scene& scene, const emu::DeviceProfile& dev, GbufferStats* stats = nullptr);

}  // namespace shadetwin
