// Shadow-map passes: orthographic depth-only renderings of the scene along arbitrary directions, each
// map sized to the scene's bounding sphere so every triangle lies inside the view volume (no clipping).
// Both builds run the shared vertex stage (shade/shadow.h) with the same host-built matrices.
#pragma once
#include <cstdint>
#include <vector>

#include "emu/device_profile.h"
#include "emu/raster.h"
#include "scene/scene.h"

namespace shadetwin {

struct ShadowMaps {
  uint32_t size = 0;              // each map is size x size D32F
  std::vector<Vec3> directions;   // unit vectors pointing from the scene towards the light
  std::vector<Mat4> viewProj;     // world -> light clip space, per direction
  std::vector<std::vector<float>> maps;  // per direction: size * size depths, rows top to bottom, cleared to 1
  const float* map(size_t i) const { return maps[i].data(); }
};

/// `count` directions spread evenly over the sphere (spherical Fibonacci lattice), deterministic.
std::vector<Vec3> sphereDirections(uint32_t count);

/// World -> light clip space for direction `dir`: x, y span the bounding sphere (centre c, radius r,
/// padded 2%) across [-1, 1]; depth = 1/2 - dot(dir, p - c) / (2 r), so the point nearest the light
/// has the smallest depth and the whole sphere maps into [0, 1]; w = 1.
Mat4 shadowViewProjection(const Scene& scene, const Vec3& dir);

struct ShadowStats {
  emu::RasterStats raster;
  double vertexMs = 0, rasterMs = 0;
};

/// Emulated shadow-map passes: every direction's map, every object one draw, in scene order.
/// Directions run in parallel (each has its own depth buffer, so bits do not depend on scheduling).
/// The second form renders into `target`, reusing its maps' storage.
ShadowMaps shadowEmu(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size,
                     const emu::DeviceProfile& dev, ShadowStats* stats = nullptr);
void shadowEmu(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size, const emu::DeviceProfile& dev,
               ShadowMaps& target, ShadowStats* stats = nullptr);

/// The same passes over the counting lane types (model/pass_counts.h): the same bits, operations counted on the
/// calling thread (which must keep the work on itself: the directions run through tbb::parallel_for).
ShadowMaps shadowCounted(const Scene& scene, const std::vector<Vec3>& directions, uint32_t size, const emu::DeviceProfile& dev,
                         ShadowStats* stats = nullptr);

}  // namespace shadetwin
