#include "emu/raster.h"

#include <stdexcept>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "emu/lanes.h"

namespace emu {

Framebuffer::Framebuffer(uint32_t w, uint32_t h, int outputs, float clearDepth) { reset(w, h, outputs, clearDepth); }

void Framebuffer::reset(uint32_t w, uint32_t h, int outputs, float clearDepth) {
  width = w, height = h, numOutputs = outputs;
  const size_t n = size_t(w) * h, per = size_t(outputs);
  depth.resize(n);
  color.resize(n * per);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
    std::fill(depth.begin() + std::ptrdiff_t(r.begin()), depth.begin() + std::ptrdiff_t(r.end()), clearDepth);
    std::fill(color.begin() + std::ptrdiff_t(r.begin() * per), color.begin() + std::ptrdiff_t(r.end() * per), 0.0f);
  });
}

void quadDerivatives(const DeviceProfile& dev, const float v[4], float ddx[4], float ddy[4]) {
  if (dev.raster.fineDerivatives) {
    ddx[0] = ddx[1] = v[1] - v[0];
    ddx[2] = ddx[3] = v[3] - v[2];
    ddy[0] = ddy[2] = v[2] - v[0];
    ddy[1] = ddy[3] = v[3] - v[1];
  } else {
    ddx[0] = ddx[1] = ddx[2] = ddx[3] = v[1] - v[0];
    ddy[0] = ddy[1] = ddy[2] = ddy[3] = v[2] - v[0];
  }
}

namespace {

constexpr int kTile = 64;

// A vertex after the viewport transform: window x, y, z, 1/w, and its varyings premultiplied by 1/w.
struct WinVertex {
  float x, y, z, oow;
  float v[kMaxVaryings];
};

struct ClipVertex {
  float c[4];
  float v[kMaxVaryings];
  bool original;  // a vertex of the draw (window position from the vertex stage), not made by the clipper
};

struct Plane3 {
  float a0, dadx, dady;
};

struct TriSetup {
  int64_t X[3], Y[3];  // snapped positions (sub-pixel units, pixel centres at multiples of 2^bits)
  bool topLeft[3];
  int x0, y0, x1, y1;  // pixel bounding box, inclusive, clipped to the framebuffer
  bool front;
  uint32_t triangle;
  Plane3 z, w;
  Plane3 v[kMaxVaryings];
};

float madd(bool fused, float a, float b, float c) { return fused ? std::fma(a, b, c) : a * b + c; }

WinVertex toWindow(bool fused, const ClipVertex& cv, int nv, float sx, float tx, float sy, float ty) {
  WinVertex w;
  w.oow = 1.0f / cv.c[3];
  w.x = madd(fused, cv.c[0] * w.oow, sx, tx);
  w.y = madd(fused, cv.c[1] * w.oow, sy, ty);
  w.z = madd(fused, cv.c[2] * w.oow, 1.0f, 0.0f);  // depth range [0, 1]
  for (int k = 0; k < nv; ++k) w.v[k] = cv.v[k] * w.oow;
  return w;
}

// Clip planes as dot products with the clip-space position, in the order a clipper visits them:
// x <= w, x >= -w, y <= w, y >= -w, z >= 0 (Vulkan's [0, w] depth), z <= w.
constexpr float kPlanes[6][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 0}, {0, 0, -1, 1}};

// Four products summed left to right, each rounded (the C dot product of Mesa's clipper; a
// multiplication by 0 of an infinite coordinate gives NaN, which discards the triangle).
float planeDistance(const float c[4], const float p[4]) { return c[0] * p[0] + c[1] * p[1] + c[2] * p[2] + c[3] * p[3]; }

// Outcode: bit i set when the vertex is outside plane i (exact comparisons, as the vertex stage makes them).
unsigned outcode(const float c[4], bool xy) {
  unsigned m = 0;
  if (xy) {
    m |= unsigned(c[0] > c[3]) << 0;
    m |= unsigned(0.0f > c[0] + c[3]) << 1;
    m |= unsigned(c[1] > c[3]) << 2;
    m |= unsigned(0.0f > c[1] + c[3]) << 3;
  }
  m |= unsigned(0.0f > c[2]) << 4;
  m |= unsigned(c[2] > c[3]) << 5;
  return m;
}

// new = from + t (to - from), per component with separate mul and add.
void lerpVertex(ClipVertex& dst, float t, const ClipVertex& from, const ClipVertex& to, int nv) {
  for (int k = 0; k < 4; ++k) dst.c[k] = from.c[k] + t * (to.c[k] - from.c[k]);
  for (int k = 0; k < nv; ++k) dst.v[k] = from.v[k] + t * (to.v[k] - from.v[k]);
  dst.original = false;
}

constexpr int kMaxPoly = 16;

// Sutherland-Hodgman over the planes in `mask`, in plane order; poly[0..2] in, polygon out (returns
// its size, 0 when nothing is left). Re-implements the semantics of Mesa's draw_pipe_clip.c:
// a vertex is kept when its distance is >= 0; a crossing edge gets a new vertex with
// t = d_near / (d_near - d_far) measured from one endpoint (the nearer one with clipFromNearer,
// else the outside one); a NaN or infinite distance discards the triangle; the polygon keeps
// its first vertex first (the next pass starts from out[0]).
int clipPolygon(const DeviceProfile::Raster& r, ClipVertex* poly, unsigned mask, int nv) {
  ClipVertex bufA[kMaxPoly + 1], bufB[kMaxPoly + 1];
  ClipVertex *in = bufA, *out = bufB;
  std::copy(poly, poly + 3, in);
  int n = 3;
  while (mask && n >= 3) {
    const int plane = std::countr_zero(mask);
    mask &= mask - 1;
    const float* P = kPlanes[plane];
    in[n] = in[0];
    float dPrev = planeDistance(in[0].c, P);
    if (!std::isfinite(dPrev)) return 0;
    int m = 0;
    for (int i = 1; i <= n; ++i) {
      const ClipVertex &prev = in[i - 1], &cur = in[i];
      const float d = planeDistance(cur.c, P);
      if (!std::isfinite(d)) return 0;
      bool crosses;
      if (dPrev >= 0.0f) {
        out[m++] = prev;
        crosses = d < 0.0f;
      } else {
        crosses = !(d < 0.0f);
      }
      if (crosses) {
        if (m >= kMaxPoly) return 0;
        const float denom = d - dPrev;
        ClipVertex& made = out[m++];
        if (d < 0.0f) {  // leaving: prev inside, cur outside
          if (!r.clipFromNearer || -d < dPrev) lerpVertex(made, d / denom, cur, prev, nv);
          else lerpVertex(made, -dPrev / denom, prev, cur, nv);
        } else {  // entering: prev outside, cur inside
          if (!r.clipFromNearer || -dPrev < d) lerpVertex(made, -dPrev / denom, prev, cur, nv);
          else lerpVertex(made, d / denom, cur, prev, nv);
        }
      }
      if (m >= kMaxPoly) return 0;
      dPrev = d;
    }
    std::swap(in, out);
    n = m;
  }
  if (n < 3) return 0;
  std::copy(in, in + n, poly);
  return n;
}

bool setupTriangle(const DeviceProfile& dev, const Framebuffer& fb, const WinVertex* in[3], int nv, bool cullBack,
                   uint32_t triangle, TriSetup& t) {
  const float scale = float(1 << dev.raster.subPixelBits);
  int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i) {
    const float fx = (in[i]->x - 0.5f) * scale, fy = (in[i]->y - 0.5f) * scale;
    if (!(std::fabs(fx) < 1.0e9f && std::fabs(fy) < 1.0e9f)) return false;  // outside the fixed-point range
    X[i] = int64_t(std::nearbyint(fx));
    Y[i] = int64_t(std::nearbyint(fy));
  }
  const int64_t area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
  if (area == 0) return false;
  t.front = area > 0;  // counter-clockwise in Vulkan's framebuffer coordinates
  if (cullBack && !t.front) return false;
  int order[3] = {0, 1, 2};
  if (area < 0) {
    if (dev.raster.cwSwapsLast) order[1] = 2, order[2] = 1;
    else order[0] = 1, order[1] = 0;
  }
  const WinVertex* v[3] = {in[order[0]], in[order[1]], in[order[2]]};
  for (int i = 0; i < 3; ++i) t.X[i] = X[order[i]], t.Y[i] = Y[order[i]];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int64_t dy = t.Y[j] - t.Y[i], dx = t.X[j] - t.X[i];
    t.topLeft[i] = dy > 0 || (dy == 0 && dx < 0);
  }
  const int bits = dev.raster.subPixelBits;
  const int64_t one = int64_t(1) << bits;
  auto floorDiv = [&](int64_t a) { return a >= 0 ? a / one : -((-a + one - 1) / one); };
  int64_t minX = std::min({t.X[0], t.X[1], t.X[2]}), maxX = std::max({t.X[0], t.X[1], t.X[2]});
  int64_t minY = std::min({t.Y[0], t.Y[1], t.Y[2]}), maxY = std::max({t.Y[0], t.Y[1], t.Y[2]});
  t.x0 = int(std::max<int64_t>(floorDiv(minX), 0));
  t.y0 = int(std::max<int64_t>(floorDiv(minY), 0));
  t.x1 = int(std::min<int64_t>(floorDiv(maxX) + 1, int64_t(fb.width) - 1));
  t.y1 = int(std::min<int64_t>(floorDiv(maxY) + 1, int64_t(fb.height) - 1));
  if (t.x0 > t.x1 || t.y0 > t.y1) return false;
  t.triangle = triangle;
  // Plane equations from the float window positions (Mesa lp_state_setup.c order of operations).
  const float x0c = v[0]->x - 0.5f, y0c = v[0]->y - 0.5f;
  const float dx01 = v[0]->x - v[1]->x, dy01 = v[0]->y - v[1]->y;
  const float dx20 = v[2]->x - v[0]->x, dy20 = v[2]->y - v[0]->y;
  const float e = dx01 * dy20, f = dy01 * dx20;
  const float ooa = 1.0f / (e - f);
  const float dx20o = dx20 * ooa, dy20o = dy20 * ooa, dx01o = dx01 * ooa, dy01o = dy01 * ooa;
  auto coef = [&](float a0, float a1, float a2) {
    const float da01 = a0 - a1, da20 = a2 - a0;
    Plane3 p;
    p.dadx = da01 * dy20o - da20 * dy01o;
    p.dady = da20 * dx01o - da01 * dx20o;
    p.a0 = a0 - (p.dadx * x0c + p.dady * y0c);
    return p;
  };
  t.z = coef(v[0]->z, v[1]->z, v[2]->z);
  t.w = coef(v[0]->oow, v[1]->oow, v[2]->oow);
  for (int k = 0; k < nv; ++k) t.v[k] = coef(v[0]->v[k], v[1]->v[k], v[2]->v[k]);
  return true;
}

inline float interp(bool fused, const Plane3& p, float px, float py) {
  return madd(fused, p.dady, py, madd(fused, p.dadx, px, p.a0));
}

// Depth-only pipelines (no fragment shader): coverage, depth and the depth test are per pixel and
// nothing is interpolated but depth, so one triangle's pixels in a tile run a row at a time, 8
// pixels per step, with the operations of the quad loop below: the same int64 edge functions
// A PX - B PY + C (stepped by A 2^bits per pixel), the same plane equation madd(dady, py,
// madd(dadx, px, a0)) per pixel, depth test less-or-equal in submission order. Pixels outside the
// bounding box are never covered, so the span is box ∩ tile. Quads (for the stats) are the 2x2
// blocks with a covered pixel, as the quad loop counts them. Bits equal the quad loop's
// (tests/raster_test.cpp DepthOnlyRowPathEqualsTheQuadLoop).
constexpr int kSpan = 8;
using I64x8 = vec_t<int64_t, kSpan>;
using F32x8 = vec_t<float, kSpan>;
using I32x8 = vec_t<int32_t, kSpan>;

