// The SH visibility fit pass (issue 16), both builds: per G-buffer pixel, the K shadow maps' tests
// fitted by an order-4 SH (shade/visibility.h visFit), 16 floats per pixel. The emulator runs the
// 8-lane build over blocks of 8 pixels (compute stage, TBB); Vulkan the compute shader
// src/shaders/visibility_fit.comp, one invocation per pixel.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "emu/device_profile.h"
#include "emu/texture.h"
#include "inputs/visibility.h"
#include "passes/gbuffer.h"
#include "passes/shadow.h"
#include "vk/context.h"

namespace shadetwin {

struct VisibilityImage {
  uint32_t width = 0, height = 0;
  std::vector<float> coeffs;  // 16 per pixel, rows top to bottom (shade/visibility.h Sh16 order)
  const float* at(uint32_t x, uint32_t y) const { return coeffs.data() + (size_t(y) * width + x) * 16; }
};

/// The maps as one R32F 2D array texture, layer k = direction k (what the fit kernels sample).
emu::Texture shadowMapArray(const ShadowMaps& maps);

VisibilityImage visibilityFitEmu(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v,
                                 const emu::DeviceProfile& dev);


/// The fit and the filter over the counting lane types (model/pass_counts.h): the same bits, operations counted
/// on the calling thread.
VisibilityImage visibilityFitCounted(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v,
                                     const emu::DeviceProfile& dev);
VisibilityImage visibilityFilterCounted(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v,
                                        const emu::DeviceProfile& dev);

/// The spatial filter of the coefficient images (shade/visibility.h visFilter); radius 0: none.
VisibilityImage visibilityFilterEmu(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v,
                                    const emu::DeviceProfile& dev);
/// The coefficient image and the G-buffer's G0, G1 as the RGBA32F 2D arrays the filter kernels read.
emu::Texture visibilityCoeffTexture(const VisibilityImage& in);
emu::Texture gbufferPositionNormalTexture(const GBuffer& g);

/// A frame's visibility passes: their times and the bytes of the images they write, as allocated:
/// the K maps (D32F, as the shadow pass leaves them), the same maps as the R32F array the fit
/// samples (a copy on both builds), the fit's coefficient image and the filter's output (16 floats
/// per pixel each; 0 when the filter is off).
struct VisibilityStats {
  double shadowMs = 0, fitMs = 0, filterMs = 0;
  size_t mapBytes = 0, mapArrayBytes = 0, coeffBytes = 0, filteredBytes = 0;
};
/// A frame's visibility on one build: the K shadow maps of v's directions, then the fit of `g`.
VisibilityImage visibilityEmu(const Scene& scene, const GBuffer& g, const VisibilitySetup& v, const emu::DeviceProfile& dev,
                              VisibilityStats* times = nullptr);

/// The same passes on a Vulkan device, built once (the shadow pass of `scene` at `mapSize`, the fit
/// and filter kernels) and run every frame; a moved object needs a new one (the scene's geometry is
/// uploaded at construction, as GbufferPassVk's).
class VisibilityPassVk {
 public:
  VisibilityPassVk(vk::Context& ctx, const Scene& scene, uint32_t mapSize);
  ~VisibilityPassVk();
  /// The K maps of v's directions, then the fit and the filter of `g`.
  VisibilityImage run(const GBuffer& g, const VisibilitySetup& v, VisibilityStats* times = nullptr);
  /// The stages alone, on given inputs (verify visibility).
  VisibilityImage fit(const GBuffer& g, const emu::Texture& maps, const VisibilitySetup& v);
  VisibilityImage filter(const GBuffer& g, const VisibilityImage& in, const VisibilitySetup& v);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadetwin
