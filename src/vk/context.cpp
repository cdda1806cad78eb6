#include "vk/context.h"

#include <chrono>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace shadetwin::vk {

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw Error(std::string("Vulkan: ") + what + " failed (VkResult " + std::to_string(r) + ")");
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                         void* user) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    auto* ctx = static_cast<Context*>(user);
    ++ctx->validationErrors_;
    ctx->lastValidationMessage = data->pMessage ? data->pMessage : "";
  }
  return VK_FALSE;
}

bool hasLayer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> props(n);
  vkEnumerateInstanceLayerProperties(&n, props.data());
  return std::any_of(props.begin(), props.end(), [&](auto& p) { return std::strcmp(p.layerName, name) == 0; });
}

std::string lower(std::string s) {
  for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The project's own drivers (issue 18): SwiftShader's ICD, which scripts/setup.sh extracts into assets/swiftshader/,
// is added to the loader's search (VK_ADD_DRIVER_FILES, honoured by Debian's loader 1.3.239) before the first
// instance, so `devices` lists it and `--device swiftshader` works with nothing set by hand. Entries the user
// set stay first; lavapipe stays the default device.
void registerProjectDrivers() {
  static const bool once = [] {
#ifdef SHADETWIN_SWIFTSHADER_ICD
    if (FILE* f = std::fopen(SHADETWIN_SWIFTSHADER_ICD, "r")) {
      std::fclose(f);
      const char* old = std::getenv("VK_ADD_DRIVER_FILES");
      std::string v = old && *old ? std::string(old) + ":" + SHADETWIN_SWIFTSHADER_ICD : std::string(SHADETWIN_SWIFTSHADER_ICD);
      if (!old || std::string(old).find(SHADETWIN_SWIFTSHADER_ICD) == std::string::npos) setenv("VK_ADD_DRIVER_FILES", v.c_str(), 1);
    }
#endif
    return true;
  }();
  (void)once;
}

VkInstance makeInstance(bool validation) {
  registerProjectDrivers();
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "shadetwin";
  app.apiVersion = VK_API_VERSION_1_1;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  if (validation) {
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = &layer;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = &ext;
  }
  VkInstance inst;
  check(vkCreateInstance(&ci, nullptr, &inst), "vkCreateInstance (is a Vulkan driver installed? mesa-vulkan-drivers)");
  return inst;
}

}  // namespace

std::vector<std::string> Context::listDevices() {
  VkInstance inst = makeInstance(false);
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(inst, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(inst, &n, devs.data());
  std::vector<std::string> names;
  for (auto d : devs) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    names.push_back(p.deviceName);
  }
  vkDestroyInstance(inst, nullptr);
  return names;
}

