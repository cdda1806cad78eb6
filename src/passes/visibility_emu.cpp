#include "passes/visibility.h"

#include <cstring>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "lanes/instantiate.h"
#include "model/counted.h"
#include "util/pass_log.h"
#include "passes/shade.h"
#include "util/timer.h"

namespace shadetwin {

namespace {
// The drivers over either lane build (an instantiation namespace): the SIMD build (the emulator) or the counting one
// (the model).
#define VISIBILITY_LANES(Name, NS)                                                          \
  struct Name {                                                                             \
    using Float = shade::NS::Float;                                                         \
    using Int = shade::NS::Int;                                                             \
    using VisSettings = shade::NS::VisSettings;                                             \
    static auto fit(auto&&... a) { return shade::NS::visFit(a...); }                        \
    static auto filter(auto&&... a) { return shade::NS::visFilter(a...); }                  \
  };
VISIBILITY_LANES(X8Lanes, x8)
VISIBILITY_LANES(CountedLanes, counted)
#undef VISIBILITY_LANES

// The emulated kernels' loop: TBB over blocks of 8 pixels (row-major; tail lanes repeat the last
// pixel) in the compute stage's denormal mode; kernel(block) gives the 8 lanes' coefficients.
template <class Kernel>
VisibilityImage perPixelBlocks(uint32_t width, uint32_t height, const emu::DeviceProfile& dev, Kernel kernel) {
  VisibilityImage out;
  out.width = width, out.height = height;
  const size_t n = size_t(width) * height;
  out.coeffs.assign(n * 16, 0.0f);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, (n + 7) / 8, 64), [&](const tbb::blocked_range<size_t>& r) {
    emu::DenormalScope mode(dev.denormCompute == emu::DenormMode::Flush);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const auto c = kernel(b, n);
      const std::decay_t<decltype(c.a)> q[4] = {c.a, c.b, c.c, c.d};
      for (int l = 0; l < 8 && b * 8 + size_t(l) < n; ++l) {
        float* o = &out.coeffs[(b * 8 + size_t(l)) * 16];
        for (int j = 0; j < 4; ++j) o[4 * j] = q[j].x[l], o[4 * j + 1] = q[j].y[l], o[4 * j + 2] = q[j].z[l], o[4 * j + 3] = q[j].w[l];
      }
    }
  });
  return out;
}
template <class L>
VisibilityImage visibilityFitLanes(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v,
                                   const emu::DeviceProfile& dev) {
  using V3x = shade::V3<typename L::Float>;
  const shade::Sampler2D mapS = environmentSampler(maps, dev, false), dataS = environmentSampler(*v.data, dev, false);
  const typename L::VisSettings s{uint32_t(maps.layers()), maps.width(), v.settings.fitCosine ? shade::x8::kVisFitVCos : shade::x8::kVisFitV,
                                  v.biasConst, v.biasSlope};
  return perPixelBlocks(g.width, g.height, dev, [&](size_t b, size_t n) {
    V3x p, nrm;
    for (int l = 0; l < 8; ++l) {
      const float* t = g.texels.data() + std::min(b * 8 + size_t(l), n - 1) * kGbufFloats;
      p.x.set(l, t[0]), p.y.set(l, t[1]), p.z.set(l, t[2]);
      nrm.x.set(l, t[4]), nrm.y.set(l, t[5]), nrm.z.set(l, t[6]);
    }
    return L::fit(mapS, dataS, s, p, nrm);
  });
}

template <class L>
VisibilityImage visibilityFilterLanes(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v,
                                      const emu::DeviceProfile& dev) {
  using I8 = typename L::Int;
  const emu::Texture ct = visibilityCoeffTexture(in), gt = gbufferPositionNormalTexture(g);
  const shade::Sampler2D cs = environmentSampler(ct, dev, false), gs = environmentSampler(gt, dev, false);
  const uint32_t mode = v.settings.filterEdgeAware ? shade::x8::kVisFilterEdge : shade::x8::kVisFilterBox;
  return perPixelBlocks(in.width, in.height, dev, [&](size_t b, size_t n) {
    I8 x, y;
    for (int l = 0; l < 8; ++l) {
      const size_t i = std::min(b * 8 + size_t(l), n - 1);
      x.set(l, int32_t(i % in.width)), y.set(l, int32_t(i / in.width));
    }
    return L::filter(cs, gs, x, y, int(in.width), int(in.height), int(v.settings.filterRadius), mode, v.planeTolerance);
  });
}
}  // namespace

