// Emulated rasterizer: clipping, viewport transform, sub-pixel snapping, the coverage
// (top-left) rule, D32F depth test (less-or-equal, early), plane-equation interpolation of depth
// and perspective-correct varyings at pixel centres, 2x2 quads with helper pixels, and a tiled,
// TBB-parallel loop whose output does not depend on the thread count (each tile runs its triangles
// in submission order). The device profile's `raster` block holds what differs between devices.
//
// What the lavapipe profile models (Mesa llvmpipe, read in lp_setup_tri.c, lp_state_setup.c and
// lp_bld_interp.c, and the draw module's draw_pipe_clip.c, re-implemented here; see docs/DESIGN.md
// "Rasterizer"):
//   clipping             no guard band: a triangle with a vertex outside x <= w, x >= -w, y <= w,
//                        y >= -w, z >= 0 or z <= w is clipped plane by plane in that order; a new
//                        vertex is interpolated from the endpoint nearer the plane, its window
//                        position computed with separate mul and add; the polygon is fanned (0, i, i+1)
//   window coordinates  x_w = x_c * (1 / w_c) * sx + tx   (1/w one IEEE division; * sx + tx fused)
//   snapping             X = rint((x_w - 0.5) * 2^subPixelBits), pixel centres at integer multiples
//   orientation          area = dx01 * dy20 - dx20 * dy01 on snapped positions; 0 culls; clockwise
//                        triangles are set up as (v0, v2, v1)
//   coverage             E_i(p) > 0, or E_i(p) = 0 on a top or left edge
//   plane equations      from the float window positions: ooa = 1 / (dx01 dy20 - dy01 dx20),
//                        dadx = da01 dy20 ooa - da20 dy01 ooa, dady = da20 dx01 ooa - da01 dx20 ooa,
//                        a0 = a_0 - (dadx (x_0 - 1/2) + dady (y_0 - 1/2))
//   per pixel (px, py)   a = fma(dady, py, fma(dadx, px, a0)); perspective varyings are set up
//                        premultiplied by 1/w and multiplied by 1 / (interpolated 1/w)
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "emu/device_profile.h"