// Bit i set where lane i is true (-1). A speed detail only: the portable loop gives the same bits.
inline uint32_t laneBits(I32x8 m) {
#if defined(__AVX__)
  return uint32_t(__builtin_ia32_movmskps256((vec_t<float, kSpan>)m));
#else
  uint32_t b = 0;
  for (int i = 0; i < kSpan; ++i) b |= uint32_t(m[i] & 1) << i;
  return b;
#endif
}

template <bool Fused>
void depthOnlyTriangle(const TriSetup& s, int bits, int tx0, int ty0, int tx1, int ty1, Framebuffer& fb,
                       size_t& quads, size_t& frags) {
  const int x0 = std::max(s.x0, tx0), x1 = std::min(s.x1, tx1), y0 = std::max(s.y0, ty0), y1 = std::min(s.y1, ty1);
  if (x0 > x1 || y0 > y1) return;
  int64_t A[3], B[3], C[3];
  for (int e = 0; e < 3; ++e) {
    const int j = e == 2 ? 0 : e + 1;
    A[e] = s.Y[j] - s.Y[e];
    B[e] = s.X[j] - s.X[e];
    C[e] = B[e] * s.Y[e] - A[e] * s.X[e] + (s.topLeft[e] ? 1 : 0);
  }
  const int64_t step = int64_t(1) << bits;
  I64x8 lane64;
  F32x8 laneF;
  for (int i = 0; i < kSpan; ++i) lane64[i] = i, laneF[i] = float(i);
  I64x8 stepE[3];
  for (int e = 0; e < 3; ++e) stepE[e] = lane64 * (A[e] * step);
  const F32x8 dadx = F32x8{} + s.z.dadx, a0 = F32x8{} + s.z.a0;
  uint64_t prevRow = 0;    // coverage of the even row above, for the quad count
  for (int py = y0; py <= y1; ++py) {
    const int64_t PY = int64_t(py) << bits;
    int64_t rowE[3];
    for (int e = 0; e < 3; ++e) rowE[e] = A[e] * (int64_t(x0) << bits) - B[e] * PY + C[e];
    float* depth = fb.depth.data() + size_t(py) * fb.width;
    const F32x8 dady = F32x8{} + s.z.dady, fy = F32x8{} + float(py);
    uint64_t rowMask = 0;
    // Chunks of 8 pixels aligned to 8: inside one tile (tiles are 64-aligned), so a whole chunk is
    // this thread's to load and store; pixels of a chunk outside the box are outside the triangle
    // and stay uncovered. Only a chunk past the framebuffer's last column (width not a multiple
    // of 8) is cut to its pixels.
    const int cx0 = x0 & ~(kSpan - 1);  // coverage bit k of the row is pixel cx0 + k (even: quads pair bits 2j, 2j+1)
    for (int e = 0; e < 3; ++e) rowE[e] -= int64_t(x0 - cx0) * A[e] * step;
    for (int px = cx0; px <= x1; px += kSpan) {
      const int n = std::min(kSpan, int(fb.width) - px);
      const I64x8 e0 = rowE[0] + stepE[0], e1 = rowE[1] + stepE[1], e2 = rowE[2] + stepE[2];
      for (int e = 0; e < 3; ++e) rowE[e] += kSpan * A[e] * step;
      const I32x8 in = __builtin_convertvector((e0 > 0) & (e1 > 0) & (e2 > 0), I32x8);
      const F32x8 fx = laneF + float(px);
      F32x8 z;
      if constexpr (Fused) {
        for (int i = 0; i < kSpan; ++i) z[i] = __builtin_fmaf(dady[i], fy[i], __builtin_fmaf(dadx[i], fx[i], a0[i]));
      } else {
        z = dady * fy + (dadx * fx + a0);
      }
      F32x8 d;
      if (n == kSpan) std::memcpy(&d, depth + px, sizeof d);
      else for (int i = 0; i < kSpan; ++i) d[i] = i < n ? depth[px + i] : 0.0f;
      const I32x8 live = in & (z <= d);
      const F32x8 out = live ? z : d;
      if (n == kSpan) std::memcpy(depth + px, &out, sizeof out);
      else for (int i = 0; i < n; ++i) depth[px + i] = out[i];
      const uint32_t lanes = (1u << n) - 1u;  // a triangle may cover pixels past the last column (guard band)
      rowMask |= uint64_t(laneBits(in) & lanes) << (px - cx0);
      frags += size_t(std::popcount(laneBits(live) & lanes));
    }
    // A quad row is complete at its odd row, or at the span's last row (the quad's other row then
    // lies outside the box or the tile and is not covered).
    const bool odd = (py & 1) != 0;
    if (odd || py == y1) {
      const uint64_t m = odd ? (prevRow | rowMask) : rowMask;
      quads += size_t(std::popcount((m | (m >> 1)) & 0x5555555555555555ull));
      prevRow = 0;
    } else {
      prevRow = rowMask;
    }
  }
}

}  // namespace

