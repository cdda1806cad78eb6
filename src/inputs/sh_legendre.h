// Host side of the high-order SH machinery for glints (issue 17): the recurrence coefficients the
// shared code reads (shade/sh_legendre.h), zonal-harmonic coefficients of the Gaussian roughness
// lobe, and the lobe's band limit.
#pragma once
#include <cstdint>
#include <vector>

#include "emu/texture.h"

namespace shadetwin {

/// The recurrence coefficients up to degree maxOrder as an RGBA32F (maxOrder + 1)^2 texture: texel
/// (l, m), m <= l: x = sqrt((2m + 1) / (2m)) at l = m >= 1, sqrt(2m + 3) at l = m + 1, a_lm
/// beyond; y = b_lm (l >= m + 2); computed in double, rounded once.
emu::Texture shLegendreCoefficients(uint32_t maxOrder);

/// Pbar_l^m(cos theta) for all 0 <= m <= l <= maxOrder in double, by the same recurrences with
/// the seeds carried as (mantissa, power of two) (no underflow at any order or angle): index
/// l (l + 1) / 2 + m. The reference the float recurrences are tested against.
std::vector<double> shLegendreDouble(uint32_t maxOrder, double theta);
/// The same from z = cos(theta) and s = sin(theta) >= 0 given separately (as the float recurrences
/// get them: the values near degree 300 change by ~l^2 times a change of z).
std::vector<double> shLegendreDouble(uint32_t maxOrder, double z, double s);

/// The Gaussian roughness lobe about a micro-normal m: g(w) = exp((w.m - 1) / sigma^2) / N with
/// N = 2 pi sigma^2 (1 - exp(-2 / sigma^2)), normalised on the sphere (about a Gaussian in the
/// angle with standard deviation sigma for small sigma). Its zonal-harmonic coefficients
/// z_l = integral g Y_l^0 over the sphere (m = +z), l = 0..maxOrder, from
/// z_l = sqrt((2l + 1) / (4 pi)) 2 pi / N * 2 e^(-1/s^2) i_l(1/s^2) (i_l the modified spherical Bessel
/// function, by Miller's backward recurrence, scaled: no overflow for sigma down to 1e-4). The SH
/// coefficients of the lobe about any m are z_l sqrt(4 pi / (2l + 1)) Y_l^m(m) (rotation of a
/// zonal function). sigma -> 0: z_l -> sqrt((2l + 1) / (4 pi)) (a delta).
std::vector<double> gaussianLobeZh(double sigma, uint32_t maxOrder);

/// The lobe's band limit: the smallest L with |z_l| sqrt(4 pi / (2l + 1)) < eps for every l > L
/// (the lobe's frequency content below eps; the paper's M_NDF with eps = 1e-6), capped at maxOrder.
uint32_t gaussianLobeBandLimit(double sigma, double eps, uint32_t maxOrder);

}  // namespace shadetwin
