// The shading pass on a Vulkan device: the compute kernel src/shaders/shade_mirror.comp (the shared
// shade/shade_mirror.h) over a G-buffer uploaded from the host, the environment as a sampler2D with
// its MIP chain and the same sampler state as the emulator's (repeat in u, clamp in v, trilinear).
#include <chrono>
#include <cstring>

#include "emu/format.h"
#include "render/passes_vk.h"

namespace shadetwin {
namespace {
#include "shade_mirror_comp.inc"

struct ShadePush {
  float eye[4], fwd[4], right[4], down[4];
  float invW, invH, envMaxLod, intensity;
  uint32_t width, count, materialCount, pad;
};
static_assert(sizeof(ShadePush) == 96, "ShadePush must match the push block of shade_mirror.comp");
struct MaterialGpu {
  float diffuse[4], specular[4];
};
static_assert(sizeof(MaterialGpu) == 32, "MaterialGpu must match shade_mirror.comp");
}  // namespace

struct ShadePassVk::Impl {
  vk::Context& ctx;
  const Scene& scene;
  vk::Image env;
  vk::Sampler sampler;
  vk::Buffer materials;
  vk::Kernel kernel;
  float envMaxLod;
  std::unique_ptr<vk::Buffer> gbuf, out;
  static VkSamplerCreateInfo samplerInfo() {
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.minLod = 0.0f;
    si.maxLod = 1000.0f;
    return si;
  }
  static constexpr VkDescriptorType kLayout[4] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                  VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  Impl(vk::Context& c, const Scene& s, const emu::Texture& tex)
      : ctx(c), scene(s),
        env(c, VK_FORMAT_R32G32B32A32_SFLOAT, tex.width(), tex.height(), 1, tex.levels(), 16, VK_IMAGE_VIEW_TYPE_2D),
        sampler(c, samplerInfo()), materials(c, std::max<size_t>(1, s.materials.size()) * sizeof(MaterialGpu)),
        kernel(c, vk::Stage::Compute, kSpv_shade_mirror_comp, kLayout, sizeof(ShadePush)),
        envMaxLod(float(tex.levelCount() - 1)) {
    if (tex.format() != emu::Format::RGBA32F) throw vk::Error("shading pass: the environment must be RGBA32F");
    for (size_t i = 0; i < s.materials.size(); ++i) {
      MaterialGpu& m = materials.as<MaterialGpu>()[i];
      m = {};
      std::memcpy(m.diffuse, s.materials[i].diffuse.data(), 12);
      std::memcpy(m.specular, s.materials[i].specular.data(), 12);
    }
  }
};

ShadePassVk::ShadePassVk(vk::Context& ctx, const Scene& scene, const emu::Texture& env)
    : impl_(std::make_unique<Impl>(ctx, scene, env)) {}
ShadePassVk::~ShadePassVk() = default;

std::vector<float> ShadePassVk::run(const GBuffer& g) {
  Impl& m = *impl_;
  const size_t n = size_t(g.width) * g.height;
  if (!m.gbuf || m.gbuf->size() < n * 32) {
    m.gbuf = std::make_unique<vk::Buffer>(m.ctx, n * 32);
    m.out = std::make_unique<vk::Buffer>(m.ctx, n * 16);
  }
  float* dst = m.gbuf->as<float>();
  for (size_t p = 0; p < n; ++p) std::memcpy(dst + 8 * p, g.texels.data() + p * kGbufFloats, 32);  // G0, G1
  const CameraRays cam = cameraRays(m.scene);
  ShadePush push{};
  std::memcpy(push.eye, cam.eye, 12);
  std::memcpy(push.fwd, cam.fwd, 12);
  std::memcpy(push.right, cam.right, 12);
  std::memcpy(push.down, cam.down, 12);
  push.invW = 1.0f / float(g.width);
  push.invH = 1.0f / float(g.height);
  push.envMaxLod = m.envMaxLod;
  push.intensity = m.scene.environmentIntensity;
  push.width = g.width;
  push.count = uint32_t(n);
  push.materialCount = uint32_t(std::max<size_t>(1, m.scene.materials.size()));
  const vk::Binding b[4] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.env.view(), m.sampler.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.gbuf->handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.materials.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.out->handle()}};
  auto t0 = std::chrono::steady_clock::now();
  m.kernel.run(b, &push, uint32_t(n));
  lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<float> out(4 * n);
  std::memcpy(out.data(), m.out->data(), out.size() * 4);
  return out;
}

}  // namespace shadetwin
