#include "vk/graphics_pass.h"

#include <string>

namespace shadetwin::vk {

GraphicsPass::GraphicsPass(Context& ctx, const GraphicsPassDesc& desc) : ctx_(ctx), desc_(desc) {
  VkDevice dev = ctx.device();
  const std::string name = desc.name;
  auto what = [&](const char* call) { return call + ("(" + name + ")"); };
  const uint32_t nc = uint32_t(desc.colorFormats.size());
  for (VkFormat f : desc.colorFormats) color_.push_back(std::make_unique<RenderTarget>(ctx, f, desc.width, desc.height, false));
  depth_ = std::make_unique<RenderTarget>(ctx, VK_FORMAT_D32_SFLOAT, desc.width, desc.height, true);

  std::vector<VkAttachmentDescription> ad(nc + 1);
  std::vector<VkAttachmentReference> refs(nc);
  for (uint32_t i = 0; i <= nc; ++i) {
    ad[i] = {};
    ad[i].format = i < nc ? desc.colorFormats[i] : VK_FORMAT_D32_SFLOAT;
    ad[i].samples = VK_SAMPLE_COUNT_1_BIT;
    ad[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    ad[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    ad[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    ad[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    ad[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    ad[i].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    if (i < nc) refs[i] = {i, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  }
  VkAttachmentReference dref{nc, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = nc;
  sub.pColorAttachments = refs.data();
  sub.pDepthStencilAttachment = &dref;
  const VkPipelineStageFlags attStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags attWrites = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  // In: a previous copyOut of the same attachments must finish reading before this pass writes them.
  // Out: the attachments' writes before the copies.
  VkSubpassDependency deps[2] = {
      {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, attStages, VK_ACCESS_TRANSFER_READ_BIT, attWrites, 0},
      {0, VK_SUBPASS_EXTERNAL, attStages, VK_PIPELINE_STAGE_TRANSFER_BIT, attWrites, VK_ACCESS_TRANSFER_READ_BIT, 0}};
  VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rpi.attachmentCount = nc + 1;
  rpi.pAttachments = ad.data();
  rpi.subpassCount = 1;
  rpi.pSubpasses = &sub;
  rpi.dependencyCount = 2;
  rpi.pDependencies = deps;
  check(vkCreateRenderPass(dev, &rpi, nullptr, &renderPass_), what("vkCreateRenderPass").c_str());
  std::vector<VkImageView> views;
  for (auto& c : color_) views.push_back(c->view());
  views.push_back(depth_->view());
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = renderPass_;
  fi.attachmentCount = nc + 1;
  fi.pAttachments = views.data();
  fi.width = desc.width;
  fi.height = desc.height;
  fi.layers = 1;
  check(vkCreateFramebuffer(dev, &fi, nullptr, &framebuffer_), what("vkCreateFramebuffer").c_str());

  const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  std::vector<VkDescriptorSetLayoutBinding> lb;
  for (uint32_t i = 0; i < desc.storageBuffers; ++i) lb.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, both, nullptr});
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = uint32_t(lb.size());
  li.pBindings = lb.data();
  check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &setLayout_), what("vkCreateDescriptorSetLayout").c_str());
  VkPushConstantRange pcr{both, 0, desc.pushBytes};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout_;
  pli.pushConstantRangeCount = desc.pushBytes ? 1 : 0;
  pli.pPushConstantRanges = &pcr;
  check(vkCreatePipelineLayout(dev, &pli, nullptr, &layout_), what("vkCreatePipelineLayout").c_str());

  VkShaderModule vsm = makeShaderModule(dev, desc.vertexSpirv);
  VkShaderModule fsm = desc.fragmentSpirv.empty() ? VK_NULL_HANDLE : makeShaderModule(dev, desc.fragmentSpirv);
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vsm, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fsm, "main", nullptr}};
  VkVertexInputBindingDescription vb{0, desc.vertexStride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vin.vertexBindingDescriptionCount = 1;
  vin.pVertexBindingDescriptions = &vb;
  vin.vertexAttributeDescriptionCount = uint32_t(desc.attributes.size());
  vin.pVertexAttributeDescriptions = desc.attributes.data();
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(desc.width), float(desc.height), 0, 1};
  VkRect2D scissor{{0, 0}, {desc.width, desc.height}};
  VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vps.viewportCount = 1;
  vps.pViewports = &viewport;
  vps.scissorCount = 1;
  vps.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo dss{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  dss.depthTestEnable = VK_TRUE;
  dss.depthWriteEnable = VK_TRUE;
  dss.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  std::vector<VkPipelineColorBlendAttachmentState> cba(nc);
  for (auto& c : cba) c = {}, c.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = nc;
  cb.pAttachments = cba.data();
  VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  gi.stageCount = fsm ? 2 : 1;
  gi.pStages = stages;
  gi.pVertexInputState = &vin;
  gi.pInputAssemblyState = &ia;
  gi.pViewportState = &vps;
  gi.pRasterizationState = &rs;
  gi.pMultisampleState = &ms;
  gi.pDepthStencilState = &dss;
  gi.pColorBlendState = &cb;
  gi.layout = layout_;
  gi.renderPass = renderPass_;
  VkResult r = vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gi, nullptr, &pipeline_);
  vkDestroyShaderModule(dev, vsm, nullptr);
  if (fsm) vkDestroyShaderModule(dev, fsm, nullptr);
  check(r, what("vkCreateGraphicsPipelines").c_str());

  if (desc.storageBuffers) {
    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, desc.storageBuffers};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.maxSets = 1;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &ps;
    check(vkCreateDescriptorPool(dev, &dpi, nullptr, &pool_), what("vkCreateDescriptorPool").c_str());
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &setLayout_;
    check(vkAllocateDescriptorSets(dev, &ai, &set_), what("vkAllocateDescriptorSets").c_str());
  }
}

GraphicsPass::~GraphicsPass() {
  VkDevice dev = ctx_.device();
  if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
  vkDestroyPipeline(dev, pipeline_, nullptr);
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
  vkDestroyFramebuffer(dev, framebuffer_, nullptr);
  vkDestroyRenderPass(dev, renderPass_, nullptr);
}

void GraphicsPass::bindBuffers(std::span<const VkBuffer> buffers) {
  if (buffers.size() != desc_.storageBuffers) throw Error(std::string(desc_.name) + ": binding count does not match");
  std::vector<VkDescriptorBufferInfo> bi(buffers.size());
  std::vector<VkWriteDescriptorSet> wr(buffers.size());
  for (uint32_t i = 0; i < buffers.size(); ++i) {
    bi[i] = {buffers[i], 0, VK_WHOLE_SIZE};
    wr[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    wr[i].dstSet = set_;
    wr[i].dstBinding = i;
    wr[i].descriptorCount = 1;
    wr[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    wr[i].pBufferInfo = &bi[i];
  }
  vkUpdateDescriptorSets(ctx_.device(), uint32_t(wr.size()), wr.data(), 0, nullptr);
}

void GraphicsPass::begin(VkCommandBuffer cmd) const {
  std::vector<VkClearValue> clears(color_.size() + 1);
  for (auto& c : clears) c = {};
  clears.back().depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rbi.renderPass = renderPass_;
  rbi.framebuffer = framebuffer_;
  rbi.renderArea = {{0, 0}, {desc_.width, desc_.height}};
  rbi.clearValueCount = uint32_t(clears.size());
  rbi.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  if (set_) vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
}

void GraphicsPass::pushConstants(VkCommandBuffer cmd, const void* data) const {
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, desc_.pushBytes, data);
}

void GraphicsPass::end(VkCommandBuffer cmd) const { vkCmdEndRenderPass(cmd); }

void GraphicsPass::copyOut(VkCommandBuffer cmd, int attachment, VkBuffer dst, VkDeviceSize offset) const {
  const bool depth = attachment < 0;
  const RenderTarget& t = depth ? *depth_ : *color_[size_t(attachment)];
  VkBufferImageCopy c{};
  c.bufferOffset = offset;
  c.imageSubresource = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 0, 1};
  c.imageExtent = {t.width(), t.height(), 1};
  vkCmdCopyImageToBuffer(cmd, t.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1, &c);
}

void GraphicsPass::hostBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

}  // namespace shadetwin::vk
