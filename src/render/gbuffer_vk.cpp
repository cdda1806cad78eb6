// The G-buffer pass on a Vulkan device: one graphics pipeline (src/shaders/gbuffer.vert/.frag, the
// shared shade/gbuffer.h), four RGBA32F attachments + D32F, one indexed draw per object, read back.
#include <cstring>
#include <memory>

#include "render/gbuffer.h"
#include "vk/context.h"

namespace shadetwin {
namespace {
#include "gbuffer_frag.inc"
#include "gbuffer_vert.inc"

using vk::check;
}  // namespace

GBuffer gbufferVulkan(vk::Context& ctx, const Scene& scene) {
  VkDevice dev = ctx.device();
  const uint32_t W = scene.width, H = scene.height;
  // Geometry and per-object data.
  std::vector<std::unique_ptr<vk::Buffer>> vbs, ibs;
  for (const Mesh& m : scene.meshes) {
    auto v = interleave(m);
    vbs.push_back(std::make_unique<vk::Buffer>(ctx, v.size() * sizeof(VertexGpu), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
    std::memcpy(vbs.back()->data(), v.data(), v.size() * sizeof(VertexGpu));
    ibs.push_back(std::make_unique<vk::Buffer>(ctx, m.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT));
    std::memcpy(ibs.back()->data(), m.indices.data(), m.indices.size() * 4);
  }
  vk::Buffer objects(ctx, scene.objects.size() * sizeof(ObjectGpu)), frame(ctx, 64);
  for (size_t i = 0; i < scene.objects.size(); ++i) objects.as<ObjectGpu>()[i] = objectGpu(scene.objects[i]);
  const Mat4 vp = scene.viewProjection();
  std::memcpy(frame.data(), vp.data(), 64);
  // Attachments, render pass, framebuffer.
  std::vector<std::unique_ptr<vk::RenderTarget>> att;
  for (int i = 0; i < kGbufAttachments; ++i)
    att.push_back(std::make_unique<vk::RenderTarget>(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, W, H, false));
  att.push_back(std::make_unique<vk::RenderTarget>(ctx, VK_FORMAT_D32_SFLOAT, W, H, true));
  VkAttachmentDescription ad[kGbufAttachments + 1];
  VkAttachmentReference refs[kGbufAttachments];
  for (int i = 0; i <= kGbufAttachments; ++i) {
    ad[i] = {};
    ad[i].format = i < kGbufAttachments ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_D32_SFLOAT;
    ad[i].samples = VK_SAMPLE_COUNT_1_BIT;
    ad[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    ad[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    ad[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    ad[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    ad[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    ad[i].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    if (i < kGbufAttachments) refs[i] = {uint32_t(i), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  }
  VkAttachmentReference dref{kGbufAttachments, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = kGbufAttachments;
  sub.pColorAttachments = refs;
  sub.pDepthStencilAttachment = &dref;
  VkSubpassDependency dep{0, VK_SUBPASS_EXTERNAL,
                          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT, 0};
  VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rpi.attachmentCount = kGbufAttachments + 1;
  rpi.pAttachments = ad;
  rpi.subpassCount = 1;
  rpi.pSubpasses = &sub;
  rpi.dependencyCount = 1;
  rpi.pDependencies = &dep;
  VkRenderPass rp;
  check(vkCreateRenderPass(dev, &rpi, nullptr, &rp), "vkCreateRenderPass(G-buffer)");
  VkImageView views[kGbufAttachments + 1];
  for (int i = 0; i <= kGbufAttachments; ++i) views[i] = att[size_t(i)]->view();
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = rp;
  fi.attachmentCount = kGbufAttachments + 1;
  fi.pAttachments = views;
  fi.width = W;
  fi.height = H;
  fi.layers = 1;
  VkFramebuffer fb;
  check(vkCreateFramebuffer(dev, &fi, nullptr, &fb), "vkCreateFramebuffer(G-buffer)");
  // Descriptors and pipeline.
  VkDescriptorSetLayoutBinding lb[2] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 2;
  li.pBindings = lb;
  VkDescriptorSetLayout dsl;
  check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &dsl), "vkCreateDescriptorSetLayout(G-buffer)");
  VkPushConstantRange pcr{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &dsl;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &pcr;
  VkPipelineLayout pl;
  check(vkCreatePipelineLayout(dev, &pli, nullptr, &pl), "vkCreatePipelineLayout(G-buffer)");
  VkShaderModule vsm = vk::makeShaderModule(dev, kSpv_gbuffer_vert), fsm = vk::makeShaderModule(dev, kSpv_gbuffer_frag);
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vsm, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fsm, "main", nullptr}};
  VkVertexInputBindingDescription vb{0, sizeof(VertexGpu), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription va[4] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                             {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12},
                                             {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 24},
                                             {3, 0, VK_FORMAT_R32G32_SFLOAT, 40}};
  VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vin.vertexBindingDescriptionCount = 1;
  vin.pVertexBindingDescriptions = &vb;
  vin.vertexAttributeDescriptionCount = 4;
  vin.pVertexAttributeDescriptions = va;
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(W), float(H), 0, 1};
  VkRect2D scissor{{0, 0}, {W, H}};
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
  VkPipelineColorBlendAttachmentState cba[kGbufAttachments] = {};
  for (auto& c : cba) c.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = kGbufAttachments;
  cb.pAttachments = cba;
  VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  gi.stageCount = 2;
  gi.pStages = stages;
  gi.pVertexInputState = &vin;
  gi.pInputAssemblyState = &ia;
  gi.pViewportState = &vps;
  gi.pRasterizationState = &rs;
  gi.pMultisampleState = &ms;
  gi.pDepthStencilState = &dss;
  gi.pColorBlendState = &cb;
  gi.layout = pl;
  gi.renderPass = rp;
  VkPipeline pipe;
  check(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gi, nullptr, &pipe), "vkCreateGraphicsPipelines(G-buffer)");
  VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = 1;
  dpi.poolSizeCount = 1;
  dpi.pPoolSizes = &ps;
  VkDescriptorPool pool;
  check(vkCreateDescriptorPool(dev, &dpi, nullptr, &pool), "vkCreateDescriptorPool(G-buffer)");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &dsl;
  VkDescriptorSet set;
  check(vkAllocateDescriptorSets(dev, &ai, &set), "vkAllocateDescriptorSets(G-buffer)");
  VkDescriptorBufferInfo bi[2] = {{objects.handle(), 0, VK_WHOLE_SIZE}, {frame.handle(), 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet wr[2];
  for (uint32_t i = 0; i < 2; ++i) {
    wr[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    wr[i].dstSet = set;
    wr[i].dstBinding = i;
    wr[i].descriptorCount = 1;
    wr[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    wr[i].pBufferInfo = &bi[i];
  }
  vkUpdateDescriptorSets(dev, 2, wr, 0, nullptr);
  // Record, submit, read back.
  std::vector<std::unique_ptr<vk::Buffer>> rb;
  for (int i = 0; i < kGbufAttachments; ++i) rb.push_back(std::make_unique<vk::Buffer>(ctx, size_t(W) * H * 16));
  rb.push_back(std::make_unique<vk::Buffer>(ctx, size_t(W) * H * 4));
  ctx.submit([&](VkCommandBuffer cmd) {
    VkClearValue clears[kGbufAttachments + 1] = {};
    clears[kGbufAttachments].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = rp;
    rbi.framebuffer = fb;
    rbi.renderArea = {{0, 0}, {W, H}};
    rbi.clearValueCount = kGbufAttachments + 1;
    rbi.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pl, 0, 1, &set, 0, nullptr);
    for (uint32_t oi = 0; oi < scene.objects.size(); ++oi) {
      const Object& o = scene.objects[oi];
      VkBuffer vbh = vbs[o.mesh]->handle();
      VkDeviceSize off = 0;
      vkCmdBindVertexBuffers(cmd, 0, 1, &vbh, &off);
      vkCmdBindIndexBuffer(cmd, ibs[o.mesh]->handle(), 0, VK_INDEX_TYPE_UINT32);
      vkCmdPushConstants(cmd, pl, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &oi);
      vkCmdDrawIndexed(cmd, uint32_t(scene.meshes[o.mesh].indices.size()), 1, 0, 0, 0);
    }
    vkCmdEndRenderPass(cmd);
    for (int i = 0; i <= kGbufAttachments; ++i) {
      VkBufferImageCopy c{};
      c.imageSubresource = {VkImageAspectFlags(i < kGbufAttachments ? VK_IMAGE_ASPECT_COLOR_BIT : VK_IMAGE_ASPECT_DEPTH_BIT), 0, 0, 1};
      c.imageExtent = {W, H, 1};
      vkCmdCopyImageToBuffer(cmd, att[size_t(i)]->image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, rb[size_t(i)]->handle(), 1, &c);
    }
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr, 0, nullptr);
  });
  GBuffer g;
  g.width = W;
  g.height = H;
  g.texels.resize(size_t(W) * H * kGbufFloats);
  g.depth.resize(size_t(W) * H);
  for (size_t p = 0; p < size_t(W) * H; ++p)
    for (int a = 0; a < kGbufAttachments; ++a) std::memcpy(&g.texels[p * kGbufFloats + size_t(4 * a)], rb[size_t(a)]->as<float>() + 4 * p, 16);
  std::memcpy(g.depth.data(), rb[kGbufAttachments]->data(), g.depth.size() * 4);
  vkDestroyDescriptorPool(dev, pool, nullptr);
  vkDestroyPipeline(dev, pipe, nullptr);
  vkDestroyShaderModule(dev, vsm, nullptr);
  vkDestroyShaderModule(dev, fsm, nullptr);
  vkDestroyPipelineLayout(dev, pl, nullptr);
  vkDestroyDescriptorSetLayout(dev, dsl, nullptr);
  vkDestroyFramebuffer(dev, fb, nullptr);
  vkDestroyRenderPass(dev, rp, nullptr);
  return g;
}

}  // namespace shadetwin