void draw(const DeviceProfile& dev, Framebuffer& fb, const DrawInput& in, const FragmentFn& fs, RasterStats* stats) {
  const int nv = in.numVaryings;
  const float sx = float(fb.width) * 0.5f, sy = float(fb.height) * 0.5f;
  // Setup, in submission order (clipped triangles become fans, in order).
  std::unique_ptr<TriSetup[]> tris(new TriSetup[in.triangles]);  // default-initialized: ok[t] says which are set up
  std::vector<uint8_t> ok(in.triangles, 0);
  std::vector<std::vector<TriSetup>> extra(in.triangles);  // clipped: fan pieces
  std::atomic<size_t> clipped{0}, culled{0};
  tbb::parallel_for(size_t(0), in.triangles, [&](size_t t) {
    DenormalScope mode(false);
    ClipVertex cv[kMaxPoly];
    const bool clipXY = dev.raster.clip == DeviceProfile::Raster::Clip::DrawModule;
    unsigned any = 0, all = 0x3f;
    for (int i = 0; i < 3; ++i) {
      const uint32_t idx = in.indices[3 * t + size_t(i)];
      std::memcpy(cv[i].c, in.clip + 4 * size_t(idx), 16);
      for (int k = 0; k < nv; ++k) cv[i].v[k] = in.varyings[size_t(idx) * size_t(nv) + size_t(k)];
      cv[i].original = true;
      const unsigned code = outcode(cv[i].c, clipXY);
      any |= code, all &= code;
    }
    const bool fusedVp = dev.raster.viewportFma;
    if (!any) {
      WinVertex w[3];
      for (int i = 0; i < 3; ++i) w[i] = toWindow(fusedVp, cv[i], nv, sx, sx, sy, sy);
      const WinVertex* p[3] = {&w[0], &w[1], &w[2]};
      ok[t] = setupTriangle(dev, fb, p, nv, in.cullBack, uint32_t(t), tris[t]);
      if (!ok[t]) culled.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    clipped.fetch_add(1, std::memory_order_relaxed);
    if (all) return;  // every vertex outside one plane
    const int n = clipPolygon(dev.raster, cv, any, nv);
    if (n < 3) return;
    WinVertex w[kMaxPoly];
    for (int i = 0; i < n; ++i)
      w[i] = toWindow(cv[i].original ? fusedVp : dev.raster.clipViewportFma, cv[i], nv, sx, sx, sy, sy);
    // The polygon as a fan around its first vertex: (0, i, i + 1).
    for (int i = 1; i + 1 < n; ++i) {
      const WinVertex* p[3] = {&w[0], &w[i], &w[i + 1]};
      TriSetup s;
      if (setupTriangle(dev, fb, p, nv, in.cullBack, uint32_t(t), s)) extra[t].push_back(s);
    }
  });
  // Binning into 64x64 tiles, in submission order.
  const int tilesX = int((fb.width + kTile - 1) / kTile), tilesY = int((fb.height + kTile - 1) / kTile);
  std::vector<std::vector<const TriSetup*>> bins(size_t(tilesX) * size_t(tilesY));
  auto bin = [&](const TriSetup& s) {
    for (int ty = s.y0 / kTile; ty <= s.y1 / kTile; ++ty)
      for (int tx = s.x0 / kTile; tx <= s.x1 / kTile; ++tx) bins[size_t(ty) * size_t(tilesX) + size_t(tx)].push_back(&s);
  };
  for (size_t t = 0; t < in.triangles; ++t) {
    if (ok[t]) bin(tris[t]);
    for (auto& s : extra[t]) bin(s);
  }
  std::atomic<size_t> quadCount{0}, fragCount{0};
  const bool fused = dev.raster.interpFma;
  const bool flush = dev.denormFragment == DenormMode::Flush;
  const int bits = dev.raster.subPixelBits;
  tbb::parallel_for(size_t(0), bins.size(), [&](size_t b) {
    if (bins[b].empty()) return;
    DenormalScope mode(flush);
    const int tx0 = int(b % size_t(tilesX)) * kTile, ty0 = int(b / size_t(tilesX)) * kTile;
    const int tx1 = std::min(tx0 + kTile, int(fb.width)) - 1, ty1 = std::min(ty0 + kTile, int(fb.height)) - 1;
    size_t quads = 0, frags = 0;
    if (!fs) {  // depth-only pipeline
      for (const TriSetup* s : bins[b]) {
        if (fused) depthOnlyTriangle<true>(*s, bits, tx0, ty0, tx1, ty1, fb, quads, frags);
        else depthOnlyTriangle<false>(*s, bits, tx0, ty0, tx1, ty1, fb, quads, frags);
      }
      quadCount.fetch_add(quads, std::memory_order_relaxed);
      fragCount.fetch_add(frags, std::memory_order_relaxed);
      return;
    }
    Quad q;
    q.drawId = in.drawId;
    float out[4 * 64][4];  // up to 64 outputs
    for (const TriSetup* s : bins[b]) {
      const int qx0 = std::max(s->x0, tx0) & ~1, qy0 = std::max(s->y0, ty0) & ~1;
      const int qx1 = std::min(s->x1, tx1), qy1 = std::min(s->y1, ty1);
      // Edge e from vertex e to e+1: E = A (PX - X_e) - B (PY - Y_e) = A PX - B PY + C, exact in
      // int64. A pixel is inside when E > 0, or E = 0 on a top or left edge: with integer E that is
      // E + [top-left] > 0, folded into C.
      int64_t A[3], B[3], C[3];
      for (int e = 0; e < 3; ++e) {
        const int j = e == 2 ? 0 : e + 1;
        A[e] = s->Y[j] - s->Y[e];
        B[e] = s->X[j] - s->X[e];
        C[e] = B[e] * s->Y[e] - A[e] * s->X[e] + (s->topLeft[e] ? 1 : 0);
      }
      const int64_t step = int64_t(1) << bits;
      // Pixels of the quad outside the tile are never covered (their tile covers them).
      const bool clipX = qx0 < tx0 || qx1 + 1 > tx1, clipY = qy0 < ty0 || qy1 + 1 > ty1;
      for (int qy = qy0; qy <= qy1; qy += 2) {
        const int64_t PY = int64_t(qy) << bits;
        int64_t rowE[3];
        for (int e = 0; e < 3; ++e) rowE[e] = A[e] * (int64_t(qx0) << bits) - B[e] * PY + C[e];
        for (int qx = qx0; qx <= qx1; qx += 2) {
          uint8_t covered = 0;
          for (int i = 0; i < 4; ++i) {
            const int64_t dx = (i & 1) ? step : 0, dy = (i >> 1) ? step : 0;
            const bool in = (rowE[0] + A[0] * dx - B[0] * dy > 0) & (rowE[1] + A[1] * dx - B[1] * dy > 0) &
                            (rowE[2] + A[2] * dx - B[2] * dy > 0);
            covered |= uint8_t(unsigned(in) << i);
          }
          for (int e = 0; e < 3; ++e) rowE[e] += 2 * A[e] * step;
          if (clipX || clipY)
            for (int i = 0; i < 4; ++i) {
              const int px = qx + (i & 1), py = qy + (i >> 1);
              if (px > tx1 || py > ty1 || px < tx0 || py < ty0) covered &= uint8_t(~(1u << i));
            }
          if (!covered) continue;
          q.x = qx, q.y = qy, q.covered = covered, q.triangle = s->triangle, q.frontFacing = s->front;
          uint8_t live = 0;
          for (int i = 0; i < 4; ++i) {
            const float px = float(qx + (i & 1)), py = float(qy + (i >> 1));
            q.z[i] = interp(fused, s->z, px, py);
            if (covered & (1u << i)) {
              const size_t at = size_t(qy + (i >> 1)) * fb.width + size_t(qx + (i & 1));
              if (q.z[i] <= fb.depth[at]) live |= uint8_t(1u << i);
            }
          }
          ++quads;
          if (!live) continue;
          q.live = live;
          if (fs) {
            for (int i = 0; nv > 0 && i < 4; ++i) {
              const float px = float(qx + (i & 1)), py = float(qy + (i >> 1));
              const float oow = 1.0f / interp(fused, s->w, px, py);
              for (int k = 0; k < nv; ++k) q.v[k][i] = interp(fused, s->v[k], px, py) * oow;
            }
            fs(q, out);
          }
          for (int i = 0; i < 4; ++i) {
            if (!(live & (1u << i))) continue;
            const size_t at = size_t(qy + (i >> 1)) * fb.width + size_t(qx + (i & 1));
            fb.depth[at] = q.z[i];
            float* dst = fb.color.data() + at * size_t(fb.numOutputs);
            for (int k = 0; fs && k < fb.numOutputs; ++k) dst[k] = out[k][i];
            ++frags;
          }
        }
      }
    }
    quadCount.fetch_add(quads, std::memory_order_relaxed);
    fragCount.fetch_add(frags, std::memory_order_relaxed);
  });
  if (stats) {
    stats->trianglesIn += in.triangles;
    stats->trianglesClipped += clipped.load();
    stats->trianglesCulled += culled.load();
    stats->quads += quadCount.load();
    stats->fragments += fragCount.load();
  }
}

}  // namespace emu

