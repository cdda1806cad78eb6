// Host side of SH visibility from shadow maps (shade/visibility.h, issue 16): the K directions drawn
// from the environment's luminance (sin theta weighted, Hammersley points through the inversion
// sampler of inputs/env_lights.h), their orthographic shadow-map matrices, and the weights of the
// per-pixel least-squares fit, w_k = M+ y(omega_k) with M = sum_k y(omega_k) y(omega_k)^T, all in one
// RGBA32F data table that both builds read (row k: light matrix columns, omega_k, w_k).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "emu/texture.h"
#include "scene/scene.h"

namespace shadetwin {

struct VisibilitySettings {
  uint32_t maps = 16;    // K directions, one shadow map each
  uint32_t size = 1024;  // S x S texels per map
  bool fitCosine = true; // fit V max(0, n . omega) (the paper's choice) or V alone
  // Depth bias in units of one map texel (the depth a surface at 45 degrees climbs over a texel):
  // b0 = biasTexels / S + slope biasSlopeTexels / S * min(tan theta, 10) (shade/visibility.h).
  float biasTexels = 1.0f, biasSlopeTexels = 1.5f;
  double muRelative = 1e-4;  // eigenvalue filter of the pseudo-inverse: mu = muRelative * lambda_max
  // Spatial filter of the coefficient images: radius in pixels (0: none), edge-aware (same surface:
  // plane distance <= planeTolerance x the scene's bounding radius, normals within ~25 degrees) or box.
  uint32_t filterRadius = 2;
  bool filterEdgeAware = true;
  float planeTolerance = 0.02f;
};

struct VisibilitySetup {
  VisibilitySettings settings;
  std::vector<Vec3> directions;  // unit vectors from the scene towards the light, k order
  std::vector<Mat4> viewProj;    // world -> light clip space per direction (passes/shadow.h)
  std::shared_ptr<const emu::Texture> data;  // RGBA32F, 9 x K (shade/visibility.h visSample / visFit)
  std::array<double, 256> pinv{};            // the regularised pseudo-inverse (row-major 16 x 16)
  uint32_t rank = 0;                         // eigenvalues of M above mu
  bool uniformFallback = false;              // no positive luminance: directions uniform on the sphere
  float biasConst = 0, biasSlope = 0;        // the settings' bias in depth units
  float planeTolerance = 0;                  // the filter's plane distance in world units
};

/// The 16 real SH basis values of unit vector d (shade/visibility.h sh16Basis), in double.
std::array<double, 16> sh16BasisDouble(const Vec3& d);

/// The regularised pseudo-inverse of M = sum_k y(d_k) y(d_k)^T: sum over eigenpairs of lambda /
/// (lambda^2 + mu^2) u u^T, mu = muRelative * lambda_max (self-adjoint eigensolver of Eigen). The
/// Moore-Penrose inverse as mu -> 0; finite for any K (no NaN when K < 16 or directions coincide).
std::array<double, 256> sh16PseudoInverse(const std::vector<Vec3>& dirs, double muRelative, uint32_t* rank = nullptr);

/// Directions, matrices and the data table for `scene` under the RGBA32F environment `env` (level 0).
VisibilitySetup visibilitySetup(const Scene& scene, const emu::Texture& env, const VisibilitySettings& s);
/// The scene's visibility settings ("visibility" block).
VisibilitySettings visibilitySettings(const Scene& scene);

struct ShIrradiance;
/// The raw order-4 lighting SH per channel (r[16], g[16], b[16]) of shade/visibility.h VisLighting:
/// bands 0-2 from the E/pi coefficients divided by their band scale (1, 2/3, 1/4), band 3 as stored.
std::array<float, 48> visibilityLighting(const ShIrradiance& sh);

}  // namespace shadetwin