Context::Context(const ContextOptions& opts) {
  validationOn_ = opts.validation && hasLayer("VK_LAYER_KHRONOS_validation");
  if (opts.validation && !validationOn_)
    throw Error("validation requested but VK_LAYER_KHRONOS_validation is not installed (vulkan-validationlayers)");
  instance_ = makeInstance(validationOn_);
  if (validationOn_) {
    VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mi.pfnUserCallback = onMessage;
    mi.pUserData = this;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) check(create(instance_, &mi, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance_, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(instance_, &n, devs.data());
  // Mesa's lavapipe names its device llvmpipe: "lavapipe" (the project's name for it, as in devices/lavapipe.json) is that.
  std::string want = lower(opts.device.empty() ? "llvmpipe" : opts.device);
  if (want == "lavapipe") want = "llvmpipe";
  std::string names;
  for (auto d : devs) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    names += std::string(names.empty() ? "" : ", ") + p.deviceName;
    if (!phys_ && lower(p.deviceName).find(want) != std::string::npos) {
      phys_ = d;
      deviceName_ = p.deviceName;
    }
  }
  if (!phys_ && opts.device.empty() && !devs.empty()) {  // no lavapipe: take the first device
    phys_ = devs[0];
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(phys_, &p);
    deviceName_ = p.deviceName;
  }
  if (!phys_) {
    vkDestroyInstance(instance_, nullptr);
    throw Error("no Vulkan device matches '" + opts.device + "'; available: " + (names.empty() ? "none" : names));
  }
  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(phys_, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> qf(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(phys_, &qn, qf.data());
  bool found = false;
  for (uint32_t i = 0; i < qn && !found; ++i)
    if ((qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
      queueFamily_ = i;
      found = true;
    }
  if (!found) throw Error("device " + deviceName_ + " has no graphics+compute queue");
  float prio = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = queueFamily_;
  qi.queueCount = 1;
  qi.pQueuePriorities = &prio;
  VkPhysicalDeviceFeatures feats{};
  feats.fragmentStoresAndAtomics = VK_TRUE;
  VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  di.pEnabledFeatures = &feats;
  check(vkCreateDevice(phys_, &di, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = queueFamily_;
  check(vkCreateCommandPool(device_, &pi, nullptr, &pool_), "vkCreateCommandPool");
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(device_, &fi, nullptr, &fence_), "vkCreateFence");
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

bool Context::isLavapipe() const { return lower(deviceName_).find("llvmpipe") != std::string::npos; }

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags props) const {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(phys_, &mp);
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & props) == props) return i;
  throw Error("no suitable Vulkan memory type");
}

void Context::submit(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cb;
  check(vkAllocateCommandBuffers(device_, &ai, &cb), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cb, &bi);
  record(cb);
  vkEndCommandBuffer(cb);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  check(vkQueueSubmit(queue_, 1, &si, fence_), "vkQueueSubmit");
  check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vkResetFences(device_, 1, &fence_);
  vkFreeCommandBuffers(device_, pool_, 1, &cb);
}

// ---------------------------------------------------------------------------------------------

Buffer::Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) : ctx_(ctx), size_(std::max<VkDeviceSize>(size, 16)) {
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size_;
  bi.usage = usage;
  check(vkCreateBuffer(ctx.device(), &bi, nullptr, &buffer_), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
  VkMemoryAllocateInfo mi{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mi.allocationSize = req.size;
  mi.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkAllocateMemory(ctx.device(), &mi, nullptr, &memory_), "vkAllocateMemory");
  vkBindBufferMemory(ctx.device(), buffer_, memory_, 0);
  check(vkMapMemory(ctx.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
}

Buffer::~Buffer() {
  vkDestroyBuffer(ctx_.device(), buffer_, nullptr);
  vkFreeMemory(ctx_.device(), memory_, nullptr);
}

// ---------------------------------------------------------------------------------------------

Image::Image(Context& ctx, VkFormat format, uint32_t width, uint32_t height, uint32_t layers,
             const std::vector<std::vector<uint8_t>>& levels, uint32_t texelBytes, VkImageViewType viewType)
    : ctx_(ctx) {
  const uint32_t nLevels = uint32_t(levels.size());
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = format;
  ii.extent = {width, height, 1};
  ii.mipLevels = nLevels;
  ii.arrayLayers = layers;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(ctx.device(), &ii, nullptr, &image_), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device(), image_, &req);
  VkMemoryAllocateInfo mi{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mi.allocationSize = req.size;
  mi.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, 0);
  check(vkAllocateMemory(ctx.device(), &mi, nullptr, &memory_), "vkAllocateMemory(image)");
  vkBindImageMemory(ctx.device(), image_, memory_, 0);

  size_t total = 0;
  for (auto& l : levels) total += l.size();
  Buffer staging(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::vector<VkBufferImageCopy> copies;
  size_t off = 0;
  for (uint32_t l = 0; l < nLevels; ++l) {
    uint32_t w = std::max(1u, width >> l), h = std::max(1u, height >> l);
    if (levels[l].size() != size_t(w) * h * layers * texelBytes) throw Error("Image: level " + std::to_string(l) + " has the wrong size");
    std::memcpy(static_cast<uint8_t*>(staging.data()) + off, levels[l].data(), levels[l].size());
    VkBufferImageCopy c{};
    c.bufferOffset = off;
    c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, layers};
    c.imageExtent = {w, h, 1};
    copies.push_back(c);
    off += levels[l].size();
  }
  ctx.submit([&](VkCommandBuffer cb) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image_;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, nLevels, 0, layers};
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
    vkCmdCopyBufferToImage(cb, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(copies.size()), copies.data());
    b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &b);
  });
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image_;
  vi.viewType = viewType;
  vi.format = format;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, nLevels, 0, layers};
  check(vkCreateImageView(ctx.device(), &vi, nullptr, &view_), "vkCreateImageView");
}

Image::~Image() {
  vkDestroyImageView(ctx_.device(), view_, nullptr);
  vkDestroyImage(ctx_.device(), image_, nullptr);
  vkFreeMemory(ctx_.device(), memory_, nullptr);
}

Sampler::Sampler(Context& ctx, const VkSamplerCreateInfo& info) : ctx_(ctx) {
  check(vkCreateSampler(ctx.device(), &info, nullptr, &sampler_), "vkCreateSampler");
}
Sampler::~Sampler() { vkDestroySampler(ctx_.device(), sampler_, nullptr); }

// ---------------------------------------------------------------------------------------------

