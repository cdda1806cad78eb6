// The directional lights of technique "env" (shade/shade_env.h): N samples of the environment's
// luminance drawn on the host (double precision) at the Hammersley points by the inversion method
// (marginal CDF over rows, conditional CDF within the row), one light per sample at its texel's
// centre with weight L_t / (N p). Both builds read the same light list.
#pragma once
#include <cstdint>
#include <vector>

#include "emu/texture.h"

namespace shadetwin {

struct EnvLights {
  /// 8 floats per light, as the GLSL struct EnvLight: direction (x, y, z, 0), weight (r, g, b, 0).
  std::vector<float> data;
  uint32_t count = 0;
};

/// `env`: RGBA32F equirectangular map, level 0 is used. Texel probability proportional to
/// max(luminance, 0) sin(theta); an environment with no positive luminance gives no lights.
EnvLights envLights(const emu::Texture& env, uint32_t n);

}  // namespace shadetwin
