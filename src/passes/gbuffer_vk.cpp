// The G-buffer pass on a Vulkan device: one graphics pipeline (src/shaders/gbuffer.vert/.frag, the
// shared shade/gbuffer.h), four RGBA32F attachments + D32F, one indexed draw per object, read back.
#include <chrono>
#include <cstring>
#include <memory>

#include "passes/passes_vk.h"

namespace shadetwin {
namespace {
#include "gbuffer_frag.inc"
#include "gbuffer_vert.inc"

vk::GraphicsPassDesc gbufferDesc(const Scene& scene) {
  vk::GraphicsPassDesc d;
  d.name = "G-buffer pass";
  d.width = scene.width;
  d.height = scene.height;
  d.colorFormats.assign(kGbufAttachments, VK_FORMAT_R32G32B32A32_SFLOAT);
  d.vertexSpirv = kSpv_gbuffer_vert;
  d.fragmentSpirv = kSpv_gbuffer_frag;
  d.vertexStride = sizeof(VertexGpu);
  d.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                  {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12},
                  {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 24},
                  {3, 0, VK_FORMAT_R32G32_SFLOAT, 40}};
  d.storageBuffers = 2;  // objects, frame (view-projection)
  d.pushBytes = 4;       // object index
  return d;
}
}  // namespace

SceneGpu::SceneGpu(vk::Context& ctx, const Scene& scene) {
  for (const Mesh& m : scene.meshes) {
    auto v = interleave(m);
    vertices.push_back(std::make_unique<vk::Buffer>(ctx, v.size() * sizeof(VertexGpu), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
    std::memcpy(vertices.back()->data(), v.data(), v.size() * sizeof(VertexGpu));
    indices.push_back(std::make_unique<vk::Buffer>(ctx, m.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT));
    std::memcpy(indices.back()->data(), m.indices.data(), m.indices.size() * 4);
  }
  objects = std::make_unique<vk::Buffer>(ctx, scene.objects.size() * sizeof(ObjectGpu));
  for (size_t i = 0; i < scene.objects.size(); ++i) objects->as<ObjectGpu>()[i] = objectGpu(scene.objects[i]);
}

void SceneGpu::drawObjects(VkCommandBuffer cmd, const Scene& scene, const std::function<void(uint32_t)>& push) const {
  for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
    const Object& o = scene.objects[oi];
    VkBuffer vbh = vertices[o.mesh]->handle();
    VkDeviceSize off = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vbh, &off);
    vkCmdBindIndexBuffer(cmd, indices[o.mesh]->handle(), 0, VK_INDEX_TYPE_UINT32);
    push(oi);
    vkCmdDrawIndexed(cmd, uint32_t(scene.meshes[o.mesh].indices.size()), 1, 0, 0, 0);
  }
}

GbufferPassVk::GbufferPassVk(vk::Context& ctx, const Scene& scene)
    : ctx_(ctx), scene_(scene), gpu_(ctx, scene), frame_(ctx, 64), pass_(ctx, gbufferDesc(scene)) {
  const Mat4 vp = scene.viewProjection();
  std::memcpy(frame_.data(), vp.data(), 64);
  const VkBuffer bufs[2] = {gpu_.objects->handle(), frame_.handle()};
  pass_.bindBuffers(bufs);
  const size_t px = size_t(scene.width) * scene.height;
  for (int i = 0; i < kGbufAttachments; ++i) readback_.push_back(std::make_unique<vk::Buffer>(ctx, px * 16));
  readback_.push_back(std::make_unique<vk::Buffer>(ctx, px * 4));
}

GBuffer GbufferPassVk::run() {
  const uint32_t W = scene_.width, H = scene_.height;
  auto t0 = std::chrono::steady_clock::now();
  ctx_.submit([&](VkCommandBuffer cmd) {
    pass_.begin(cmd);
    gpu_.drawObjects(cmd, scene_, [&](uint32_t oi) { pass_.pushConstants(cmd, &oi); });
    pass_.end(cmd);
    for (int i = 0; i < kGbufAttachments; ++i) pass_.copyOut(cmd, i, readback_[size_t(i)]->handle(), 0);
    pass_.copyOut(cmd, -1, readback_[kGbufAttachments]->handle(), 0);
    vk::GraphicsPass::hostBarrier(cmd);
  });
  lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  GBuffer g;
  g.width = W;
  g.height = H;
  g.texels.resize(size_t(W) * H * kGbufFloats);
  g.depth.resize(size_t(W) * H);
  for (int a = 0; a < kGbufAttachments; ++a) {
    const float* src = readback_[size_t(a)]->as<float>();
    for (size_t p = 0; p < size_t(W) * H; ++p) std::memcpy(&g.texels[p * kGbufFloats + size_t(4 * a)], src + 4 * p, 16);
  }
  std::memcpy(g.depth.data(), readback_[kGbufAttachments]->data(), g.depth.size() * 4);
  return g;
}

GBuffer gbufferVulkan(vk::Context& ctx, const Scene& scene) { return GbufferPassVk(ctx, scene).run(); }

}  // namespace shadetwin
