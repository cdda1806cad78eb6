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
#include "shade_fis_comp.inc"

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
struct FisPush {
  float eye[4], fwd[4], right[4], down[4];
  float invW, invH, maxLod, intensity;
  uint32_t width, count, materialCount, sampleCount;
  float levelConstant, pad[3];
};
static_assert(sizeof(FisPush) == 112, "FisPush must match the push block of shade_fis.comp");
struct FisMaterialGpu {
  float diffuse[4], specular[4], brdf[4];
  uint32_t kind[4];
};
static_assert(sizeof(FisMaterialGpu) == 64, "FisMaterialGpu must match shade_fis.comp");
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
  bool fis;
  static VkSamplerCreateInfo samplerFor(bool fis) {
    VkSamplerCreateInfo si = samplerInfo();
    if (fis) si.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;  // the atlas: clamp in both
    return si;
  }
  Impl(vk::Context& c, const Scene& s, const emu::Texture& tex)
      : ctx(c), scene(s),
        env(c, VK_FORMAT_R32G32B32A32_SFLOAT, tex.width(), tex.height(), 1, tex.levels(), 16, VK_IMAGE_VIEW_TYPE_2D),
        sampler(c, samplerFor(s.technique == "fis")),
        materials(c, std::max<size_t>(1, s.materials.size()) * (s.technique == "fis" ? sizeof(FisMaterialGpu) : sizeof(MaterialGpu))),
        kernel(c, vk::Stage::Compute, s.technique == "fis" ? std::span<const uint32_t>(kSpv_shade_fis_comp)
                                                           : std::span<const uint32_t>(kSpv_shade_mirror_comp),
               kLayout, s.technique == "fis" ? sizeof(FisPush) : sizeof(ShadePush)),
        envMaxLod(float(tex.levelCount() - 1)), fis(s.technique == "fis") {
    if (tex.format() != emu::Format::RGBA32F) throw vk::Error("shading pass: the environment must be RGBA32F");
    std::vector<Material> mats = s.materials;
    if (mats.empty()) mats.push_back(Material{});
    for (size_t i = 0; i < mats.size(); ++i) {
      if (fis) {
        FisMaterialGpu& m = materials.as<FisMaterialGpu>()[i];
        m = {};
        std::memcpy(m.diffuse, mats[i].diffuse.data(), 12);
        std::memcpy(m.specular, mats[i].specular.data(), 12);
        const BrdfGpu b = brdfOf(mats[i]);
        m.brdf[0] = b.e, m.brdf[1] = b.ax, m.brdf[2] = b.ay, m.kind[0] = b.kind;
      } else {
        MaterialGpu& m = materials.as<MaterialGpu>()[i];
        m = {};
        std::memcpy(m.diffuse, mats[i].diffuse.data(), 12);
        std::memcpy(m.specular, mats[i].specular.data(), 12);
      }
    }
  }
};

ShadePassVk::ShadePassVk(vk::Context& ctx, const Scene& scene, const emu::Texture& env)
    : impl_(std::make_unique<Impl>(ctx, scene, env)) {}
ShadePassVk::~ShadePassVk() = default;

std::vector<float> ShadePassVk::run(const GBuffer& g) {
  Impl& m = *impl_;
  const size_t n = size_t(g.width) * g.height;
  const size_t stride = m.fis ? 48 : 32;  // G0, G1 (+ G2, the tangent, for fis)
  if (!m.gbuf || m.gbuf->size() < n * stride) {
    m.gbuf = std::make_unique<vk::Buffer>(m.ctx, n * stride);
    m.out = std::make_unique<vk::Buffer>(m.ctx, n * 16);
  }
  float* dst = m.gbuf->as<float>();
  for (size_t p = 0; p < n; ++p) std::memcpy(dst + stride / 4 * p, g.texels.data() + p * kGbufFloats, stride);
  const CameraRays cam = cameraRays(m.scene);
  const vk::Binding b[4] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.env.view(), m.sampler.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.gbuf->handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.materials.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.out->handle()}};
  if (m.fis) {
    FisPush push{};
    std::memcpy(push.eye, cam.eye, 12);
    std::memcpy(push.fwd, cam.fwd, 12);
    std::memcpy(push.right, cam.right, 12);
    std::memcpy(push.down, cam.down, 12);
    push.invW = 1.0f / float(g.width);
    push.invH = 1.0f / float(g.height);
    push.maxLod = m.envMaxLod;
    push.intensity = m.scene.environmentIntensity;
    push.width = g.width;
    push.count = uint32_t(n);
    push.materialCount = uint32_t(std::max<size_t>(1, m.scene.materials.size()));
    push.sampleCount = m.scene.fisSamples;
    push.levelConstant = fisLevelConstant(m.scene);
    auto t0 = std::chrono::steady_clock::now();
    m.kernel.run(b, &push, uint32_t(n));
    lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::vector<float> out(4 * n);
    std::memcpy(out.data(), m.out->data(), out.size() * 4);
    return out;
  }
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
  auto t0 = std::chrono::steady_clock::now();
  m.kernel.run(b, &push, uint32_t(n));
  lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<float> out(4 * n);
  std::memcpy(out.data(), m.out->data(), out.size() * 4);
  return out;
}

}  // namespace shadetwin
