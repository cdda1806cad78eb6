#include "emu/raster.h"

#include <stdexcept>

#include <algorithm>
#include <atomic>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>
#include <tuple>
#include <type_traits>

#include <immintrin.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "emu/fpenv.h"
#include "emu/lanes.h"
#include "emu/x86_float.h"

namespace emu {

namespace {
// Fills n floats with v. Large clears bypass the cache (non-temporal stores: no read of the
// lines first); a speed detail only, the values are those of std::fill_n.
void fillStreaming(float* p, size_t n, float v) {
#if defined(__AVX512F__)
  size_t i = 0;
  while (i < n && (reinterpret_cast<uintptr_t>(p + i) & 63)) p[i++] = v;
  const __m512 x = _mm512_set1_ps(v);
  for (; i + 16 <= n; i += 16) _mm512_stream_ps(p + i, x);
  for (; i < n; ++i) p[i] = v;
  _mm_sfence();
#else
  std::fill_n(p, n, v);
#endif
}
}  // namespace

Framebuffer::Framebuffer(uint32_t w, uint32_t h, int outputs, float clearDepth) { reset(w, h, outputs, clearDepth); }

void Framebuffer::reset(uint32_t w, uint32_t h, int outputs, float clearDepth) {
  width = w, height = h, numOutputs = outputs;
  const size_t n = size_t(w) * h, per = size_t(outputs);
  depth.resize(n);
  color.resize(n * per);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
    fillStreaming(depth.data() + r.begin(), r.size(), clearDepth);
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
  // Gallivm: a = fma(dady, py, fma(dadx, px, a0)) at pixel centres. Reactor: a0, dadx, dady are C, A, B
  // of SwiftShader's planes relative to vertex 0, evaluated as (C + y' B) + x' A with x' = px + xq[px & 1].
  bool reactor = false;
  float xq[2], yq[2];
  Plane3 z, w;
  Plane3 v[kMaxVaryings];
};

// A vertex as SwiftShader's vertex stage leaves it (VertexRoutine): clip y and w (setup sorts on them),
// projected X, Y in fixed point, z / w, 1 / w, and the raw varyings.
struct RVertex {
  float cy, cw;
  int32_t X, Y;
  float z, rhw;
  float v[kMaxVaryings];
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

// SwiftShader's projection: w = 0 becomes +-1 (the bits of w OR those of 1.0), rhw = 1 / w, then
// X = rint(X0xF + (x rhw) WxF) with X0xF = X0 2^b - 2^(b-1), WxF = W 2^b (Renderer's DrawData).
RVertex toReactor(const ClipVertex& cv, int nv, int bits, float W, float X0, float H, float Y0) {
  const float F = float(1 << bits);
  const float WxF = W * F, HxF = H * F, X0xF = X0 * F - F / 2, Y0xF = Y0 * F - F / 2;
  uint32_t wb;
  std::memcpy(&wb, &cv.c[3], 4);
  if (cv.c[3] == 0.0f) wb |= 0x3f800000u;
  float w;
  std::memcpy(&w, &wb, 4);
  RVertex r;
  r.cy = cv.c[1], r.cw = cv.c[3];
  r.rhw = 1.0f / w;
  r.X = x86::cvtps2dq(X0xF + (cv.c[0] * r.rhw) * WxF);
  r.Y = x86::cvtps2dq(Y0xF + (cv.c[1] * r.rhw) * HxF);
  r.z = cv.c[2] * r.rhw;
  for (int k = 0; k < nv; ++k) r.v[k] = cv.v[k];
  return r;
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

// Coverage part of setup from snapped positions: orientation, culling, edge order, top-left flags and
// the pixel box; order[] is the vertex order the edges use (counter-clockwise).
bool setupCoverage(const DeviceProfile& dev, const Framebuffer& fb, const int64_t X[3], const int64_t Y[3],
                   bool cullBack, uint32_t triangle, TriSetup& t, int order[3]) {
  const int64_t area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
  if (area == 0) return false;
  t.front = area > 0;  // counter-clockwise in Vulkan's framebuffer coordinates
  if (cullBack && !t.front) return false;
  order[0] = 0, order[1] = 1, order[2] = 2;
  if (area < 0) {
    if (dev.raster.cwSwapsLast) order[1] = 2, order[2] = 1;
    else order[0] = 1, order[1] = 0;
  }
  for (int i = 0; i < 3; ++i) t.X[i] = X[order[i]], t.Y[i] = Y[order[i]];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int64_t dy = t.Y[j] - t.Y[i], dx = t.X[j] - t.X[i];
    t.topLeft[i] = dy > 0 || (dy == 0 && dx < 0);
  }
  const int bits = dev.raster.subPixelBits;
  auto floorDiv = [&](int64_t a) { return a >> bits; };  // floor(a / 2^bits): C++20 shifts signed values arithmetically
  int64_t minX = std::min({t.X[0], t.X[1], t.X[2]}), maxX = std::max({t.X[0], t.X[1], t.X[2]});
  int64_t minY = std::min({t.Y[0], t.Y[1], t.Y[2]}), maxY = std::max({t.Y[0], t.Y[1], t.Y[2]});
  t.x0 = int(std::max<int64_t>(floorDiv(minX), 0));
  t.y0 = int(std::max<int64_t>(floorDiv(minY), 0));
  t.x1 = int(std::min<int64_t>(floorDiv(maxX) + 1, int64_t(fb.width) - 1));
  t.y1 = int(std::min<int64_t>(floorDiv(maxY) + 1, int64_t(fb.height) - 1));
  if (t.x0 > t.x1 || t.y0 > t.y1) return false;
  t.triangle = triangle;
  return true;
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
  int order[3];
  if (!setupCoverage(dev, fb, X, Y, cullBack, triangle, t, order)) return false;
  const WinVertex* v[3] = {in[order[0]], in[order[1]], in[order[2]]};
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

// SwiftShader's SetupRoutine for one triangle (submission order in[0..2]): coverage from the projected
// fixed-point positions (cov, the clipped polygon's when clipped), planes from the triangle's own vertices
// rotated so that the minimum clip y, then the maximum clip w comes first; see Raster::Setup::Reactor.
bool setupTriangleReactor(const DeviceProfile& dev, const Framebuffer& fb, const RVertex* const in[3],
                          const int64_t covX[3], const int64_t covY[3], int nv, bool cullBack, uint32_t triangle,
                          TriSetup& t) {
  int order[3];
  if (!setupCoverage(dev, fb, covX, covY, cullBack, triangle, t, order)) return false;
  t.reactor = true;
  const RVertex* v0 = in[0];
  const RVertex* v1 = in[1];
  const RVertex* v2 = in[2];
  auto rotate1 = [&](bool c) {  // (v0, v1, v2) = (v1, v2, v0)
    if (c) std::tie(v0, v1, v2) = std::make_tuple(v1, v2, v0);
  };
  auto rotate2 = [&](bool c) {  // (v0, v1, v2) = (v2, v0, v1)
    if (c) std::tie(v0, v1, v2) = std::make_tuple(v2, v0, v1);
  };
  {
    const float y0 = v0->cy, y1 = v1->cy, y2 = v2->cy;
    const float yMin = x86::minps(x86::minps(y0, y1), y2);
    rotate1(yMin == y1);
    rotate2(yMin == y2);
  }
  {
    const float w0 = v0->cw, w1 = v1->cw, w2 = v2->cw;
    const float wMax = x86::maxps(x86::maxps(w0, w1), w2);
    rotate1(wMax == w1);
    rotate2(wMax == w2);
  }
  const float F = 1.0f / float(1 << dev.raster.subPixelBits);
  const float w1 = v1->cw, w2 = v2->cw, rhw0 = v0->rhw;
  const int32_t X0 = v0->X, Y0 = v0->Y;
  const int32_t X1 = v1->X - X0, Y1 = v1->Y - Y0, X2 = v2->X - X0, Y2 = v2->Y - Y0;
  const float dx = float(X0) * F, dy = float(Y0) * F;
  const float x1 = w1 * F * float(X1), y1 = w1 * F * float(Y1);
  const float x2 = w2 * F * float(X2), y2 = w2 * F * float(Y2);
  const float a = x1 * y2 - x2 * y1;
  t.xq[0] = 0.0f - dx, t.xq[1] = 1.0f - dx;
  t.yq[0] = 0.0f - dy, t.yq[1] = 1.0f - dy;
  float M[3][3] = {{0, 0, rhw0}, {0, 0, 0}, {0, 0, 0}};  // rows: x, y, z components of M[0..2]
  if (a != 0.0f) {
    const float A = 1.0f / a, D = A * rhw0;
    M[0][0] = (y1 * w2 - y2 * w1) * D;
    M[0][1] = (x2 * w1 - x1 * w2) * D;
    M[1][0] = y2 * A;
    M[1][1] = -x2 * A;
    M[2][0] = -y1 * A;
    M[2][1] = x1 * A;
  }
  t.w.dadx = (M[0][0] + M[1][0]) + M[2][0];
  t.w.dady = (M[0][1] + M[1][1]) + M[2][1];
  t.w.a0 = (M[0][2] + M[1][2]) + M[2][2];
  {  // depth: the plane of z / w over the fixed-point positions, times the depth range [0, 1]
    const float z0 = v0->z, z1 = v1->z - z0, z2 = v2->z - z0;
    const float fx1 = float(X1) * F, fy1 = float(Y1) * F, fx2 = float(X2) * F, fy2 = float(Y2) * F;
    const float D = 1.0f / (fx1 * fy2 - fx2 * fy1);
    t.z.dadx = (fy2 * z1 - fy1 * z2) * D;
    t.z.dady = (fx1 * z2 - fx2 * z1) * D;
    t.z.a0 = z0 * 1.0f + 0.0f;
  }
  for (int k = 0; k < nv; ++k) {
    const float i0 = v0->v[k], i1 = v1->v[k], i2 = v2->v[k];
    t.v[k].dadx = (i0 * M[0][0] + i1 * M[1][0]) + i2 * M[2][0];
    t.v[k].dady = (i0 * M[0][1] + i1 * M[1][1]) + i2 * M[2][1];
    t.v[k].a0 = (i0 * M[0][2] + i1 * M[1][2]) + i2 * M[2][2];
  }
  return true;
}

// Reactor's perspective reciprocal (Raster::PerspectiveRcp).
float reactorRcp(DeviceProfile::Raster::PerspectiveRcp mode, float w) {
  if (mode == DeviceProfile::Raster::PerspectiveRcp::Division) return 1.0f / w;
  static const float exact = 1.0f / _mm_cvtss_f32(_mm_rcp_ss(_mm_set_ss(1.0f)));  // exactAtPow2
  float r = _mm_cvtss_f32(_mm_rcp_ss(_mm_set_ss(w))) * exact;
  return (r + r) - (w * r) * r;
}

inline float interp(bool fused, const Plane3& p, float px, float py) {
  return madd(fused, p.dady, py, madd(fused, p.dadx, px, p.a0));
}

// Depth-only pipelines (no fragment shader): coverage, depth and the depth test are per pixel and
// nothing is interpolated but depth, so one triangle's pixels in a tile run as 4x4 blocks of 16
// lanes (llvmpipe's inner block), with the operations of the quad loop below: the same exact edge
// functions A PX - B PY + C, the same plane equation madd(dady, py, madd(dadx, px, a0)) per pixel,
// the depth test less-or-equal in submission order. Pixel order inside one triangle does not
// matter (each pixel is touched once per triangle), so the bits equal the quad loop's
// (tests/raster_test.cpp DepthOnlyBlockPathEqualsTheQuadLoop).
//
// Per triangle and tile, each edge is classified over the rectangle of blocks the triangle's box
// touches: E affine, so its extremes over the rectangle are at its corners. An edge negative (or 0)
// at all four corners rejects the triangle there; an edge positive at all four passes every pixel
// and becomes the constant edge 0 PX - 0 PY + 1 (the big triangles' interior tiles test nothing).
// When every remaining edge is within int32 at the four corners, so is every lane's E (it lies
// between the corners' extremes), and the lanes use exact int32 edge values (one 16-lane register
// with AVX-512); otherwise int64 lanes. The lanes add in unsigned arithmetic, modulo 2^32 (or
// 2^64): a sum is exact when its true value is in range, whatever the partial sums were.
constexpr int kBlockW = 4, kBlockH = 4, kLanes = kBlockW * kBlockH;
using F32xL = vec_t<float, kLanes>;
using I32xL = vec_t<int32_t, kLanes>;

// Bit i set where lane i is true (-1). A speed detail only: the portable loop gives the same bits.
inline uint32_t laneBits(I32xL m) {
#if defined(__AVX512DQ__)
  return uint32_t(__builtin_ia32_cvtd2mask512((vec_t<int32_t, 16>)m));
#elif defined(__AVX__)
  const vec_t<float, 8> lo = (vec_t<float, 8>)__builtin_shufflevector(m, m, 0, 1, 2, 3, 4, 5, 6, 7);
  const vec_t<float, 8> hi = (vec_t<float, 8>)__builtin_shufflevector(m, m, 8, 9, 10, 11, 12, 13, 14, 15);
  return uint32_t(__builtin_ia32_movmskps256(lo)) | uint32_t(__builtin_ia32_movmskps256(hi)) << 8;
#else
  uint32_t b = 0;
  for (int i = 0; i < kLanes; ++i) b |= uint32_t(m[i] & 1) << i;
  return b;
#endif
}

// 2x2 quads of a 4x4 block with a set bit (bit 4 r + c is pixel (c, r)).
inline int blockQuads(uint32_t m) {
  const uint32_t rows = (m | m >> 4) & 0x0f0fu;  // rows 0|1 in bits 0-3, rows 2|3 in bits 8-11
  return std::popcount((rows | rows >> 1) & 0x0505u);
}

// A 4x4 block's 16 depths from four rows of the framebuffer (four 4-lane loads joined, so the
// 16-lane value is built in registers, not stored in pieces and reloaded whole).
inline F32xL loadBlock(const float* p, size_t stride) {
  using F4 = vec_t<float, 4>;
  using F8 = vec_t<float, 8>;
  F4 r0, r1, r2, r3;
  std::memcpy(&r0, p, 16), std::memcpy(&r1, p + stride, 16), std::memcpy(&r2, p + 2 * stride, 16), std::memcpy(&r3, p + 3 * stride, 16);
  const F8 lo = __builtin_shufflevector(r0, r1, 0, 1, 2, 3, 4, 5, 6, 7), hi = __builtin_shufflevector(r2, r3, 0, 1, 2, 3, 4, 5, 6, 7);
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}

inline void storeBlock(float* p, size_t stride, F32xL v) {
  using F4 = vec_t<float, 4>;
  const F4 r0 = __builtin_shufflevector(v, v, 0, 1, 2, 3), r1 = __builtin_shufflevector(v, v, 4, 5, 6, 7);
  const F4 r2 = __builtin_shufflevector(v, v, 8, 9, 10, 11), r3 = __builtin_shufflevector(v, v, 12, 13, 14, 15);
  std::memcpy(p, &r0, 16), std::memcpy(p + stride, &r1, 16), std::memcpy(p + 2 * stride, &r2, 16), std::memcpy(p + 3 * stride, &r3, 16);
}

// The lane constants of a block: pixel offsets (dx, dy) of lane i = 4 dy + dx.
template <class T>
constexpr vec_t<T, kLanes> kLaneDx = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3};
template <class T>
constexpr vec_t<T, kLanes> kLaneDy = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};

template <class EdgeT, bool Fused>
void depthOnlyBlocks(const int64_t A[3], const int64_t B[3], const int64_t C[3], int bits, const Plane3& pz, int bx0,
                     int by0, int x1, int y1, Framebuffer& fb, size_t& quads, size_t& frags, size_t& blocks, size_t& partial) {
  // Edge values accumulate in unsigned lanes (wrap-around is defined; every value compared is inside
  // EdgeT's range, see depthOnlyTriangle) and are compared as signed.
  using U = std::make_unsigned_t<EdgeT>;
  using EV = vec_t<EdgeT, kLanes>;
  using UV = vec_t<U, kLanes>;
  const int64_t step = int64_t(1) << bits;
  // Lane offsets A dx - B dy and the step to the next block, modulo 2^32 (or 2^64).
  UV off[3];
  U stepX[3];
  for (int e = 0; e < 3; ++e) {
    off[e] = UV(U(A[e] * step) * kLaneDx<U> - U(B[e] * step) * kLaneDy<U>);
    stepX[e] = U(kBlockW * A[e] * step);
  }
  const F32xL dadx = F32xL{} + pz.dadx, dady = F32xL{} + pz.dady, a0 = F32xL{} + pz.a0;
  const int W = int(fb.width), H = int(fb.height);
  const size_t stride = fb.width;
  for (int by = by0; by <= y1; by += kBlockH) {
    UV e0 = off[0], e1 = off[1], e2 = off[2];
    {
      const int64_t X0 = int64_t(bx0) << bits, Y0 = int64_t(by) << bits;
      e0 += U(A[0] * X0 - B[0] * Y0 + C[0]), e1 += U(A[1] * X0 - B[1] * Y0 + C[1]), e2 += U(A[2] * X0 - B[2] * Y0 + C[2]);
    }
    const F32xL fy = kLaneDy<float> + float(by);
    // Blocks inside the framebuffer load and store whole rows; a block past its last column or row
    // (the guard band lets a triangle reach there) masks those lanes.
    const bool allWhole = by + kBlockH <= H && (x1 | (kBlockW - 1)) < W;
    for (int bx = bx0; bx <= x1; bx += kBlockW, e0 += stepX[0], e1 += stepX[1], e2 += stepX[2]) {
      I32xL inV = __builtin_convertvector(((EV)e0 > 0) & ((EV)e1 > 0) & ((EV)e2 > 0), I32xL);
      if (!allWhole) inV &= (kLaneDx<int32_t> + bx < W) & (kLaneDy<int32_t> + by < H);
      const uint32_t in = laneBits(inV);
      const F32xL fx = kLaneDx<float> + float(bx);
      F32xL z;
      if constexpr (Fused) {
        for (int i = 0; i < kLanes; ++i) z[i] = __builtin_fmaf(dady[i], fy[i], __builtin_fmaf(dadx[i], fx[i], a0[i]));
      } else {
        z = dady * fy + (dadx * fx + a0);
      }
      float* row = fb.depth.data() + size_t(by) * stride + size_t(bx);
      const bool whole = allWhole || (bx + kBlockW <= W && by + kBlockH <= H);
      F32xL d;
      if (whole) {
        d = loadBlock(row, stride);
      } else {
        for (int i = 0; i < kLanes; ++i) d[i] = inV[i] ? row[size_t(i / kBlockW) * stride + size_t(i % kBlockW)] : 0.0f;
      }
      const I32xL liveV = inV & (z <= d);
      const uint32_t live = laneBits(liveV);
      quads += size_t(blockQuads(in));
      blocks += in != 0;
      partial += in != 0 && in != 0xffffu;
      frags += size_t(std::popcount(live));
      const F32xL out = liveV ? z : d;
      if (whole) {
        storeBlock(row, stride, out);
      } else {
        for (int i = 0; i < kLanes; ++i)
          if (liveV[i]) row[size_t(i / kBlockW) * stride + size_t(i % kBlockW)] = out[i];
      }
    }
  }
}

template <bool Fused>
void depthOnlyTriangle(const TriSetup& s, int bits, int tx0, int ty0, int tx1, int ty1, Framebuffer& fb,
                       size_t& quads, size_t& frags, size_t& blocks, size_t& partial) {
  const int x0 = std::max(s.x0, tx0), x1 = std::min(s.x1, tx1), y0 = std::max(s.y0, ty0), y1 = std::min(s.y1, ty1);
  if (x0 > x1 || y0 > y1) return;
  // The blocks' rectangle: 4-aligned inside the 64-aligned tile.
  const int bx0 = x0 & ~(kBlockW - 1), by0 = y0 & ~(kBlockH - 1);
  const int rx1 = (x1 | (kBlockW - 1)), ry1 = (y1 | (kBlockH - 1));
  int64_t A[3], B[3], C[3];
  bool narrow = true;
  for (int e = 0; e < 3; ++e) {
    const int j = e == 2 ? 0 : e + 1;
    A[e] = s.Y[j] - s.Y[e];
    B[e] = s.X[j] - s.X[e];
    C[e] = B[e] * s.Y[e] - A[e] * s.X[e] + (s.topLeft[e] ? 1 : 0);
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (const int cx : {bx0, rx1})
      for (const int cy : {by0, ry1}) {
        const int64_t E = A[e] * (int64_t(cx) << bits) - B[e] * (int64_t(cy) << bits) + C[e];
        lo = std::min(lo, E), hi = std::max(hi, E);
      }
    if (hi <= 0) return;  // no pixel of the rectangle passes this edge
    if (lo > 0) A[e] = 0, B[e] = 0, C[e] = 1;  // every pixel passes it
    else narrow = narrow && lo >= INT32_MIN && hi <= INT32_MAX;
  }
  if (narrow) depthOnlyBlocks<int32_t, Fused>(A, B, C, bits, s.z, bx0, by0, x1, y1, fb, quads, frags, blocks, partial);
  else depthOnlyBlocks<int64_t, Fused>(A, B, C, bits, s.z, bx0, by0, x1, y1, fb, quads, frags, blocks, partial);
}

}  // namespace

