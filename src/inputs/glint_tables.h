// The glints technique's SH quantities in double on the host (issue 17, docs/DESIGN.md §12): the
// half-vector lighting coefficients for a view direction, the bins' directions, and the double
// product of a footprint's histogram with them. This is the reference the shared kernels and their
// float tables are checked against, and the formulation the G x D baseline validates.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "emu/texture.h"
#include "inputs/ndf_histogram.h"
#include "reference/reference_brdf.h"
#include "reference/ref_environment.h"

namespace shadetwin {

/// Every real SH value of degree <= order at unit d (shade/sh_legendre.h conventions, sh16 order:
/// index l^2 + l + m), in double.
std::vector<double> shRealDouble(uint32_t order, reference::D3 d);

/// Lambda_lm(wo) = integral over wh of L(wi(wh)) 4 (wo.wh) Y_lm(wh) dwh, which by wh -> wi
/// (dwh = dwi / (4 wo.wh)) is  integral over wi of L(wi) Y_lm(normalize(wo + wi)) dwi,  summed on an
/// `nu` x `nv` equirectangular grid of wi (cell centres, bilinear radiance of the reference
/// environment). RGB: index 3 (l^2 + l + m) + channel. Directions wi within 1e-9 of -wo (h undefined,
/// zero measure) are skipped.
std::vector<double> glintLightingShDouble(const reference::Environment& env, reference::D3 wo, uint32_t order,
                                          uint32_t nu = 512, uint32_t nv = 256);

/// The rotated-lobe table (the paper's lobe table, 65 x 128 directions by default): for each direction of
/// a rings x sectors grid (glintViewDirections' grid: row j at v = j / (rings - 1), poles included, column
/// k at u = k / sectors) the real SH Y_lm of degree <= order there, from shRealDouble rounded once;
/// RGBA32F, four coefficients (index 4 q .. 4 q + 3, l^2 + l + m order) per texel, ceil((order + 1)^2 / 4)
/// texels per row, one row per direction. The kernel interpolates it bilinearly at each bin's world
/// direction and multiplies by the lobe's k_l (so one table serves every roughness).
emu::Texture glintLobeTable(uint32_t order, uint32_t rings, uint32_t sectors);

/// The tangent-space direction a bin stands for: its centre (theta, phi) = ((t + 1/2) thetaMax / T,
/// (p + 1/2) 2 pi / P).
reference::D3 ndfBinDirection(const NdfBinningSpec& bins, uint32_t ring, uint32_t sector);

/// The double product for one pixel: sum over bins b of (counts_b / total) sum_l k_l sum_m
/// Lambda_lm Y_lm(d_b), k_l = z_l sqrt(4 pi / (2l + 1)) the lobe's zonal factor (gaussianLobeZh),
/// d_b the bin's direction through the frame (t, b, n) into world space, to degree `order`. RGB;
/// the FG / (4 cos_o) factor is the caller's.
std::array<double, 3> glintShDoubleProduct(const std::vector<double>& lightingSh, const std::vector<uint32_t>& counts,
                                           const NdfBinningSpec& bins, reference::D3 t, reference::D3 b, reference::D3 n,
                                           double sigma, uint32_t order);

}  // namespace shadetwin
