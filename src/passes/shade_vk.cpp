// The shading pass on a Vulkan device: the compute kernel src/shaders/shade_mirror.comp (the shared
// shade/shade_mirror.h) over a G-buffer uploaded from the host, the environment as a sampler2D with
// its MIP chain and the same sampler state as the emulator's (repeat in u, clamp in v, trilinear).
#include <chrono>
#include <cstddef>
#include <cstring>

#include "emu/format.h"
#include "inputs/material.h"
#include "passes/passes_vk.h"
#include "passes/visibility.h"

namespace shadetwin {
namespace {
#include "shade_mirror_comp.inc"
#include "shade_fis_comp.inc"
#include "shade_env_comp.inc"
#include "shade_env_mis_comp.inc"
#include "shade_glints_comp.inc"

// One push block for both kernels: shade_mirror.comp declares the first 96 bytes (its last uint is
// padding), shade_fis.comp all 116.
struct ShadePush {
  float eye[4], fwd[4], right[4], down[4];
  float invW, invH, maxLod, intensity;
  uint32_t width, count, materialCount, sampleCount;
  float levelConstant, levelBias;
  uint32_t mode, visMode;
  uint32_t background;
};
static_assert(offsetof(ShadePush, levelConstant) == 96, "the first 96 bytes are shade_mirror.comp's push block");
static_assert(offsetof(ShadePush, background) == 112 && sizeof(ShadePush) == 116,
              "ShadePush must match the push block of shade_fis.comp");
// What each kernel binds: mirror reads 96 push bytes, 4 bindings, {diffuse, specular} of the material
// records (inputs/material.h, 32-byte stride) and the equirectangular map; fis all 116 bytes, binding
// 4 = SH coefficients, 5 = material maps and 6 = the equirectangular map (the background), the atlas (clamped in u); env 96 bytes (sampleCount =
// light count), binding 4 = lights and 5 = material maps, the equirectangular map. fis and env read
// whole 128-byte material records and G0..G3 (64 bytes per pixel), mirror G0, G1. The MIS kernel:
// 96 bytes, binding 4 = MisSettingsGpu, 5 = material maps, 6 and 7 = the sampler's tables. glints:
// 96 bytes, G0..G3, binding 4 = GlintUniforms, 5 = the SATs (RGBA32UI array), 6 bin directions,
// 7 material rows, 8 the lighting table, 9 the Legendre coefficients, 10 the rotated-lobe table (inputs/glints.h).
struct KernelInfo {
  std::span<const uint32_t> spirv;
  uint32_t bindings;
  size_t pushBytes;
  bool brdf, repeatU;
};
KernelInfo kernelInfo(const std::string& technique) {
  if (usesFisPass(technique)) return {kSpv_shade_fis_comp, 7, sizeof(ShadePush), true, false};
  if (technique == "env") return {kSpv_shade_env_comp, 6, offsetof(ShadePush, levelConstant), true, true};
  if (usesMisPass(technique)) return {kSpv_shade_env_mis_comp, 8, offsetof(ShadePush, levelConstant), true, true};
  if (technique == "glints") return {kSpv_shade_glints_comp, 11, offsetof(ShadePush, levelConstant), false, true};
  return {kSpv_shade_mirror_comp, 4, offsetof(ShadePush, levelConstant), false, true};
}

}  // namespace

std::span<const uint32_t> shadeModule(const std::string& technique) { return kernelInfo(technique).spirv; }

namespace {
VkSamplerCreateInfo materialMapSamplerInfo() {
  VkSamplerCreateInfo si = environmentSamplerInfo(true);
  si.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  return si;
}

// Binding 4 of shade_env_mis.comp: shade/env_sampling.h EnvSampling, then shade/shade_env_mis.h MisSettings.
struct MisSettingsGpu {
  EnvSamplingUniforms sampling;
  uint32_t heuristic, sampleCount, frame, seed;
};
static_assert(sizeof(MisSettingsGpu) == 48, "MisSettingsGpu must match the Settings block of shade_env_mis.comp");

const emu::Texture& whiteTexture() {
  static const emu::Texture t = materialMapsEmu(MaterialMapImages{});
  return t;
}
}  // namespace

struct ShadePassVk::Impl {
  vk::Context& ctx;
  const Scene& scene;
  vk::Image env;
  vk::Sampler sampler;
  vk::Buffer materials;
  std::vector<MaterialGpu> records;
  uint32_t kinds[3];  // specialization constants 0: kSceneBrdfKinds, 1 and 2: glints' kGlintShadeCoeffs, kGlintShadePaths
  vk::Kernel kernel;
  float envMaxLod;
  vk::Buffer extra;  // binding 4: fis, 9 vec4 of E/pi coefficients; env, the lights
  vk::Image maps;    // binding 5 (fis, env): material maps
  vk::Sampler mapSampler;
  std::unique_ptr<vk::Image> table, texels;  // *-mis: the environment sampler's tables (bindings 6, 7)
  std::unique_ptr<vk::Image> background;      // fis: the equirectangular map (binding 6)
  vk::Sampler backgroundSampler;
  vk::Sampler tableSampler;
  std::unique_ptr<vk::Image> glintSat, glintBins, glintMats, glintLighting, glintCoef, glintLobes;  // glints: bindings 5-10
  std::shared_ptr<const GlintInputs> glints;
  std::unique_ptr<vk::Buffer> gbuf, out;
  static constexpr VkDescriptorType kLayout[11] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                   VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                   VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                   VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
  const EnvSamplingTables* envTables;
  KernelInfo info;
  bool fis;
  uint32_t lightCount;
  std::shared_ptr<const VisibilitySetup> visibility;  // fis with visibility
  std::array<float, 48> visLighting;
  size_t materialStride() const { return info.brdf ? sizeof(MaterialGpu) : offsetof(MaterialGpu, brdf); }
  Impl(vk::Context& c, const Scene& s, const ShadeInputs& in)
      : Impl(c, s, in, in.texture(), in.maps ? *in.maps : whiteTexture(), kernelInfo(s.technique)) {}
  Impl(vk::Context& c, const Scene& s, const ShadeInputs& in, const emu::Texture& tex, const emu::Texture& mapTex,
       const KernelInfo& ki)
      : ctx(c), scene(s),
        env(c, VK_FORMAT_R32G32B32A32_SFLOAT, tex.width(), tex.height(), 1, tex.levels(), 16, VK_IMAGE_VIEW_TYPE_2D),
        sampler(c, environmentSamplerInfo(ki.repeatU)),
        materials(c, std::max<size_t>(1, s.materials.size()) * sizeof(MaterialGpu)),
        records(materialRecords(s, ki.brdf)),
        kinds{brdfKindsOf(records), in.glints ? (in.glints->order + 1) * (in.glints->order + 1) : 1u,
              in.glints && in.glints->lobeRings ? 2u : 1u},
        kernel(c, vk::Stage::Compute, ki.spirv, std::span<const VkDescriptorType>(kLayout, ki.bindings), uint32_t(ki.pushBytes),
               {}, std::span<const uint32_t>(kinds, ki.brdf ? 1 : in.glints ? 3 : 0)),
        envMaxLod(float(tex.levelCount() - 1)), extra(c, std::max<size_t>(9 * 16, in.lights.data.size() * 4)),
        maps(c, VK_FORMAT_R32G32B32A32_SFLOAT, mapTex.width(), mapTex.height(), mapTex.layers(), mapTex.levels(), 16,
             VK_IMAGE_VIEW_TYPE_2D_ARRAY),
        mapSampler(c, materialMapSamplerInfo()),
        table(in.envTables ? dataTextureImage(c, *in.envTables->table) : nullptr),
        texels(in.envTables ? dataTextureImage(c, *in.envTables->texels) : nullptr),
        background(usesFisPass(s.technique) && in.environment
                       ? std::make_unique<vk::Image>(c, VK_FORMAT_R32G32B32A32_SFLOAT, in.environment->width(), in.environment->height(),
                                                     1, in.environment->levels(), 16, VK_IMAGE_VIEW_TYPE_2D)
                       : nullptr),
        backgroundSampler(c, environmentSamplerInfo(true)), tableSampler(c, dataTextureSamplerInfo()),
        envTables(in.envTables.get()), info(ki),
        fis(usesFisPass(s.technique)), lightCount(in.lights.count), visibility(in.visibility),
        visLighting(in.visLighting) {
    if (fis && !background) throw vk::Error("shading pass: technique " + s.technique + " needs the environment (its background)");
    if (fis)
      for (int k = 0; k < 9; ++k) {
        float* d = extra.as<float>() + 4 * k;
        std::memcpy(d, &in.sh.c[3 * size_t(k)], 12);
        d[3] = 0.0f;
      }
    else if (!in.lights.data.empty())
      std::memcpy(extra.data(), in.lights.data.data(), in.lights.data.size() * 4);
    if (tex.format() != emu::Format::RGBA32F || mapTex.format() != emu::Format::RGBA32F)
      throw vk::Error("shading pass: the environment and the material maps must be RGBA32F");
    for (size_t i = 0; i < records.size(); ++i)
      std::memcpy(materials.as<uint8_t>() + i * materialStride(), &records[i], materialStride());
    if (in.glints) {
      // The device's loop limit bounds the kernel: refuse a degree and binning that could exceed it
      // (lavapipe: a pixel past it gets partial sums; measured in docs/RESULTS.md).
      const emu::DeviceProfile& prof = emu::profileForDevice(c.deviceName());
      const bool lobe = in.glints->lobeRings != 0;
      const uint64_t bound = glintShadeLoopBound(in.glints->order, in.glints->bins.rings, in.glints->bins.sectors, lobe);
      if (prof.loopIterationLimit && bound > prof.loopIterationLimit) {
        uint32_t ok = in.glints->order;
        while (ok > 0 && glintShadeLoopBound(ok, in.glints->bins.rings, in.glints->bins.sectors, lobe) > prof.loopIterationLimit) --ok;
        throw vk::Error("glints on " + c.deviceName() + ": degree " + std::to_string(in.glints->order) + " with " +
                        std::to_string(in.glints->bins.rings) + " x " + std::to_string(in.glints->bins.sectors) +
                        " bins may take " + std::to_string(bound) + " loop iterations per pixel, the device stops loops after " +
                        std::to_string(prof.loopIterationLimit) + " (use degree <= " + std::to_string(ok) + " or fewer bins)");
      }
      glints = in.glints;
      const emu::Texture& st = *in.glints->sat;
      glintSat = std::make_unique<vk::Image>(c, VK_FORMAT_R32G32B32A32_UINT, st.width(), st.height(), st.layers(), st.levels(), 16,
                                             VK_IMAGE_VIEW_TYPE_2D_ARRAY);
      glintBins = dataTextureImage(c, *in.glints->binDirs);
      glintMats = dataTextureImage(c, *in.glints->materials);
      glintLighting = dataTextureImage(c, *in.glints->lighting);
      glintCoef = dataTextureImage(c, *in.glints->coef);
      glintLobes = dataTextureImage(c, *in.glints->lobes);
    }
  }
};

ShadePassVk::ShadePassVk(vk::Context& ctx, const Scene& scene, const ShadeInputs& in)
    : impl_(std::make_unique<Impl>(ctx, scene, in)) {}
ShadePassVk::~ShadePassVk() = default;

std::vector<float> ShadePassVk::run(const GBuffer& g, const VisibilityImage* vis) {
  Impl& m = *impl_;
  const size_t n = size_t(g.width) * g.height;
  const size_t stride = m.info.brdf || m.glints ? 64 : 32;  // G0, G1 (+ G2, G3: tangent, uv derivatives, for fis, env, glints)
  if (!m.gbuf || m.gbuf->size() < n * stride) {
    m.gbuf = std::make_unique<vk::Buffer>(m.ctx, n * stride);
    m.out = std::make_unique<vk::Buffer>(m.ctx, n * 16);
  }
  float* dst = m.gbuf->as<float>();
  for (size_t p = 0; p < n; ++p) std::memcpy(dst + stride / 4 * p, g.texels.data() + p * kGbufFloats, stride);
  const CameraRays cam = cameraRays(m.scene);
  vk::Binding b[11] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.env.view(), m.sampler.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.gbuf->handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.materials.handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.out->handle()},
                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, m.extra.handle()},
                            {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.maps.view(), m.mapSampler.handle()},
                            {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.table ? m.table->view() : VK_NULL_HANDLE,
                             m.tableSampler.handle()},
                            {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.texels ? m.texels->view() : VK_NULL_HANDLE,
                             m.tableSampler.handle()},
                            {}, {}, {}};
  if (m.glints) {  // glints: the uniforms in binding 4, the tables in 5-10
    const GlintUniforms u = glintUniforms(*m.glints);
    std::memcpy(m.extra.data(), &u, sizeof u);
    const vk::Image* img[6] = {m.glintSat.get(), m.glintBins.get(), m.glintMats.get(), m.glintLighting.get(), m.glintCoef.get(),
                               m.glintLobes.get()};
    for (int k = 0; k < 6; ++k) b[5 + k] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, img[k]->view(), m.tableSampler.handle()};
  }
  // fis with visibility: binding 4 is the E/pi coefficients, the lighting SH and the pixels' fit.
  std::unique_ptr<vk::Buffer> visExtra;
  const bool useVis = m.fis && vis && m.visibility;
  const bool misVis = m.info.bindings == 8 && vis && m.visibility;
  const uint32_t visMode = !(useVis || misVis) ? shade::scalar::kFisVisNone
                           : m.visibility->settings.fitCosine  ? shade::scalar::kFisVisCos
                                                               : shade::scalar::kFisVisV;
  if ((useVis || misVis) && (vis->width != g.width || vis->height != g.height))
    throw vk::Error("shading pass: the visibility fit is not of this G-buffer");
  if (useVis) {
    visExtra = std::make_unique<vk::Buffer>(m.ctx, (21 + 4 * n) * 16);
    float* d = visExtra->as<float>();
    std::memcpy(d, m.extra.data(), 9 * 16);
    std::memcpy(d + 36, m.visLighting.data(), 48 * 4);
    std::memcpy(d + 84, vis->coeffs.data(), n * 64);
    b[4] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, visExtra->handle()};
  }
  if (m.info.bindings == 8) {  // the MIS kernel: its settings, the frame's included, in binding 4
    if (!m.envTables) throw vk::Error("shading pass: technique " + m.scene.technique + " needs its environment sampler's tables");
    const MisSettingsGpu st{m.envTables->uniforms, m.scene.misHeuristic, m.scene.misSamples, m.scene.misFrame, m.scene.misSeed};
    // The settings, the visibility mode (uvec4 at 48) and, with visibility, the pixels' fit (from 64).
    const uint32_t mode4[4] = {visMode, 0, 0, 0};
    if (misVis) {
      visExtra = std::make_unique<vk::Buffer>(m.ctx, 64 + n * 64);
      std::memcpy(visExtra->data(), &st, sizeof st);
      std::memcpy(visExtra->as<uint8_t>() + 48, mode4, 16);
      std::memcpy(visExtra->as<uint8_t>() + 64, vis->coeffs.data(), n * 64);
      b[4] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, visExtra->handle()};
    } else {
      std::memcpy(m.extra.data(), &st, sizeof st);
      std::memcpy(m.extra.as<uint8_t>() + 48, mode4, 16);
    }
  }
  ShadePush push{};
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
  if (m.fis) {
    push.sampleCount = m.scene.fisSamples;
    push.levelConstant = fisLevelConstant(m.scene);
    push.levelBias = m.scene.fisLevelBias;
    push.mode = fisMode(m.scene);
    push.visMode = visMode;
    push.background = m.scene.fisBackgroundAtlas ? shade::scalar::kFisBackgroundAtlas : shade::scalar::kFisBackgroundEnvironment;
    b[6] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, m.background->view(), m.backgroundSampler.handle()};
  } else if (m.scene.technique == "env") {
    push.sampleCount = m.lightCount;
  }
  auto t0 = std::chrono::steady_clock::now();
  m.kernel.run(std::span<const vk::Binding>(b, m.info.bindings), &push, uint32_t(n));
  lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<float> out(4 * n);
  std::memcpy(out.data(), m.out->data(), out.size() * 4);
  return out;
}

VkSamplerCreateInfo dataTextureSamplerInfo() {
  VkSamplerCreateInfo si = environmentSamplerInfo(false);
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;  // texelFetch only; R32F needs no linear-filter support
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  return si;
}

std::unique_ptr<vk::Image> dataTextureImage(vk::Context& c, const emu::Texture& t) {
  const bool r32 = t.format() == emu::Format::R32F;
  if (!r32 && t.format() != emu::Format::RGBA32F) throw vk::Error("data texture: expected R32F or RGBA32F");
  return std::make_unique<vk::Image>(c, r32 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT, t.width(), t.height(), 1,
                                     t.levels(), r32 ? 4 : 16, VK_IMAGE_VIEW_TYPE_2D);
}

VkSamplerCreateInfo environmentSamplerInfo(bool repeatU) {
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  si.addressModeU = repeatU ? VK_SAMPLER_ADDRESS_MODE_REPEAT : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.minLod = 0.0f;
  si.maxLod = 1000.0f;
  return si;
}

}  // namespace shadetwin
