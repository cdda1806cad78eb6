// Tangent-space normal maps for glints (issue 17, Gamboa et al. 2018 §6): procedural generators with
// seeds and any normal map OpenImageIO reads. A map tiles the surface's UVs (u along +x, v along +y
// of the map, z the macro normal); every generated map tiles seamlessly (all distances, lines and
// noise are periodic in the map's size).
//
// Generators (deterministic for a seed: std::mt19937, whose output the standard fixes, and our own
// conversions to uniform and normal variates):
//   flakes    — metallic flakes: a Voronoi diagram (toroidal distance) of `cells` x `cells` jittered
//               seeds; every texel takes its nearest seed's normal, tilted from +z by an angle with a
//               half-normal distribution of scale `spread` (radians; mean spread * sqrt(2 / pi)) at a
//               uniform azimuth: a narrow distribution of flat facets.
//   scratches — `count` straight scratches of random direction, length (0.1 to 0.6 of the map) and
//               width (`width` texels) on a flat (+z) base; a texel within a scratch is a V-groove
//               facet: tilted by `spread` radians across the scratch, towards its centre line.
//   brushed   — anisotropic noise: a periodic height field, sum of 64 cosine waves whose frequencies
//               are high across the brush (v) and low along it (u); normal = normalize(-dh/du,
//               -dh/dv, 1), the slopes scaled to an RMS slope of `spread`.
//   bumps     — isotropic noise: the same with frequencies of random direction in a band.
//   flat      — every normal +z (glints reduce to the smooth microfacet BRDF).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace shadetwin {

enum class NormalMapKind { Flat, Flakes, Scratches, Brushed, Bumps };

struct NormalMapSpec {
  NormalMapKind kind = NormalMapKind::Flakes;
  uint32_t size = 1024;  // square, 1 to 8192 (the range is 256 to 2048)
  uint32_t seed = 1;
  float spread = 0.15f;  // radians: flake tilt scale, scratch groove tilt, RMS slope of the noises
  uint32_t cells = 64;   // flakes: seeds per side
  uint32_t count = 40;   // scratches
  float width = 2.0f;    // scratches: texels
};

struct NormalMap {
  uint32_t width = 0, height = 0;
  std::vector<float> n;  // 3 floats per texel, unit length, rows top (v = 0) to bottom
  const float* at(uint32_t x, uint32_t y) const { return n.data() + 3 * (size_t(y) * width + x); }
};

/// Parses a kind name (flat, flakes, scratches, brushed, bumps); throws std::invalid_argument listing them.
NormalMapKind normalMapKind(const std::string& name);
const char* normalMapKindName(NormalMapKind k);

/// Generates the map; throws std::invalid_argument for a size outside [1, 8192] or a negative spread.
NormalMap generateNormalMap(const NormalMapSpec& spec);

/// A tangent-space normal map file (any OpenImageIO format; RGB in [0, 1] encodes 2c - 1, as
/// normal-map tools write them; float files with negative values are read as the components
/// themselves), each texel renormalised. Throws FileError naming the file for a missing or unreadable
/// file, fewer than three channels, or a texel of zero length or pointing below the surface (z <= 0).
NormalMap loadNormalMap(const std::string& path);

}  // namespace shadetwin
