// One graphics pipeline with its render pass, attachments and descriptor set, built once and
// recorded many times: the G-buffer pass (4 x RGBA32F + D32F) and the shadow-map passes (D32F only)
// both use it. Vertex input is one interleaved binding; descriptors are storage buffers 0..n-1
// visible to both stages; push constants are visible to both stages.
#pragma once
#include <memory>
#include <span>
#include <vector>

#include "vk/context.h"

namespace shadetwin::vk {

struct GraphicsPassDesc {
  uint32_t width = 0, height = 0;
  std::vector<VkFormat> colorFormats;  // may be empty (depth-only pass)
  std::span<const uint32_t> vertexSpirv, fragmentSpirv;  // fragment may be empty (depth-only)
  uint32_t vertexStride = 0;
  std::vector<VkVertexInputAttributeDescription> attributes;
  uint32_t storageBuffers = 0;
  uint32_t pushBytes = 0;
  const char* name = "graphics pass";  // for error messages
};

class GraphicsPass {
 public:
  GraphicsPass(Context& ctx, const GraphicsPassDesc& desc);
  ~GraphicsPass();
  GraphicsPass(const GraphicsPass&) = delete;
  GraphicsPass& operator=(const GraphicsPass&) = delete;

  /// Points descriptor binding i at buffers[i] (whole buffer).
  void bindBuffers(std::span<const VkBuffer> buffers);
  /// Begins the render pass (colors cleared to 0, depth to 1) and binds the pipeline and set.
  void begin(VkCommandBuffer cmd) const;
  void pushConstants(VkCommandBuffer cmd, const void* data) const;
  void end(VkCommandBuffer cmd) const;
  /// After end(): copies color attachment i (or the depth attachment, i = -1) to dst at offset, tightly packed.
  void copyOut(VkCommandBuffer cmd, int attachment, VkBuffer dst, VkDeviceSize offset) const;
  /// After the last copyOut: makes the transfers visible to the host.
  static void hostBarrier(VkCommandBuffer cmd);

 private:
  Context& ctx_;
  GraphicsPassDesc desc_;
  std::vector<std::unique_ptr<RenderTarget>> color_;
  std::unique_ptr<RenderTarget> depth_;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace shadetwin::vk
