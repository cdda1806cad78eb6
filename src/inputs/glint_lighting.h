// The glints lighting table (issue 17, shade/glint_lighting.h): the half-vector lighting's SH
// coefficients Lambda_lm for a grid of view directions, built by the shared kernel on either build.
// View (j, k), j = 0 .. rings - 1, k = 0 .. sectors - 1, is the equirectangular direction at
// (u, v) = (k / sectors, j / (rings - 1)) (the environment's frame; the paper's 65 x 128 grid by
// default), computed on the host in double and rounded once, so both builds get the same floats; the
// shading lookup interpolates between the four views around wo.
#pragma once
#include <cstdint>
#include <vector>

#include "emu/device_profile.h"
#include "emu/texture.h"

namespace shadetwin {
namespace vk { class Context; }

struct GlintLightingSpec {
  uint32_t order = 16;      // SH degree (<= shade kGlintMaxOrder = 64)
  uint32_t rings = 65;      // view directions in theta (poles included)
  uint32_t sectors = 128;   // in phi
  uint32_t level = 0;       // environment MIP level summed (its texels are the quadrature)
  // Rows of the level one kernel invocation sums (a band; 0: all). The bands' sums are added on the
  // host in band order, the same on both builds. glintBandRows picks it from a device's loop limit.
  uint32_t bandRows = 0;
};

/// Band rows for a device whose invocations may take `loopLimit` loop back-edges (0: unlimited): the
/// kernel takes about rows w (order + 5) + 6 (order + 1) of them for a level w texels wide (measured; the
/// bands keep rows w (order + 8) + 6 (order + 1) + 400 below the limit).
uint32_t glintBandRows(uint32_t loopLimit, uint32_t levelWidth, uint32_t levelHeight, uint32_t order);

struct GlintLightingTable {
  GlintLightingSpec spec;
  uint32_t coeffs = 0;     // (order + 1)^2
  std::vector<float> rgba;  // [view j sectors + k][coefficient l^2 + l + m]: RGB, A = 0
  double buildMs = 0;
  size_t bytes() const { return rgba.size() * sizeof(float); }
  const float* at(uint32_t view, uint32_t coeff) const { return &rgba[(size_t(view) * coeffs + coeff) * 4]; }
};

/// The lighting's band limit per view (M_light of the adaptive band limit, docs/DESIGN.md §12): the
/// largest degree l <= order whose relative band amplitude rho_l = sqrt(2l + 1) |Lambda_l| / |Lambda_00|
/// reaches eps in some channel (|Lambda_l| the norm of the band's 2l + 1 coefficients). rho_l k_l bounds
/// band l's share of the pixel against its band 0 for any NDF of lobes with zonal factors k_l (the
/// addition theorem bounds |D_l| by k_l sqrt((2l + 1) / 4 pi)). A black view: 0.
std::vector<uint32_t> glintLightBandLimits(const GlintLightingTable& t, double eps);

/// The view directions (xyz, 0), view-major.
std::vector<float> glintViewDirections(const GlintLightingSpec& spec);
/// The quadrature table of an equirectangular level of w x h texels: texel centre direction and
/// solid angle (2 pi / w)(pi / h) sin(theta), RGBA32F.
emu::Texture glintEnvDirections(uint32_t w, uint32_t h);

/// Throws std::invalid_argument for an order above 64, fewer than 2 rings, no sectors, a level the
/// environment lacks or an environment that is not RGBA32F.
GlintLightingTable glintLightingEmu(const emu::Texture& env, const emu::DeviceProfile& dev, const GlintLightingSpec& spec);
/// The same driver over the counting lane types (model/pass_counts.h): the same bits, operations counted on the
/// calling thread.
GlintLightingTable glintLightingCounted(const emu::Texture& env, const emu::DeviceProfile& dev, const GlintLightingSpec& spec);
GlintLightingTable glintLightingVulkan(vk::Context& ctx, const emu::Texture& env, const GlintLightingSpec& spec);

}  // namespace shadetwin