VkShaderModule makeShaderModule(VkDevice dev, std::span<const uint32_t> code) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = code.size_bytes();
  ci.pCode = code.data();
  VkShaderModule m;
  check(vkCreateShaderModule(dev, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}

RenderTarget::RenderTarget(Context& ctx, VkFormat format, uint32_t width, uint32_t height, bool depth)
    : ctx_(ctx), width_(width), height_(height) {
  VkDevice dev = ctx.device();
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = format;
  ii.extent = {width, height, 1};
  ii.mipLevels = 1;
  ii.arrayLayers = 1;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
             (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
  check(vkCreateImage(dev, &ii, nullptr, &image_), "vkCreateImage(render target)");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(dev, image_, &req);
  VkMemoryAllocateInfo mi{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mi.allocationSize = req.size;
  mi.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, 0);
  check(vkAllocateMemory(dev, &mi, nullptr, &memory_), "vkAllocateMemory(render target)");
  vkBindImageMemory(dev, image_, memory_, 0);
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image_;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  vi.subresourceRange = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
  check(vkCreateImageView(dev, &vi, nullptr, &view_), "vkCreateImageView(render target)");
}

RenderTarget::~RenderTarget() {
  vkDestroyImageView(ctx_.device(), view_, nullptr);
  vkDestroyImage(ctx_.device(), image_, nullptr);
  vkFreeMemory(ctx_.device(), memory_, nullptr);
}

Kernel::Kernel(Context& ctx, Stage stage, std::span<const uint32_t> spirv, std::span<const VkDescriptorType> layout,
               uint32_t pushBytes, std::span<const uint32_t> vertexSpirv, std::span<const uint32_t> specialization)
    : ctx_(ctx), stage_(stage), pushBytes_(pushBytes), layout_(layout.begin(), layout.end()) {
  VkDevice dev = ctx.device();
  VkShaderStageFlags stageBit = stage == Stage::Compute ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
  std::vector<VkDescriptorSetLayoutBinding> binds;
  for (uint32_t i = 0; i < layout_.size(); ++i) binds.push_back({i, layout_[i], 1, stageBit, nullptr});
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = uint32_t(binds.size());
  li.pBindings = binds.data();
  check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
  VkPushConstantRange pr{stageBit, 0, pushBytes};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout_;
  pli.pushConstantRangeCount = pushBytes ? 1 : 0;
  pli.pPushConstantRanges = &pr;
  check(vkCreatePipelineLayout(dev, &pli, nullptr, &pipeLayout_), "vkCreatePipelineLayout");
  std::vector<VkDescriptorPoolSize> sizes;
  for (auto t : layout_) sizes.push_back({t, 1});
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dpi.maxSets = 1;
  dpi.poolSizeCount = uint32_t(sizes.size());
  dpi.pPoolSizes = sizes.data();
  check(vkCreateDescriptorPool(dev, &dpi, nullptr, &descPool_), "vkCreateDescriptorPool");
  module_ = makeShaderModule(dev, spirv);
  if (stage == Stage::Compute) {
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < specialization.size(); ++i) entries.push_back({i, 4 * i, 4});
    const VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), specialization.size_bytes(), specialization.data()};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module_, "main",
                specialization.empty() ? nullptr : &spec};
    ci.layout = pipeLayout_;
    check(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_), "vkCreateComputePipelines");
    return;
  }
  if (vertexSpirv.empty()) throw Error("fragment kernel needs a vertex shader");
  vertModule_ = makeShaderModule(dev, vertexSpirv);
  VkAttachmentDescription att{};
  att.format = VK_FORMAT_R8G8B8A8_UNORM;
  att.samples = VK_SAMPLE_COUNT_1_BIT;
  att.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  att.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  att.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  att.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rpi.attachmentCount = 1;
  rpi.pAttachments = &att;
  rpi.subpassCount = 1;
  rpi.pSubpasses = &sub;
  check(vkCreateRenderPass(dev, &rpi, nullptr, &renderPass_), "vkCreateRenderPass");
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vertModule_, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, module_, "main", nullptr}};
  VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState cba{};
  cba.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 1;
  cb.pAttachments = &cba;
  VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  ds.dynamicStateCount = 2;
  ds.pDynamicStates = dyn;
  VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  gi.stageCount = 2;
  gi.pStages = stages;
  gi.pVertexInputState = &vin;
  gi.pInputAssemblyState = &ia;
  gi.pViewportState = &vp;
  gi.pRasterizationState = &rs;
  gi.pMultisampleState = &ms;
  gi.pColorBlendState = &cb;
  gi.pDynamicState = &ds;
  gi.layout = pipeLayout_;
  gi.renderPass = renderPass_;
  check(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gi, nullptr, &pipeline_), "vkCreateGraphicsPipelines");
}

