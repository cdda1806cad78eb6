// The glints ground truth, "G x D" (issue 17; Gamboa et al. 2018 §3.1-3.2): brute force over every
// texel of a pixel's footprint, integrated over the whole environment by Monte Carlo.
//
// Model (docs/DESIGN.md §12): texel t of the footprint P is a patch with micro-normal n_t (tangent
// space) and a Gaussian lobe g_sigma(w; n) = exp((w.n - 1) / sigma^2) / N(sigma); the footprint's
// NDF is D_P(h) = (1/|P|) sum_t g_sigma(h; n_t). The BRDF is the microfacet one,
//   f(wo, wi) = F(wi.h) G1(wo) G1(wi) D_P(h) / (4 cos_o cos_i),  h = normalize(wo + wi),
// F the conductor's Fresnel (complex IOR per channel), G1 Smith's Beckmann masking with alpha =
// sqrt(2) sigma about the macro normal. With `fgOutside` the F G factor is taken at the macro normal
// (F(wo.n) G1(wo) G1(reflect(wo, n))) and out of the integral: the technique's model, so a
// comparison isolates its SH and binning errors.
//
// Estimator: per sample one environment direction (the reference renderer's sampler) and one NDF
// direction (a texel of P uniformly, h from its lobe exactly, wi = reflect(wo about h)), balance
// heuristic. D_P(h) is summed over P's texels, skipping any block of a min-max hierarchy of the
// map's normals (8 x 8 and 64 x 64 texels) whose normals all lie farther from h than
// 1 - h.n > 40 sigma^2 (their lobes are below e^-40 of the peak there). Random numbers depend only
// on (seed, pixel, sample).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "inputs/normal_map.h"
#include "reference/ref_environment.h"
#include "reference/reference_brdf.h"
#include "scene/scene.h"

namespace shadetwin {

/// Per-block bounds of a map's normals: for 8 x 8 and 64 x 64 blocks, min and max of each
/// component (tangent space).
struct NormalBounds {
  uint32_t width = 0, height = 0;
  struct Level {
    uint32_t block, bw, bh;
    std::vector<float> lo, hi;  // 3 per block
  };
  Level level[2];
};
NormalBounds normalBounds(const NormalMap& map);

struct GlintPixel {
  const NormalMap* map = nullptr;
  const NormalBounds* bounds = nullptr;  // optional: no pruning without it
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // footprint texels, inclusive, unwrapped (the map tiles)
  reference::D3 t{1, 0, 0}, b{0, 1, 0}, n{0, 0, 1};  // tangent frame, world space, orthonormal
  reference::D3 wo{0, 0, 1};                         // towards the viewer, unit
  double sigma = 0.05;
  double eta[3] = {0.143, 0.374, 1.442}, k[3] = {3.983, 2.385, 1.603};  // gold
  bool fgOutside = false;
  uint64_t pixel = 0;  // for the random numbers
};

struct GxdResult {
  double rgb[3] = {0, 0, 0};
  double stdErr[3] = {0, 0, 0};  // of the mean
  uint64_t texelLobes = 0;       // texels visited (their normal tested against h) after the hierarchy's pruning
};

/// A G-buffer pixel (16 floats, passes/gbuffer.h) as the glints kernel sees it (shade/shade_glints.h):
/// its frame (n, t by Gram-Schmidt or any perpendicular, b by the handedness), wo towards `eye`, the
/// footprint by the shared glintFootprint on the same floats (map width x the material's scale), the
/// material's sigma and conductor. The pixel has geometry (G0.w != 0).
GlintPixel glintPixelOf(const float* gbufTexel, const float eye[3], const Material& m, const NormalMap& map,
                        const NormalBounds* bounds, uint64_t pixel);

/// L_o towards wo, `samples` MIS sample pairs.
GxdResult glintGxd(const GlintPixel& px, const reference::Environment& env, uint32_t samples, uint64_t seed);

/// D_P(h) for h in world space (the footprint's NDF; what the estimator sums); adds the texels
/// visited (not pruned by the hierarchy) to *lobes.
double glintFootprintNdf(const GlintPixel& px, reference::D3 h, uint64_t* lobes = nullptr);

/// The F G factor at the macro normal, per channel: F(wo.n) G1(wo) G1(reflect(wo, n)) (exact
/// Beckmann masking, alpha = sqrt(2) sigma); what `fgOutside` multiplies by.
std::array<double, 3> glintFgOutside(const GlintPixel& px);

/// Technique glints-gxd: the G x D image of a glints scene over a G-buffer (16 floats per pixel,
/// passes/gbuffer.h; drawn by either build, it holds the footprints' uv derivatives), RGBA, TBB over
/// pixels. Pixels with geometry: glintGxd of glintPixelOf with `samples` pairs (exact F G, or the
/// technique's F G outside); pixels without (G0.w == 0): the environment along the camera ray (the
/// kernel's background); with `only`, pixels it marks 0 are 0 (not shaded). Bits do not depend on the thread count.
/// Throws std::invalid_argument naming the material whose map cannot be made, or one without a
/// glints block.
struct GlintGxdOptions {
  uint32_t samples = 64;
  uint64_t seed = 1;
  bool fgOutside = false;
  const std::vector<uint8_t>* only = nullptr;  // optional, one per pixel: shade where non-zero
};
std::vector<float> glintGxdImage(const Scene& scene, const float* gbuffer, uint32_t width, uint32_t height,
                                 const reference::Environment& env, const GlintGxdOptions& opts);

/// The Gaussian lobe's normalisation N(sigma) = 2 pi sigma^2 (1 - exp(-2 / sigma^2)).
double glintLobeNorm(double sigma);

}  // namespace shadetwin