emu::Texture shadowMapArray(const ShadowMaps& maps) {
  const uint32_t S = maps.size, K = uint32_t(maps.maps.size());
  if (K == 0 || S == 0) throw std::invalid_argument("visibility: no shadow maps");
  std::vector<std::vector<uint8_t>> level(1, std::vector<uint8_t>(size_t(S) * S * K * 4));
  for (uint32_t k = 0; k < K; ++k) std::memcpy(level[0].data() + size_t(k) * S * S * 4, maps.maps[k].data(), size_t(S) * S * 4);
  return emu::Texture(emu::Format::R32F, S, S, K, std::move(level));
}

VisibilityImage visibilityFitEmu(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v,
                                 const emu::DeviceProfile& dev) {
  notePass("visibility-fit");
  return visibilityFitLanes<X8Lanes>(g, maps, v, dev);
}

VisibilityImage visibilityFitCounted(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v,
                                     const emu::DeviceProfile& dev) {
  return visibilityFitLanes<CountedLanes>(g, maps, v, dev);
}

emu::Texture visibilityCoeffTexture(const VisibilityImage& in) {
  const size_t n = size_t(in.width) * in.height;
  std::vector<std::vector<uint8_t>> level(1, std::vector<uint8_t>(n * 64));
  float* d = reinterpret_cast<float*>(level[0].data());
  for (size_t j = 0; j < 4; ++j)
    for (size_t p = 0; p < n; ++p) std::memcpy(d + (j * n + p) * 4, &in.coeffs[p * 16 + 4 * j], 16);
  return emu::Texture(emu::Format::RGBA32F, in.width, in.height, 4, std::move(level));
}

emu::Texture gbufferPositionNormalTexture(const GBuffer& g) {
  const size_t n = size_t(g.width) * g.height;
  std::vector<std::vector<uint8_t>> level(1, std::vector<uint8_t>(n * 32));
  float* d = reinterpret_cast<float*>(level[0].data());
  for (size_t j = 0; j < 2; ++j)
    for (size_t p = 0; p < n; ++p) std::memcpy(d + (j * n + p) * 4, &g.texels[p * kGbufFloats + 4 * j], 16);
  return emu::Texture(emu::Format::RGBA32F, g.width, g.height, 2, std::move(level));
}

VisibilityImage visibilityFilterEmu(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v,
                                    const emu::DeviceProfile& dev) {
  if (v.settings.filterRadius == 0) return in;
  notePass("visibility-filter");
  return visibilityFilterLanes<X8Lanes>(g, in, v, dev);
}

VisibilityImage visibilityFilterCounted(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v,
                                        const emu::DeviceProfile& dev) {
  if (v.settings.filterRadius == 0) return in;
  return visibilityFilterLanes<CountedLanes>(g, in, v, dev);
}

VisibilityImage visibilityEmu(const Scene& scene, const GBuffer& g, const VisibilitySetup& v, const emu::DeviceProfile& dev,
                              VisibilityStats* times) {
  VisibilityStats t;
  ShadowMaps sm;
  t.shadowMs = timeMs([&] { shadowEmu(scene, v.directions, v.settings.size, dev, sm); });
  const emu::Texture maps = shadowMapArray(sm);
  for (const auto& m : sm.maps) t.mapBytes += m.size() * sizeof(float);
  for (const auto& l : maps.levels()) t.mapArrayBytes += l.size();
  VisibilityImage img;
  t.fitMs = timeMs([&] { img = visibilityFitEmu(g, maps, v, dev); });
  t.coeffBytes = img.coeffs.size() * sizeof(float);
  if (v.settings.filterRadius) {
    t.filterMs = timeMs([&] { img = visibilityFilterEmu(g, img, v, dev); });
    t.filteredBytes = img.coeffs.size() * sizeof(float);
  }
  if (times) *times = t;
  return img;
}

}  // namespace shadetwin
