#include <cstring>

#include "passes/passes_vk.h"
#include "passes/visibility.h"
#include "util/timer.h"

namespace shadetwin {
namespace {
#include "visibility_fit_comp.inc"
#include "visibility_filter_comp.inc"

struct FilterPush {
  int32_t width, height, radius;
  uint32_t mode, pixels;
  float planeTolerance;
};
static_assert(sizeof(FilterPush) == 24, "FilterPush must match the push block of visibility_filter.comp");

struct FitPush {
  uint32_t count, size, fit, pixels;
  float biasConst, biasSlope;
};
static_assert(sizeof(FitPush) == 24, "FitPush must match the push block of visibility_fit.comp");
// The 16 coefficients per pixel a kernel wrote into `out`.
VisibilityImage readBack(vk::Buffer& out, uint32_t width, uint32_t height) {
  VisibilityImage r;
  r.width = width, r.height = height;
  r.coeffs.resize(size_t(width) * height * 16);
  std::memcpy(r.coeffs.data(), out.as<float>(), r.coeffs.size() * 4);
  return r;
}
}  // namespace

VisibilityImage visibilityFitVulkan(vk::Context& ctx, const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v) {
  const size_t n = size_t(g.width) * g.height;
  vk::Buffer gbuf(ctx, n * 32), out(ctx, n * 64);
  for (size_t i = 0; i < n; ++i) std::memcpy(gbuf.as<float>() + 8 * i, g.texels.data() + i * kGbufFloats, 32);  // G0, G1
  vk::Image mapImg(ctx, VK_FORMAT_R32_SFLOAT, maps.width(), maps.height(), maps.layers(), maps.levels(), 4);
  const std::unique_ptr<vk::Image> data = dataTextureImage(ctx, *v.data);
  vk::Sampler sampler(ctx, dataTextureSamplerInfo());  // texelFetch only
  static constexpr VkDescriptorType kLayout[4] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                  VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel fit(ctx, vk::Stage::Compute, kSpv_visibility_fit_comp, kLayout, sizeof(FitPush));
  const FitPush push{maps.layers(), maps.width(), v.settings.fitCosine ? 0u : 1u, uint32_t(n), v.biasConst, v.biasSlope};
  const vk::Binding b[4] = {{kLayout[0], gbuf.handle()},
                            {kLayout[1], VK_NULL_HANDLE, mapImg.view(), sampler.handle()},
                            {kLayout[2], VK_NULL_HANDLE, data->view(), sampler.handle()},
                            {kLayout[3], out.handle()}};
  fit.run(b, &push, uint32_t(n));
  return readBack(out, g.width, g.height);
}

VisibilityImage visibilityFilterVulkan(vk::Context& ctx, const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v) {
  if (v.settings.filterRadius == 0) return in;
  const emu::Texture ct = visibilityCoeffTexture(in), gt = gbufferPositionNormalTexture(g);
  vk::Image cImg(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, ct.width(), ct.height(), ct.layers(), ct.levels(), 16);
  vk::Image gImg(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, gt.width(), gt.height(), gt.layers(), gt.levels(), 16);
  vk::Sampler sampler(ctx, dataTextureSamplerInfo());  // texelFetch only
  const size_t n = size_t(in.width) * in.height;
  vk::Buffer out(ctx, n * 64);
  static constexpr VkDescriptorType kLayout[3] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                  VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel filter(ctx, vk::Stage::Compute, kSpv_visibility_filter_comp, kLayout, sizeof(FilterPush));
  const FilterPush push{int32_t(in.width), int32_t(in.height), int32_t(v.settings.filterRadius),
                        v.settings.filterEdgeAware ? 1u : 0u, uint32_t(n), v.planeTolerance};
  const vk::Binding b[3] = {{kLayout[0], VK_NULL_HANDLE, cImg.view(), sampler.handle()},
                            {kLayout[1], VK_NULL_HANDLE, gImg.view(), sampler.handle()},
                            {kLayout[2], out.handle()}};
  filter.run(b, &push, uint32_t(n));
  return readBack(out, in.width, in.height);
}

VisibilityImage visibilityVulkan(vk::Context& ctx, const Scene& scene, const GBuffer& g, const VisibilitySetup& v,
                                 VisibilityTimes* times) {
  VisibilityTimes t;
  ShadowPassVk pass(ctx, scene, v.settings.size);
  const emu::Texture maps = shadowMapArray(pass.run(v.directions));  // maps read back, uploaded as one array
  t.shadowMs = pass.lastMs;
  VisibilityImage img;
  t.fitMs = timeMs([&] { img = visibilityFitVulkan(ctx, g, maps, v); });
  t.filterMs = timeMs([&] { img = visibilityFilterVulkan(ctx, g, img, v); });
  if (times) *times = t;
  return img;
}

}  // namespace shadetwin