namespace emu {

std::vector<FragmentLane> fragmentLanes(const DeviceProfile& dev, uint32_t width, uint32_t height,
                                        const uint32_t* primitiveOf, uint32_t primitives) {
  if (primitives == 0 || primitives > 32) throw std::invalid_argument("fragmentLanes: 1 to 32 primitives per target");
  const uint32_t bw = uint32_t(dev.fragmentVectorW), bh = uint32_t(dev.fragmentVectorH);
  const uint32_t blocksPerRow = (width + bw - 1) / bw;
  const size_t pixels = size_t(width) * height;
  auto blockOf = [&](size_t i) { return uint32_t(i / width / bh) * blocksPerRow + uint32_t(i % width) / bw; };
  std::vector<FragmentLane> lanes(pixels);
  for (size_t i = 0; i < pixels; ++i) lanes[i] = {uint32_t(i), blockOf(i) * primitives + primitiveOf[i], primitiveOf[i]};
  if (dev.maskedFragmentLanes == DeviceProfile::MaskedFragmentLanes::Skip) return lanes;
  // Which primitives run in each block (one bit per primitive, up to 32).
  std::vector<uint32_t> runs(size_t(blocksPerRow) * ((height + bh - 1) / bh), 0);
  for (size_t i = 0; i < pixels; ++i) runs[blockOf(i)] |= 1u << primitiveOf[i];
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t b = blockOf(i), others = runs[b] & ~(1u << primitiveOf[i]);
    for (uint32_t p = 0; p < primitives; ++p)
      if (others & (1u << p)) lanes.push_back({uint32_t(i), b * primitives + p, p});
  }
  return lanes;
}

}  // namespace emu
