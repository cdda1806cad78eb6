// `shadetwin reference`: the ground-truth renderer. Embree finds the first hit of each camera ray
// (one ray through each pixel centre, as the G-buffer samples the scene), TBB runs rows in parallel,
// and a Monte Carlo estimator with multiple importance sampling (balance heuristic) computes the
// shading integral  L_o = integral L_env(w_i) f(w_i, w_o) cos(theta_i) dw_i  with, per sample, one
// direction from the environment (piecewise-constant in luminance x sin(theta), inversion method)
// and one from the BRDF (reference_brdf.h). Optional visibility: an occlusion ray per direction.
// Random numbers depend only on (seed, pixel, sample): output bits do not depend on the thread count.
//
// The radiance L_env(w) is the environment's level 0 filtered bilinearly (repeat in u, clamp in v),
// intensity-scaled: exactly what a trilinear textureLod at LOD 0 returns, up to float rounding.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace shadetwin {

struct EnvImage {
  uint32_t width = 0, height = 0;
  const float* rgba = nullptr;  // level 0, rows top to bottom (v = 0 is +y)
};

struct ReferenceOptions {
  uint32_t spp = 64;
  uint64_t seed = 1;
  bool visibility = false;
  /// Called with the fraction done (0..1) as rows finish; from any thread, serialised.
  std::function<void(double)> progress;
};

/// Renders RGBA (alpha 1) at the scene's size. Throws std::invalid_argument naming the material
/// when a BRDF has no reference implementation.
std::vector<float> renderReference(const Scene& scene, const EnvImage& env, const ReferenceOptions& opts);

/// The best an order-4 SH can do for a G-buffer's visibility (issue 16, the FIS paper's Figure 5 (b)):
/// per pixel with geometry (G0.w != 0; `gbuffer`: 16 floats per pixel, G0 position, G1 normal), an
/// Embree occlusion ray along each of `rays` stratified directions (spherical Fibonacci set) from the
/// position offset 1e-4 along the normal, and the projection c_i = (4 pi / rays) sum_j V_j w_j
/// y_i(w_j) with w_j = max(0, n . w_j) (cosine fit) or 1, in double. 16 floats per pixel, the layout of
/// passes/visibility.h VisibilityImage; background pixels get the unoccluded projection.
std::vector<float> referenceVisibilitySh(const Scene& scene, const std::vector<float>& gbuffer, uint32_t width,
                                         uint32_t height, uint32_t rays, bool cosine);

/// CLI: loads the scene and environment, renders, writes the EXR (and a tone-mapped PNG), with a
/// progress bar on stderr.
struct ReferenceCommandOptions : SceneOverrides {  // the shared scene options it takes: --width, --height
  std::string scene = "scenes/bunny.json";
  std::string out;
  ReferenceOptions render;
};
int referenceCommand(const ReferenceCommandOptions& opts, std::ostream& log);

}  // namespace shadetwin
