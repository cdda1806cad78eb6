// The shadow-map passes on a Vulkan device: a depth-only graphics pipeline (src/shaders/shadow.vert,
// the shared shade/shadow.h, no fragment shader), one render pass per direction into one D32F
// target, each copied out before the next direction's pass; all directions in one submission.
#include <chrono>
#include <cstring>

#include "passes/passes_vk.h"

namespace shadetwin {
namespace {
#include "shadow_vert.inc"

struct ShadowPush {
  float lightViewProj[16];
  uint32_t object;
};
static_assert(sizeof(ShadowPush) == 68, "ShadowPush must match the push block of shadow.vert");

vk::GraphicsPassDesc shadowDesc(uint32_t size) {
  vk::GraphicsPassDesc d;
  d.name = "shadow-map pass";
  d.width = d.height = size;
  d.vertexSpirv = kSpv_shadow_vert;
  d.vertexStride = sizeof(VertexGpu);
  d.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  d.storageBuffers = 1;  // objects
  d.pushBytes = sizeof(ShadowPush);
  return d;
}
}  // namespace

ShadowPassVk::ShadowPassVk(vk::Context& ctx, const Scene& scene, uint32_t size)
    : ctx_(ctx), scene_(scene), size_(size), gpu_(ctx, scene), pass_(ctx, shadowDesc(size)) {
  const VkBuffer bufs[1] = {gpu_.objects->handle()};
  pass_.bindBuffers(bufs);
}

ShadowMaps ShadowPassVk::run(const std::vector<Vec3>& directions) {
  ShadowMaps sm;
  sm.size = size_;
  sm.directions = directions;
  for (const Vec3& d : directions) sm.viewProj.push_back(shadowViewProjection(scene_, d));
  const VkDeviceSize mapBytes = VkDeviceSize(size_) * size_ * 4;
  if (!readback_ || readback_->size() < mapBytes * directions.size())
    readback_ = std::make_unique<vk::Buffer>(ctx_, std::max<VkDeviceSize>(mapBytes * directions.size(), 4));
  auto t0 = std::chrono::steady_clock::now();
  ctx_.submit([&](VkCommandBuffer cmd) {
    for (size_t di = 0; di < directions.size(); ++di) {
      pass_.begin(cmd);
      gpu_.drawObjects(cmd, scene_, [&](uint32_t oi) {
        ShadowPush push;
        std::memcpy(push.lightViewProj, sm.viewProj[di].data(), 64);
        push.object = oi;
        pass_.pushConstants(cmd, &push);
      });
      pass_.end(cmd);
      pass_.copyOut(cmd, -1, readback_->handle(), di * mapBytes);
    }
    vk::GraphicsPass::hostBarrier(cmd);
  });
  lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  sm.maps.resize(directions.size());
  for (size_t di = 0; di < directions.size(); ++di) {
    sm.maps[di].resize(size_t(size_) * size_);
    std::memcpy(sm.maps[di].data(), readback_->as<uint8_t>() + di * mapBytes, mapBytes);
  }
  return sm;
}

}  // namespace shadetwin
