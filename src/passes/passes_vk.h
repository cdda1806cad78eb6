// The deferred pipeline's passes on a Vulkan device, each built once (pipelines, targets, buffers)
// and run many times: the G-buffer pass, the shadow-map passes and the shading pass. Each run()
// records, submits, waits, reads back, and records the wall time of the submission in lastMs.
#pragma once
#include <span>
#include <functional>
#include <memory>
#include <vector>

#include "passes/shade.h"
#include "passes/shadow.h"
#include "vk/context.h"
#include "vk/graphics_pass.h"

namespace shadetwin {

struct VisibilityImage;  // passes/visibility.h

/// The scene's geometry and per-object data in device buffers.
struct SceneGpu {
  SceneGpu(vk::Context& ctx, const Scene& scene);
  std::vector<std::unique_ptr<vk::Buffer>> vertices, indices;  // per mesh
  std::unique_ptr<vk::Buffer> objects;                         // ObjectGpu per object
  /// Records one indexed draw per object, in scene order; `push(oi)` records the object's push
  /// constants before its draw.
  void drawObjects(VkCommandBuffer cmd, const Scene& scene, const std::function<void(uint32_t)>& push) const;
};

class GbufferPassVk {
 public:
  GbufferPassVk(vk::Context& ctx, const Scene& scene);
  GBuffer run();
  double lastMs = 0;

 private:
  vk::Context& ctx_;
  const Scene& scene_;
  SceneGpu gpu_;
  vk::Buffer frame_;
  vk::GraphicsPass pass_;
  std::vector<std::unique_ptr<vk::Buffer>> readback_;
};

class ShadowPassVk {
 public:
  ShadowPassVk(vk::Context& ctx, const Scene& scene, uint32_t size);
  ShadowMaps run(const std::vector<Vec3>& directions);
  double lastMs = 0;

 private:
  vk::Context& ctx_;
  const Scene& scene_;
  uint32_t size_;
  SceneGpu gpu_;
  vk::GraphicsPass pass_;
  std::unique_ptr<vk::Buffer> readback_;
};

/// The shading pass as a compute shader (src/shaders/shade_mirror.comp, the shared shade_mirror.h),
/// one invocation per pixel in row-major order, local size 64, over a G-buffer uploaded from the host.
/// Sampler state of an environment texture, the same as the emulator's: trilinear, clamp in v,
/// repeat (equirectangular map) or clamp (paraboloid atlas) in u.
VkSamplerCreateInfo environmentSamplerInfo(bool repeatU);
/// A table the shaders read with texelFetch (inputs/env_sampling.h): an R32F or RGBA32F texture as a
/// one-level 2D image, and its sampler (nearest: no filtering is involved).
std::unique_ptr<vk::Image> dataTextureImage(vk::Context& ctx, const emu::Texture& t);
VkSamplerCreateInfo dataTextureSamplerInfo();
/// The SPIR-V module ShadePassVk runs for `technique` (the performance model's code-size and loop-state terms).
std::span<const uint32_t> shadeModule(const std::string& technique);

class ShadePassVk {
 public:
  /// in: the technique's inputs (either build's), sampled with the emulator's sampler state.
  ShadePassVk(vk::Context& ctx, const Scene& scene, const ShadeInputs& in);
  ~ShadePassVk();
  /// vis: the frame's SH visibility fit of `g` (fis with a "visibility" block), or nullptr.
  std::vector<float> run(const GBuffer& g, const VisibilityImage* vis = nullptr);
  double lastMs = 0;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Convenience: the G-buffer pass built, run once and torn down.
GBuffer gbufferVulkan(vk::Context& ctx, const Scene& scene);

}  // namespace shadetwin