void draw(const DeviceProfile& dev, Framebuffer& fb, const DrawInput& in, const FragmentFn& fs, RasterStats* stats) {
  const int nv = in.numVaryings;
  const float sx = float(fb.width) * 0.5f, sy = float(fb.height) * 0.5f;
  // Setup, in submission order (clipped triangles become fans, in order).
  std::unique_ptr<TriSetup[]> tris(new TriSetup[in.triangles]);  // default-initialized: ok[t] says which are set up
  std::vector<uint8_t> ok(in.triangles, 0);
  std::vector<std::vector<TriSetup>> extra(in.triangles);  // clipped: fan pieces
  std::atomic<size_t> clipped{0}, culled{0}, outside{0};
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
    if (dev.raster.setup == DeviceProfile::Raster::Setup::Reactor) {
      const int bits = dev.raster.subPixelBits;
      RVertex rv[3];
      for (int i = 0; i < 3; ++i) rv[i] = toReactor(cv[i], nv, bits, sx, sx, sy, sy);
      const RVertex* p[3] = {&rv[0], &rv[1], &rv[2]};
      if (!any) {
        const int64_t X[3] = {rv[0].X, rv[1].X, rv[2].X}, Y[3] = {rv[0].Y, rv[1].Y, rv[2].Y};
        ok[t] = setupTriangleReactor(dev, fb, p, X, Y, nv, in.cullBack, uint32_t(t), tris[t]);
        if (!ok[t]) culled.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      clipped.fetch_add(1, std::memory_order_relaxed);
      if (all) {
        outside.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      const int n = clipPolygon(dev.raster, cv, any, nv);
      if (n < 3) return;
      // Coverage from the clipped polygon, re-projected (SetupRoutine: rhw = w != 0 ? 1 / w : 1); the planes
      // stay the triangle's own. The polygon's fan pieces tile it exactly under the top-left rule.
      int64_t PX[kMaxPoly], PY[kMaxPoly];
      const float F = float(1 << bits);
      for (int i = 0; i < n; ++i) {
        const float rhw = cv[i].c[3] != 0.0f ? 1.0f / cv[i].c[3] : 1.0f;
        PX[i] = x86::cvtps2dq((sx * F - F / 2) + (cv[i].c[0] * rhw) * (sx * F));
        PY[i] = x86::cvtps2dq((sy * F - F / 2) + (cv[i].c[1] * rhw) * (sy * F));
      }
      for (int i = 1; i + 1 < n; ++i) {
        const int64_t X[3] = {PX[0], PX[i], PX[i + 1]}, Y[3] = {PY[0], PY[i], PY[i + 1]};
        TriSetup s;
        if (setupTriangleReactor(dev, fb, p, X, Y, nv, in.cullBack, uint32_t(t), s)) extra[t].push_back(s);
      }
      return;
    }
    if (!any) {
      WinVertex w[3];
      for (int i = 0; i < 3; ++i) w[i] = toWindow(fusedVp, cv[i], nv, sx, sx, sy, sy);
      const WinVertex* p[3] = {&w[0], &w[1], &w[2]};
      ok[t] = setupTriangle(dev, fb, p, nv, in.cullBack, uint32_t(t), tris[t]);
      if (!ok[t]) culled.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    clipped.fetch_add(1, std::memory_order_relaxed);
    if (all) {  // every vertex outside one plane
      outside.fetch_add(1, std::memory_order_relaxed);
      return;
    }
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
  size_t spanning = 0;  // statistics only: set-ups whose y extent holds a pixel-centre row (sub-pixel units, centre 0)
  auto spans = [&](const TriSetup& s) {
    const int b = dev.raster.subPixelBits;
    const int64_t lo = std::min({s.Y[0], s.Y[1], s.Y[2]}), hi = std::max({s.Y[0], s.Y[1], s.Y[2]});
    const int64_t first = std::max<int64_t>(-((-lo) >> b), 0), last = std::min<int64_t>(hi >> b, int64_t(fb.height) - 1);
    spanning += first <= last;
  };
  for (size_t t = 0; t < in.triangles; ++t) {
    if (ok[t]) bin(tris[t]), spans(tris[t]);
    for (auto& s : extra[t]) bin(s), spans(s);
  }
  std::atomic<size_t> quadCount{0}, fragCount{0}, blockCount{0}, partialCount{0};
  const bool fused = dev.raster.interpFma;
  const bool flush = dev.denormFragment == DenormMode::Flush;
  const int bits = dev.raster.subPixelBits;
  tbb::parallel_for(size_t(0), bins.size(), [&](size_t b) {
    if (bins[b].empty()) return;
    DenormalScope mode(flush);
    const int tx0 = int(b % size_t(tilesX)) * kTile, ty0 = int(b / size_t(tilesX)) * kTile;
    const int tx1 = std::min(tx0 + kTile, int(fb.width)) - 1, ty1 = std::min(ty0 + kTile, int(fb.height)) - 1;
    size_t quads = 0, frags = 0, blocks = 0, partial = 0;
    if (!fs && dev.raster.setup == DeviceProfile::Raster::Setup::Gallivm) {  // depth-only pipeline
      for (const TriSetup* s : bins[b]) {
        if (fused) depthOnlyTriangle<true>(*s, bits, tx0, ty0, tx1, ty1, fb, quads, frags, blocks, partial);
        else depthOnlyTriangle<false>(*s, bits, tx0, ty0, tx1, ty1, fb, quads, frags, blocks, partial);
      }
      quadCount.fetch_add(quads, std::memory_order_relaxed);
      fragCount.fetch_add(frags, std::memory_order_relaxed);
      blockCount.fetch_add(blocks, std::memory_order_relaxed);
      partialCount.fetch_add(partial, std::memory_order_relaxed);
      return;
    }
    Quad q;
    q.drawId = in.drawId;
    float out[4 * 64][4];  // up to 64 outputs
    uint16_t blockCover[256] = {};  // per triangle: the pixels it covers of each 4x4 block of the tile (cleared after it)
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
      // The blocks of 4x4 pixels this triangle covers a pixel of (blockCover: which, bit 4 r + c).
      uint8_t touched[256];
      int nTouched = 0;
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
          {
            const int bi = ((qy - ty0) >> 2) * 16 + ((qx - tx0) >> 2);
            if (!blockCover[bi]) touched[nTouched++] = uint8_t(bi);
            const int shift = (qy & 2) * 4 + (qx & 2);  // the quad's top-left pixel in the block
            blockCover[bi] |= uint16_t((covered & 3u) << shift | (covered >> 2) << (shift + 4));
          }
          q.x = qx, q.y = qy, q.covered = covered, q.triangle = s->triangle, q.frontFacing = s->front;
          uint8_t live = 0;
          float xr[4], yr[4];  // Reactor: pixel positions relative to vertex 0
          for (int i = 0; i < 4; ++i) {
            const float px = float(qx + (i & 1)), py = float(qy + (i >> 1));
            if (s->reactor) {
              xr[i] = float(qx) + s->xq[i & 1], yr[i] = float(qy) + s->yq[i >> 1];
              const float D = s->z.a0 + yr[i] * s->z.dady;
              const float z = D + xr[i] * s->z.dadx;
              q.z[i] = x86::minps(x86::maxps(z, 0.0f), 1.0f);  // depth clamp to the [0, 1] range of a D32F buffer
            } else {
              q.z[i] = interp(fused, s->z, px, py);
            }
            if (covered & (1u << i)) {
              const size_t at = size_t(qy + (i >> 1)) * fb.width + size_t(qx + (i & 1));
              if (q.z[i] <= fb.depth[at]) live |= uint8_t(1u << i);
            }
          }
          ++quads;
          if (!live) continue;
          q.live = live;
          if (fs) {
            for (int i = 0; s->reactor && nv > 0 && i < 4; ++i) {
              const float D = s->w.a0 + yr[i] * s->w.dady;
              const float rhw = reactorRcp(dev.raster.perspectiveRcp, D + xr[i] * s->w.dadx);
              for (int k = 0; k < nv; ++k) {
                const float Dv = s->v[k].a0 + yr[i] * s->v[k].dady;
                q.v[k][i] = (Dv + xr[i] * s->v[k].dadx) * rhw;
              }
            }
            for (int i = 0; !s->reactor && nv > 0 && i < 4; ++i) {
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
      for (int i = 0; i < nTouched; ++i) {
        ++blocks;
        partial += blockCover[touched[i]] != 0xffffu;
        blockCover[touched[i]] = 0;
      }
    }
    quadCount.fetch_add(quads, std::memory_order_relaxed);
    fragCount.fetch_add(frags, std::memory_order_relaxed);
    blockCount.fetch_add(blocks, std::memory_order_relaxed);
    partialCount.fetch_add(partial, std::memory_order_relaxed);
  });
  if (stats) {
    stats->trianglesIn += in.triangles;
    stats->trianglesClipped += clipped.load();
    stats->trianglesCulled += culled.load();
    stats->trianglesOutside += outside.load();
    stats->quads += quadCount.load();
    stats->fragments += fragCount.load();
    stats->blocks += blockCount.load();
    stats->partialBlocks += partialCount.load();
    stats->trianglesSpanning += spanning;
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