void Kernel::buildFragmentTarget(uint32_t width, uint32_t height) {
  if (target_ && target_->width() == width && target_->height() == height) return;
  destroyFragmentTarget();
  target_ = std::make_unique<RenderTarget>(ctx_, VK_FORMAT_R8G8B8A8_UNORM, width, height, false);
  VkImageView view = target_->view();
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = renderPass_;
  fi.attachmentCount = 1;
  fi.pAttachments = &view;
  fi.width = width;
  fi.height = height;
  fi.layers = 1;
  check(vkCreateFramebuffer(ctx_.device(), &fi, nullptr, &framebuffer_), "vkCreateFramebuffer");
}

void Kernel::destroyFragmentTarget() {
  if (framebuffer_) vkDestroyFramebuffer(ctx_.device(), framebuffer_, nullptr);
  framebuffer_ = VK_NULL_HANDLE;
  target_.reset();
}

void Kernel::run(std::span<const Binding> bindings, const void* push, uint32_t count, uint32_t width) {
  if (bindings.size() != layout_.size()) throw Error("Kernel::run: binding count does not match the layout");
  if (count == 0) return;
  VkDevice dev = ctx_.device();
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = descPool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout_;
  VkDescriptorSet set;
  check(vkAllocateDescriptorSets(dev, &ai, &set), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorBufferInfo> bufInfos(bindings.size());
  std::vector<VkDescriptorImageInfo> imgInfos(bindings.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t i = 0; i < bindings.size(); ++i) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = i;
    w.descriptorCount = 1;
    w.descriptorType = layout_[i];
    if (layout_[i] == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) {
      imgInfos[i] = {bindings[i].sampler, bindings[i].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      w.pImageInfo = &imgInfos[i];
    } else {
      bufInfos[i] = {bindings[i].buffer, 0, VK_WHOLE_SIZE};
      w.pBufferInfo = &bufInfos[i];
    }
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(dev, uint32_t(writes.size()), writes.data(), 0, nullptr);
  VkShaderStageFlags stageBit = stage_ == Stage::Compute ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
  if (stage_ == Stage::Compute) {
    const auto t0 = std::chrono::steady_clock::now();
    ctx_.submit([&](VkCommandBuffer cb) {
      vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
      vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeLayout_, 0, 1, &set, 0, nullptr);
      if (pushBytes_) vkCmdPushConstants(cb, pipeLayout_, stageBit, 0, pushBytes_, push);
      vkCmdDispatch(cb, (count + 63) / 64, 1, 1);
      VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr, 0, nullptr);
    });
    if (DispatchLog* l = DispatchLog::active())
      l->ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  } else {
    uint32_t w = std::min(width, count), h = (count + w - 1) / w;
    buildFragmentTarget(w, h);
    ctx_.submit([&](VkCommandBuffer cb) {
      VkRenderPassBeginInfo rb{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      rb.renderPass = renderPass_;
      rb.framebuffer = framebuffer_;
      rb.renderArea = {{0, 0}, {w, h}};
      vkCmdBeginRenderPass(cb, &rb, VK_SUBPASS_CONTENTS_INLINE);
      vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
      vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeLayout_, 0, 1, &set, 0, nullptr);
      if (pushBytes_) vkCmdPushConstants(cb, pipeLayout_, stageBit, 0, pushBytes_, push);
      VkViewport vpt{0, 0, float(w), float(h), 0, 1};
      VkRect2D sc{{0, 0}, {w, h}};
      vkCmdSetViewport(cb, 0, 1, &vpt);
      vkCmdSetScissor(cb, 0, 1, &sc);
      vkCmdDraw(cb, 3, 1, 0, 0);
      vkCmdEndRenderPass(cb);
      VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr, 0, nullptr);
    });
  }
  vkFreeDescriptorSets(dev, descPool_, 1, &set);
}

Kernel::~Kernel() {
  VkDevice dev = ctx_.device();
  destroyFragmentTarget();
  if (renderPass_) vkDestroyRenderPass(dev, renderPass_, nullptr);
  vkDestroyPipeline(dev, pipeline_, nullptr);
  vkDestroyPipelineLayout(dev, pipeLayout_, nullptr);
  vkDestroyDescriptorPool(dev, descPool_, nullptr);
  vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
  vkDestroyShaderModule(dev, module_, nullptr);
  if (vertModule_) vkDestroyShaderModule(dev, vertModule_, nullptr);
}

}  // namespace shadetwin::vk