namespace emu {

inline constexpr int kMaxVaryings = 16;

struct DrawInput {
  const float* clip = nullptr;      // 4 floats per vertex: clip-space position
  const float* varyings = nullptr;  // numVaryings floats per vertex, interpolated perspective-correct
  int numVaryings = 0;
  const uint32_t* indices = nullptr;  // 3 per triangle
  size_t triangles = 0;
  uint32_t drawId = 0;  // passed through to the fragment callback (material, object)
  bool cullBack = false;
};

/// One 2x2 quad of one triangle: pixels 0 (x, y), 1 (x+1, y), 2 (x, y+1), 3 (x+1, y+1).
struct Quad {
  int x = 0, y = 0;        // top-left pixel, both even
  uint32_t drawId = 0;
  uint32_t triangle = 0;   // index within the draw
  uint8_t covered = 0;     // bit i: pixel i inside the triangle
  uint8_t live = 0;        // bit i: covered, inside the framebuffer and passing the depth test
  bool frontFacing = true;
  float z[4] = {};
  float v[kMaxVaryings][4] = {};  // varyings at the 4 pixel centres (helper pixels included)
};

/// Fragment stage: writes out[k][i], output float k of pixel i (numOutputs floats per pixel).
using FragmentFn = std::function<void(const Quad&, float (*out)[4])>;

struct Framebuffer {
  uint32_t width = 0, height = 0;
  int numOutputs = 0;          // floats per pixel in `color`
  std::vector<float> depth;    // D32F, cleared to 1
  std::vector<float> color;    // numOutputs floats per pixel, pixel-major
  Framebuffer() = default;
  Framebuffer(uint32_t w, uint32_t h, int outputs, float clearDepth = 1.0f);
  /// Resizes (reusing the storage when it is large enough) and clears: depth to clearDepth, color
  /// to 0, in parallel. Passes that run every frame keep their framebuffer and reset it, as a GPU
  /// keeps its attachments and clears them.
  void reset(uint32_t w, uint32_t h, int outputs, float clearDepth = 1.0f);
};

// trianglesSpanning: set-up triangles whose extent contains a pixel-centre row of the target (a software rasterizer's
// set-up may reject the others before computing spans and interpolants; the performance model prints it, a lead for a
// set-up term of its raster cost, not used yet). trianglesOutside: triangles whose three vertices are all outside one
// clip plane (trivially rejected before set-up; counted in trianglesClipped too).
// blocks: per triangle, the 4x4-aligned pixel blocks holding a pixel it covers (llvmpipe's rasterizer runs the fragment
// stage, depth test included, once per such block whatever its coverage: lp_rast_tri.c's 4x4 stamps), summed.
// partialBlocks: of those, the blocks the triangle covers only partly (fewer than 16 pixels): llvmpipe shades a fully
// covered stamp as is and tests the triangle's edges per pixel of a partial one first (lp_rast_tri_tmp.h: block_full_4
// against do_block_4), so a pass of small and medium triangles, nearly all of whose stamps are partial, pays per stamp
// what one of large triangles pays per pixel.
struct RasterStats {
  size_t trianglesIn = 0, trianglesClipped = 0, trianglesCulled = 0, quads = 0, fragments = 0, trianglesSpanning = 0;
  size_t trianglesOutside = 0, blocks = 0, partialBlocks = 0;
  /// Several draws' statistics as one (every field: a pass that sums them field by field once left two out).
  RasterStats& operator+=(const RasterStats& o) {
    trianglesIn += o.trianglesIn, trianglesClipped += o.trianglesClipped, trianglesCulled += o.trianglesCulled;
    quads += o.quads, fragments += o.fragments, trianglesSpanning += o.trianglesSpanning, trianglesOutside += o.trianglesOutside;
    blocks += o.blocks, partialBlocks += o.partialBlocks;
    return *this;
  }
};

/// Rasterizes one draw into `fb` (depth test less-or-equal with depth writes), running `fs` on every
/// quad with at least one live pixel; outputs of live pixels are written. An empty `fs` is a
/// depth-only pipeline (no fragment shader: nothing is interpolated but depth). Parallel over 64x64 tiles.
void draw(const DeviceProfile& dev, Framebuffer& fb, const DrawInput& in, const FragmentFn& fs,
          RasterStats* stats = nullptr);

/// One lane of the fragment stage's SIMD vectors, the grouping of the sampler's per-vector decisions
/// (emu::textureLodBatch's vectorOf).
struct FragmentLane {
  uint32_t pixel;      // y * width + x
  uint32_t vector;     // the device vector (one run of one block for one primitive)
  uint32_t primitive;  // the run's primitive; the lane is masked when it is not the pixel's own
};
/// The fragment lanes of a width x height target whose pixel i is covered by primitive
/// primitiveOf[i] < primitives: per the profile, pixels in blocks of fragmentVectorW x fragmentVectorH,
/// one run (vector block * primitives + p) per primitive p covering part of the block. Lanes 0 .. w*h-1
/// are the pixels' own (lane i = pixel i); with MaskedFragmentLanes::Sample, every pixel of a block
/// that p does not cover follows as a masked lane of p's run.
std::vector<FragmentLane> fragmentLanes(const DeviceProfile& dev, uint32_t width, uint32_t height,
                                        const uint32_t* primitiveOf, uint32_t primitives);

/// Quad derivatives as the profile takes them: fine (per row / column) or coarse (row 0 / column 0).
/// v: values at the 4 pixels; returns d/dx and d/dy for each pixel.
void quadDerivatives(const DeviceProfile& dev, const float v[4], float ddx[4], float ddy[4]);

}  // namespace emu
