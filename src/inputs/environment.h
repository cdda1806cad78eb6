// The environment map as a technique input: loaded from an HDRI (NaN/inf texels zeroed and counted),
// its MIP chain from the shared kernel, turned about +y by whole texel columns for animated frames.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "emu/texture.h"
#include "scene/scene.h"

namespace shadetwin {

/// The environment map as both builds sample it: RGBA32F with its full MIP chain from the shared kernel.
struct EnvironmentMap {
  uint32_t width = 0, height = 0;
  std::vector<std::vector<float>> levels;
  std::unique_ptr<emu::Texture> texture;
  size_t nonFinite = 0, negative = 0;  // texel values replaced by 0 / below 0 in the source (kept unless clamped)
};
/// The policy for a source HDRI's texel values (docs/DESIGN.md, docs/RESULTS.md "Bad input"): NaN and infinities become 0
/// and are counted; negative values are counted and kept (real data in the CC0 maps, and hard cases of the exactness
/// tests), or set to 0 with clampNegative (a scene's "environment": {"negative": "clamp"}). Returns {non-finite,
/// negative}.
std::array<size_t, 2> sanitizeTexels(std::vector<float>& texels, bool clampNegative);
/// Loads the HDRI with that policy (the counts logged when anything was replaced) and builds its MIP chain.
EnvironmentMap loadEnvironment(const std::string& path, std::ostream& log, bool clampNegative = false);
/// The scene's environment under the scene's policy (its "negative" key).
EnvironmentMap loadEnvironment(const Scene& scene, std::ostream& log);
/// The same from level-0 texels (RGBA, rows top to bottom); throws std::invalid_argument for an empty image.
EnvironmentMap environmentFromLevel0(std::vector<float> texels, uint32_t width, uint32_t height, bool clampNegative = false);
/// Whole columns an equirectangular map of `width` shifts for a turn of `degrees` about +y (rounded).
uint32_t environmentShift(uint32_t width, double degrees);
/// The environment turned about +y by whole columns (exact: texels move, none is resampled), with
/// its MIP chain rebuilt. Positive degrees turn it right-handedly about +y: a light at azimuth
/// atan2(x, -z) = phi moves to phi - degrees (its column u W to u W - shift).
EnvironmentMap rotateEnvironment(const EnvironmentMap& env, double degrees);
/// RGBA texels of a W x H map with each texel repeated scale x scale times ((W scale) x (H scale)).
std::vector<float> repeatTexels(const float* rgba, uint32_t width, uint32_t height, uint32_t scale);

}  // namespace shadetwin
