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

struct VisibilityPassVk::Impl {
  vk::Context& ctx;
  ShadowPassVk shadow;
  vk::Sampler sampler;  // texelFetch only
  static constexpr VkDescriptorType kFit[4] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                               VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  static constexpr VkDescriptorType kFilter[3] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                  VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel fit, filter;
  Impl(vk::Context& c, const Scene& scene, uint32_t mapSize)
      : ctx(c), shadow(c, scene, mapSize), sampler(c, dataTextureSamplerInfo()),
        fit(c, vk::Stage::Compute, kSpv_visibility_fit_comp, kFit, sizeof(FitPush)),
        filter(c, vk::Stage::Compute, kSpv_visibility_filter_comp, kFilter, sizeof(FilterPush)) {}
};

VisibilityPassVk::VisibilityPassVk(vk::Context& ctx, const Scene& scene, uint32_t mapSize)
    : impl_(std::make_unique<Impl>(ctx, scene, mapSize)) {}
VisibilityPassVk::~VisibilityPassVk() = default;

VisibilityImage VisibilityPassVk::fit(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v) {
  Impl& m = *impl_;
  const size_t n = size_t(g.width) * g.height;
  vk::Buffer gbuf(m.ctx, n * 32), out(m.ctx, n * 64);
  for (size_t i = 0; i < n; ++i) std::memcpy(gbuf.as<float>() + 8 * i, g.texels.data() + i * kGbufFloats, 32);  // G0, G1
  vk::Image mapImg(m.ctx, VK_FORMAT_R32_SFLOAT, maps.width(), maps.height(), maps.layers(), maps.levels(), 4);
  const std::unique_ptr<vk::Image> data = dataTextureImage(m.ctx, *v.data);
  const FitPush push{maps.layers(), maps.width(), v.settings.fitCosine ? 0u : 1u, uint32_t(n), v.biasConst, v.biasSlope};
  const vk::Binding b[4] = {{Impl::kFit[0], gbuf.handle()},
                            {Impl::kFit[1], VK_NULL_HANDLE, mapImg.view(), m.sampler.handle()},
                            {Impl::kFit[2], VK_NULL_HANDLE, data->view(), m.sampler.handle()},
                            {Impl::kFit[3], out.handle()}};
  m.fit.run(b, &push, uint32_t(n));
  return readBack(out, g.width, g.height);
}

VisibilityImage VisibilityPassVk::filter(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v) {
  if (v.settings.filterRadius == 0) return in;
  Impl& m = *impl_;
  const emu::Texture ct = visibilityCoeffTexture(in), gt = gbufferPositionNormalTexture(g);
  vk::Image cImg(m.ctx, VK_FORMAT_R32G32B32A32_SFLOAT, ct.width(), ct.height(), ct.layers(), ct.levels(), 16);
  vk::Image gImg(m.ctx, VK_FORMAT_R32G32B32A32_SFLOAT, gt.width(), gt.height(), gt.layers(), gt.levels(), 16);
  const size_t n = size_t(in.width) * in.height;
  vk::Buffer out(m.ctx, n * 64);
  const FilterPush push{int32_t(in.width), int32_t(in.height), int32_t(v.settings.filterRadius),
                        v.settings.filterEdgeAware ? 1u : 0u, uint32_t(n), v.planeTolerance};
  const vk::Binding b[3] = {{Impl::kFilter[0], VK_NULL_HANDLE, cImg.view(), m.sampler.handle()},
                            {Impl::kFilter[1], VK_NULL_HANDLE, gImg.view(), m.sampler.handle()},
                            {Impl::kFilter[2], out.handle()}};
  m.filter.run(b, &push, uint32_t(n));
  return readBack(out, in.width, in.height);
}

VisibilityImage VisibilityPassVk::run(const GBuffer& g, const VisibilitySetup& v, VisibilityStats* times) {
  VisibilityStats t;
  const ShadowMaps sm = impl_->shadow.run(v.directions);
  const emu::Texture maps = shadowMapArray(sm);  // maps read back, uploaded as one array
  t.shadowMs = impl_->shadow.lastMs;
  for (const auto& mp : sm.maps) t.mapBytes += mp.size() * sizeof(float);
  for (const auto& l : maps.levels()) t.mapArrayBytes += l.size();
  VisibilityImage img;
  t.fitMs = timeMs([&] { img = fit(g, maps, v); });
  t.coeffBytes = size_t(g.width) * g.height * 64;  // the fit's storage buffer
  if (v.settings.filterRadius) {
    t.filterMs = timeMs([&] { img = filter(g, img, v); });
    t.filteredBytes = size_t(g.width) * g.height * 64;  // the filter's storage buffer
  }
  if (times) *times = t;
  return img;
}

}  // namespace shadetwin
