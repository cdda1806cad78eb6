// Headless Vulkan host: device selection, buffers, images, samplers, and "kernels" — a shader run
// once per work item either as a compute dispatch or as the fragment stage of a full-screen
// triangle (so both shader stages of a device can be measured with the same shader source).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/thread_log.h"

namespace shadetwin::vk {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check(VkResult r, const char* what);

struct ContextOptions {
  std::string device;       // substring of the device name (case-insensitive); empty = lavapipe if present
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation and count its errors
};

class Context {
 public:
  explicit Context(const ContextOptions& opts = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical() const { return phys_; }
  const std::string& deviceName() const { return deviceName_; }
  bool isLavapipe() const;
  bool validationEnabled() const { return validationOn_; }
  uint32_t validationErrors() const { return validationErrors_; }
  uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags props) const;
  /// Records with `record`, submits, waits for completion.
  void submit(const std::function<void(VkCommandBuffer)>& record);
  /// Names of all physical devices.
  static std::vector<std::string> listDevices();

  uint32_t validationErrors_ = 0;  // written by the debug messenger
  std::string lastValidationMessage;

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice phys_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::string deviceName_;
  bool validationOn_ = false;
};

/// Host-visible buffer (storage + transfer).
class Buffer {
 public:
  Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* data() { return mapped_; }
  template <class T> T* as() { return static_cast<T*>(mapped_); }

 private:
  Context& ctx_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_;
  void* mapped_ = nullptr;
};

/// 2D array image with a full or partial MIP chain, sampled in shaders.
class Image {
 public:
  /// `levels[l]` holds layers * w_l * h_l texels of `texelBytes` each, w_l = max(1, w >> l).
  /// `viewType`: 2D_ARRAY (sampler2DArray) or, for one layer, 2D (sampler2D).
  Image(Context& ctx, VkFormat format, uint32_t width, uint32_t height, uint32_t layers,
        const std::vector<std::vector<uint8_t>>& levels, uint32_t texelBytes,
        VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY);
  ~Image();
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  VkImageView view() const { return view_; }

 private:
  Context& ctx_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
};

/// A 2D render target (color or depth attachment, also a transfer source) with its memory and view.
class RenderTarget {
 public:
  RenderTarget(Context& ctx, VkFormat format, uint32_t width, uint32_t height, bool depth);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  VkImage image() const { return image_; }
  VkImageView view() const { return view_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  Context& ctx_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  uint32_t width_, height_;
};

VkShaderModule makeShaderModule(VkDevice dev, std::span<const uint32_t> spirv);

class Sampler {
 public:
  Sampler(Context& ctx, const VkSamplerCreateInfo& info);
  ~Sampler();
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;
  VkSampler handle() const { return sampler_; }

 private:
  Context& ctx_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

enum class Stage { Compute, Fragment };

/// One descriptor binding of a kernel, in binding order 0, 1, ...
struct Binding {
  VkDescriptorType type;
  VkBuffer buffer = VK_NULL_HANDLE;        // storage buffer
  VkImageView view = VK_NULL_HANDLE;       // combined image sampler
  VkSampler sampler = VK_NULL_HANDLE;
};

/// A shader run over `count` work items: compute (local size 64, item = global id) or fragment
/// (full-screen triangle over a width x ceil(count/width) target, item = y * width + x).
/// The submit-to-completion times of the Kernel::run calls made on this thread while a DispatchLog is alive (the
/// performance model's measured side of passes built and torn down inside one function, e.g. the technique inputs).
struct DispatchLog : ThreadLog<DispatchLog> {
  std::vector<double> ms;  // one per dispatch, in order
  double totalMs() const {
    double t = 0;
    for (double m : ms) t += m;
    return t;
  }
};

class Kernel {
 public:
  /// `specialization[i]` sets the 32-bit specialization constant constant_id = i (compute stage).
  Kernel(Context& ctx, Stage stage, std::span<const uint32_t> spirv, std::span<const VkDescriptorType> layout,
         uint32_t pushBytes, std::span<const uint32_t> vertexSpirv = {}, std::span<const uint32_t> specialization = {});
  ~Kernel();
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;
  /// Runs the kernel; `push` must be pushBytes long. For the fragment stage `width` is the row length.
  void run(std::span<const Binding> bindings, const void* push, uint32_t count, uint32_t width = 1024);

 private:
  void buildFragmentTarget(uint32_t width, uint32_t height);
  void destroyFragmentTarget();
  Context& ctx_;
  Stage stage_;
  uint32_t pushBytes_;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipeLayout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool descPool_ = VK_NULL_HANDLE;
  VkShaderModule module_ = VK_NULL_HANDLE, vertModule_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorType> layout_;
  // fragment target
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  std::unique_ptr<RenderTarget> target_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
};

}  // namespace shadetwin::vk
