// The NDF histogram summed-area table of a normal map (Gamboa et al. 2018 §4.1, §6.1; issue 17).
//
// Every texel's micro-normal falls in one bin of a T x P (theta, phi) grid (shade/ndf_histogram.h
// ndfBin, the shared code, so every build bins alike). For each bin the table holds the 2D
// summed-area table of the texels' counts, S_b(x, y) = #{texels (x', y') <= (x, y) in bin b}, stored
// modulo 2^16: a box's count is S(x1, y1) - S(x0 - 1, y1) - S(x1, y0 - 1) + S(x0 - 1, y0 - 1) in
// 16-bit modular arithmetic, exact whenever the true count is below 65,536 — so for every box of
// fewer than 65,536 texels (the paper's 576 MB for 1024^2 and 9 x 32 bins is exactly this table).
//
// Layout: texel-major, a ring's P sectors contiguous (one 64-byte row for P = 32), so a footprint
// reads four rows per ring. Rings no texel of the map falls in are not stored (their counts are 0
// everywhere): a map whose normals stay within a few rings of the pole — flakes, scratches, brushed
// metal — needs a fraction of the full table. `bytes()` is what is allocated.
//
// Tiled maps: a box may start at negative coordinates or be wider than the map; it is split at the
// map's edges into at most three distinct column ranges (head, whole periods, tail) times three row
// ranges, each counted with its multiplicity, still modulo 2^16, so the rule stays "exact when the
// box has fewer than 65,536 texels".
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "emu/texture.h"
#include "inputs/normal_map.h"

namespace shadetwin {

struct NdfBinningSpec {
  uint32_t rings = 9;     // T (theta bins)
  uint32_t sectors = 32;  // P (phi bins)
  float thetaMax = 1.57079633f;  // radians: rings are uniform in theta over [0, thetaMax]; beyond, the last ring
};

struct NdfSat {
  uint32_t width = 0, height = 0;
  NdfBinningSpec bins;
  std::vector<int32_t> slot;     // per ring: its index among the stored rings, -1 when empty
  uint32_t storedRings = 0;
  std::vector<uint16_t> table;   // [y][x][stored ring][sector]
  std::vector<uint32_t> totals;  // per bin (T x P): the whole map's count, exact
  double buildMs = 0;
  size_t bytes() const { return table.size() * sizeof(uint16_t); }
  /// The full table's bytes (every ring stored): width x height x T x P x 2.
  size_t fullBytes() const { return size_t(width) * height * bins.rings * bins.sectors * 2; }
};

/// The table's bytes before building it (all rings), for a width x height map.
size_t ndfSatFullBytes(uint32_t width, uint32_t height, const NdfBinningSpec& bins);

/// Builds the table. Throws std::invalid_argument for an empty map, zero bins or thetaMax outside
/// (0, pi], and std::length_error — before allocating it — when the table would need more than
/// `memoryLimit` bytes (0: the machine's available physical memory), saying how much it would need.
NdfSat buildNdfSat(const NormalMap& map, const NdfBinningSpec& bins, size_t memoryLimit = 0);

/// The bin of one normal (the shared ndfBin, scalar build).
uint32_t ndfBinOf(const NdfBinningSpec& bins, const float n[3]);

/// Counts of every bin (T x P values into `out`) over the inclusive texel box [x0, x1] x [y0, y1]
/// of the tiled map (any integers, x0 <= x1, y0 <= y1). Exact when the box has fewer than 65,536
/// texels; throws std::invalid_argument otherwise (the caller shrinks larger footprints).
void ndfBoxCounts(const NdfSat& sat, int64_t x0, int64_t y0, int64_t x1, int64_t y1, uint32_t* out);

/// The map ranges an unrolled inclusive range [a, b] of a tiled axis of n texels covers: head
/// [lo, hi] once, then [0, n - 1] `mult` times (whole periods), then a tail [0, t - 1] once; up to
/// three, returned count. The SAT's box counts and the G x D baseline split footprints with it.
struct TileSpan {
  int64_t lo, hi, mult;
};
int tileSpans(int64_t a, int64_t b, int64_t n, TileSpan out[3]);

/// The table as the shaders read it (shade/ndf_histogram.h ndfBoxCounts8): an RGBA32UI 2D array,
/// layer = stored ring, width x groups by height texels (groups = ceil(P / 8)); texel (x groups + g,
/// y) packs sectors 8g .. 8g + 7 of map texel (x, y), two per uint (the even sector low). Sectors
/// past P are 0.
emu::Texture ndfSatTexture(const NdfSat& sat);
inline uint32_t ndfSatGroups(const NdfBinningSpec& b) { return (b.sectors + 7) / 8; }

}  // namespace shadetwin
