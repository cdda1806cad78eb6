// Emulated rasterizer: coverage rule, interpolation, depth test, quads, thread-count independence.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <random>
#include <limits>
#include <map>
#include <mutex>
#include <vector>

#include "emu/raster.h"
#include "passes/gbuffer.h"
#include "scene/scene.h"

namespace {

const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }

// One triangle (clip-space xyzw x 3) into `fb`, every covered pixel's single output 1; its raster statistics.
emu::RasterStats drawOneTriangle(emu::Framebuffer& fb, const float clip[12], const emu::DeviceProfile& profile = dev()) {
  const float vary[3] = {0, 0, 0};
  const uint32_t idx[3] = {0, 1, 2};
  emu::RasterStats st;
  emu::DrawInput in{clip, vary, 1, idx, 1};
  emu::draw(profile, fb, in, [&](const emu::Quad&, float (*out)[4]) { for (int i = 0; i < 4; ++i) out[0][i] = 1; }, &st);
  return st;
}

// Window position (x, y in pixels, depth z) -> clip coordinates with w = 1 for a W x H target.
void clipOf(float x, float y, float z, uint32_t W, uint32_t H, float* c) {
  c[0] = x / (W * 0.5f) - 1.0f;
  c[1] = y / (H * 0.5f) - 1.0f;
  c[2] = z;
  c[3] = 1.0f;
}

// Counts how many times each pixel is shaded across a set of triangles.
std::vector<int> coverageCount(uint32_t W, uint32_t H, const std::vector<float>& clip, const std::vector<uint32_t>& idx,
                               const emu::DeviceProfile& profile = dev()) {
  emu::Framebuffer fb(W, H, 1, 2.0f);  // depth test never rejects (z <= 2)
  std::vector<int> count(size_t(W) * H, 0);
  std::vector<float> vary(clip.size() / 4, 0.0f);
  for (size_t t = 0; t < idx.size() / 3; ++t) {  // one draw per triangle: the depth test stays out of it
    emu::DrawInput in;
    in.clip = clip.data();
    in.varyings = vary.data();
    in.numVaryings = 1;
    in.indices = idx.data() + 3 * t;
    in.triangles = 1;
    emu::draw(profile, fb, in, [&](const emu::Quad& q, float (*out)[4]) {
      for (int i = 0; i < 4; ++i) {
        out[0][i] = 0.0f;
        if (q.live & (1 << i)) ++count[size_t(q.y + (i >> 1)) * W + size_t(q.x + (i & 1))];
      }
    });
  }
  return count;
}

TEST(Raster, SharedEdgesCoverEachPixelExactlyOnce) {
  // A fan of triangles around a centre, vertices on pixel centres and off them: every pixel centre
  // inside the fan is shaded exactly once (top-left rule), none twice.
  const uint32_t W = 64, H = 64;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(4.0f, 60.0f);
  for (int trial = 0; trial < 20; ++trial) {
    const bool snapped = trial % 2 == 0;
    std::vector<float> clip;
    std::vector<uint32_t> idx;
    auto vert = [&](float x, float y) {
      if (snapped) x = std::floor(x) + 0.5f, y = std::floor(y) + 0.5f;  // exactly on pixel centres: ties
      float c[4];
      clipOf(x, y, 0.5f, W, H, c);
      clip.insert(clip.end(), c, c + 4);
      return uint32_t(clip.size() / 4 - 1);
    };
    uint32_t centre = vert(32.0f, 32.0f);
    const int n = 7;
    std::vector<uint32_t> ring;
    for (int k = 0; k < n; ++k) {
      float a = float(k) * 6.2831853f / n + float(trial) * 0.1f;
      ring.push_back(vert(32.0f + 24.0f * std::cos(a), 32.0f + 24.0f * std::sin(a)));
    }
    for (int k = 0; k < n; ++k) idx.insert(idx.end(), {centre, ring[size_t(k)], ring[size_t((k + 1) % n)]});
    auto count = coverageCount(W, H, clip, idx);
    int shaded = 0;
    for (int c : count) {
      EXPECT_LE(c, 1);
      shaded += c;
    }
    EXPECT_GT(shaded, 1000) << "trial " << trial;
  }
}

TEST(Raster, SwiftShaderSetupCoversLikeTheTopLeftRule) {
  // Raster::Setup::Reactor at SwiftShader's 4 sub-pixel bits: SwiftShader walks each edge into per-row spans
  // (left = ceil(x_edge), covered left <= px < right, rows with y*16 in [y_top, y_bottom)), which is the top-left
  // rule of the edge functions. With vertices on pixel centres (exact in both fixed points) the pixels are those of
  // lavapipe's profile, one by one; off centres every pixel of a fan is still shaded at most once.
  const uint32_t W = 64, H = 64;
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const bool snapped = trial % 2 == 0;
    std::vector<float> clip;
    std::vector<uint32_t> idx;
    auto vert = [&](float x, float y) {
      if (snapped) x = std::floor(x) + 0.5f, y = std::floor(y) + 0.5f;
      float c[4];
      clipOf(x, y, 0.5f, W, H, c);
      clip.insert(clip.end(), c, c + 4);
      return uint32_t(clip.size() / 4 - 1);
    };
    const uint32_t centre = vert(31.3f, 32.7f);
    const int n = 9;
    std::vector<uint32_t> ring;
    for (int k = 0; k < n; ++k) {
      const float a = float(k) * 6.2831853f / n + float(trial) * 0.13f;
      ring.push_back(vert(32.0f + 25.0f * std::cos(a), 32.0f + 25.0f * std::sin(a)));
    }
    for (int k = 0; k < n; ++k) idx.insert(idx.end(), {centre, ring[size_t(k)], ring[size_t((k + 1) % n)]});
    const auto ss = coverageCount(W, H, clip, idx, emu::swiftshaderProfile());
    int shaded = 0;
    for (int c : ss) {
      EXPECT_LE(c, 1) << "trial " << trial;
      shaded += c;
    }
    EXPECT_GT(shaded, 1000) << "trial " << trial;
    if (snapped) EXPECT_EQ(ss, coverageCount(W, H, clip, idx, dev())) << "trial " << trial;
  }
}

TEST(Raster, TopLeftRuleOnAxisAlignedSquare) {
  // Square [8, 24] x [8, 24] in window coordinates: pixel centres at 8.5 .. 23.5 -> exactly 16 x 16
  // pixels, and a square whose edges pass through pixel centres (8.5 .. 24.5) includes its left and
  // top edges only: again 16 x 16, starting at pixel 8.
  const uint32_t W = 32, H = 32;
  for (float o : {0.0f, 0.5f}) {
    std::vector<float> clip(16);
    const float xs[4] = {8 + o, 24 + o, 24 + o, 8 + o}, ys[4] = {8 + o, 8 + o, 24 + o, 24 + o};
    for (int i = 0; i < 4; ++i) clipOf(xs[i], ys[i], 0.5f, W, H, &clip[size_t(4 * i)]);
    auto count = coverageCount(W, H, clip, {0, 1, 2, 0, 2, 3});
    int total = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const bool inside = x >= 8 && x < 24 && y >= 8 && y < 24;
        EXPECT_EQ(count[y * W + x], inside ? 1 : 0) << "offset " << o << " pixel " << x << "," << y;
        total += count[y * W + x];
      }
    EXPECT_EQ(total, 256);
  }
}

TEST(Raster, PerspectiveCorrectInterpolationAndDepth) {
  // One triangle with different w per vertex: the interpolated varying equals the perspective-correct
  // barycentric value (within float rounding), depth equals z/w interpolated linearly in screen space.
  const uint32_t W = 64, H = 64;
  const float clip[12] = {-0.8f * 1.0f, -0.8f * 1.0f, 0.2f, 1.0f, 0.9f * 4.0f, -0.7f * 4.0f, 0.5f * 4.0f, 4.0f,
                          -0.6f * 2.0f, 0.9f * 2.0f,  0.3f * 2.0f, 2.0f};
  const float vary[3] = {1.0f, 5.0f, -3.0f};
  const uint32_t idx[3] = {0, 1, 2};
  emu::Framebuffer fb(W, H, 1);
  emu::DrawInput in{clip, vary, 1, idx, 1};
  std::vector<float> val(size_t(W) * H, NAN);
  emu::draw(dev(), fb, in, [&](const emu::Quad& q, float (*out)[4]) {
    for (int i = 0; i < 4; ++i) out[0][i] = q.v[0][i];
  });
  // window positions
  float wx[3], wy[3], wz[3], ww[3];
  for (int i = 0; i < 3; ++i) {
    ww[i] = clip[4 * i + 3];
    wx[i] = clip[4 * i] / ww[i] * 32 + 32, wy[i] = clip[4 * i + 1] / ww[i] * 32 + 32, wz[i] = clip[4 * i + 2] / ww[i];
  }
  int checked = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      if (fb.depth[y * W + x] == 1.0f) continue;
      double px = x + 0.5, py = y + 0.5;
      double d = (wy[1] - wy[2]) * (wx[0] - wx[2]) + (wx[2] - wx[1]) * (wy[0] - wy[2]);
      double b0 = ((wy[1] - wy[2]) * (px - wx[2]) + (wx[2] - wx[1]) * (py - wy[2])) / d;
      double b1 = ((wy[2] - wy[0]) * (px - wx[2]) + (wx[0] - wx[2]) * (py - wy[2])) / d;
      double b2 = 1 - b0 - b1;
      double z = b0 * wz[0] + b1 * wz[1] + b2 * wz[2];
      double iw = b0 / ww[0] + b1 / ww[1] + b2 / ww[2];
      double v = (b0 * vary[0] / ww[0] + b1 * vary[1] / ww[1] + b2 * vary[2] / ww[2]) / iw;
      EXPECT_NEAR(fb.depth[y * W + x], z, 1e-5) << x << "," << y;
      EXPECT_NEAR(fb.color[y * W + x], v, 2e-4) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 500);
}

TEST(Raster, DepthTestLessOrEqualKeepsNearest) {
  const uint32_t W = 16, H = 16;
  emu::Framebuffer fb(W, H, 1);
  for (float z : {0.7f, 0.3f, 0.5f, 0.3f}) {  // the second 0.3 passes (less-or-equal) and writes its id
    float clip[12];
    clipOf(0, 0, z, W, H, clip), clipOf(40, 0, z, W, H, clip + 4), clipOf(0, 40, z, W, H, clip + 8);
    static int call = 0;
    float id = float(++call);
    float vary[3] = {id, id, id};
    uint32_t idx[3] = {0, 1, 2};
    emu::DrawInput in{clip, vary, 1, idx, 1};
    emu::draw(dev(), fb, in, [&](const emu::Quad& q, float (*out)[4]) {
      for (int i = 0; i < 4; ++i) out[0][i] = q.v[0][i];
    });
  }
  EXPECT_EQ(fb.depth[5 * W + 5], 0.3f);
  EXPECT_EQ(fb.color[5 * W + 5], 4.0f);
}

TEST(Raster, QuadDerivativesFineAndHelpers) {
  // Varying = window x + 2 * window y: dFdx = 1 and dFdy = 2 everywhere, helper pixels included.
  const uint32_t W = 32, H = 32;
  float clip[12];
  clipOf(3.3f, 2.1f, 0.5f, W, H, clip), clipOf(29.7f, 5.2f, 0.5f, W, H, clip + 4), clipOf(7.1f, 30.2f, 0.5f, W, H, clip + 8);
  float vary[3];
  const float pts[3][2] = {{3.3f, 2.1f}, {29.7f, 5.2f}, {7.1f, 30.2f}};
  for (int i = 0; i < 3; ++i) vary[i] = pts[i][0] + 2 * pts[i][1];
  uint32_t idx[3] = {0, 1, 2};
  emu::Framebuffer fb(W, H, 2);
  emu::DrawInput in{clip, vary, 1, idx, 1};
  int partial = 0;
  emu::draw(dev(), fb, in, [&](const emu::Quad& q, float (*out)[4]) {
    float dx[4], dy[4];
    emu::quadDerivatives(dev(), q.v[0], dx, dy);
    if (q.covered != 15) ++partial;
    for (int i = 0; i < 4; ++i) out[0][i] = dx[i], out[1][i] = dy[i];
  });
  int n = 0;
  for (size_t p = 0; p < size_t(W) * H; ++p)
    if (fb.depth[p] < 1.0f) {
      EXPECT_NEAR(fb.color[2 * p], 1.0f, 1e-4);
      EXPECT_NEAR(fb.color[2 * p + 1], 2.0f, 1e-4);
      ++n;
    }
  EXPECT_GT(n, 200);
  EXPECT_GT(partial, 10);  // edge quads ran with helper pixels
}

TEST(Raster, NearPlaneClipping) {
  // A triangle crossing z = 0 is clipped, not dropped, and nothing behind the camera is drawn.
  const uint32_t W = 32, H = 32;
  const float clip[12] = {-0.5f, -0.5f, -0.5f, 1.0f, 0.5f, -0.5f, 0.5f, 1.0f, 0.0f, 0.5f, 0.5f, 1.0f};
  emu::Framebuffer fb(W, H, 1);
  const emu::RasterStats st = drawOneTriangle(fb, clip);
  EXPECT_EQ(st.trianglesClipped, 1u);
  EXPECT_GT(st.fragments, 20u);
  for (float d : fb.depth) EXPECT_GE(d, 0.0f);
}

TEST(Raster, ClippedMeshStaysWatertight) {
  // A 6x6-vertex grid spanning well past every border of the viewport, with w varying per vertex
  // (perspective) and two vertices behind the near plane: after clipping against x, y and near, each
  // pixel is still covered at most once (exactly once without the near-plane cut). Bit-exactness of
  // the clipped vertices against lavapipe is the differential test verify_raster_clipped.
  const uint32_t W = 37, H = 29;
  std::vector<float> clip;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      const float w = 0.7f + 0.13f * float(i) + 0.11f * float(j);
      const float x = -2.3f + 0.9f * float(i) + 0.05f * float(j), y = -2.2f + 0.85f * float(j) + 0.03f * float(i);
      const float z = (i == 2 && j == 3) || (i == 3 && j == 2) ? -0.2f * w : 0.3f * w;
      clip.insert(clip.end(), {x * w, y * w, z, w});
    }
  std::vector<uint32_t> idx;
  for (uint32_t j = 0; j < 5; ++j)
    for (uint32_t i = 0; i < 5; ++i) {
      const uint32_t a = j * 6 + i;
      idx.insert(idx.end(), {a, a + 1, a + 7, a, a + 7, a + 6});
    }
  const auto count = coverageCount(W, H, clip, idx);
  int holes = 0, twice = 0;
  for (int c : count) holes += c == 0, twice += c > 1;
  // The two vertices behind the near plane cut a hole that some pixels fall into; none is covered twice.
  EXPECT_EQ(twice, 0);
  EXPECT_GT(holes, 0);
  EXPECT_LT(holes, int(W * H) / 2);
  // Without the near-plane vertices the grid covers every pixel exactly once.
  for (size_t v = 0; v < clip.size() / 4; ++v) clip[4 * v + 2] = 0.3f * clip[4 * v + 3];
  const auto full = coverageCount(W, H, clip, idx);
  for (size_t p = 0; p < full.size(); ++p) ASSERT_EQ(full[p], 1) << "pixel " << p % W << "," << p / W;
}

TEST(Raster, ClipperDiscardsNonFiniteAndOutsideTriangles) {
  const uint32_t W = 16, H = 16;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Triangle 0 crosses x = w and has an infinite coordinate; triangle 1 lies wholly right of x = w.
  const float clip[24] = {0.0f, 0.0f, 0.5f, 1.0f, 3.0f, 0.0f, 0.5f, 1.0f, std::numeric_limits<float>::infinity(), nan, 0.5f, 1.0f,
                          1.5f, 0.0f, 0.5f, 1.0f, 3.0f, 0.0f, 0.5f, 1.0f, 2.0f, 1.0f, 0.5f, 1.0f};
  const float vary[6] = {};
  const uint32_t idx[6] = {0, 1, 2, 3, 4, 5};
  emu::Framebuffer fb(W, H, 1);
  emu::RasterStats st;
  emu::DrawInput in{clip, vary, 1, idx, 2};
  emu::draw(dev(), fb, in, [&](const emu::Quad&, float (*out)[4]) { for (int i = 0; i < 4; ++i) out[0][i] = 1; }, &st);
  EXPECT_EQ(st.trianglesClipped, 2u);
  EXPECT_EQ(st.fragments, 0u);
}

TEST(Raster, DepthOnlyBlockPathEqualsTheQuadLoop) {
  // A depth-only draw (no fragment shader) takes the 4x4 block path; the same draw with a fragment
  // shader that writes nothing (0 outputs) takes the quad loop. Depth buffers must be equal bit for
  // bit, and so must the counted quads and fragments: many seeds, target sizes that are and are not
  // multiples of 4 and of the 64-pixel tile, overlapping triangles of every size (the depth test
  // in submission order), triangles crossing the target's edges, fused and separate plane equations.
  // The large triangles of the 1024-wide targets (edges up to ~700 pixels: |E| reaches 2^35 inside
  // a tile) take the int64 lanes and, inside them, whole tiles of constant (accepted) edges; the
  // small ones the int32 lanes.
  const uint32_t sizes[][2] = {{64, 64}, {100, 37}, {257, 129}, {1024, 24}, {8, 300}, {3, 5}, {1024, 1024}, {130, 1023}};
  for (const int variant : {0, 1, 2}) {  // lavapipe (fused, draw-module clipper), separate mul + add, guard band
    const bool fused = variant != 1;
    emu::DeviceProfile p = dev();
    p.raster.interpFma = fused;
    if (variant == 2) p.raster.clip = emu::DeviceProfile::Raster::Clip::GuardBand;  // triangles reach past the edges
    for (uint32_t seed = 1; seed <= 24; ++seed) {
      const uint32_t W = sizes[seed % 8][0], H = sizes[seed % 8][1];
      std::mt19937 rng(seed);
      std::uniform_real_distribution<float> U(-0.3f, 1.3f), Z(0.0f, 1.0f);
      const size_t tris = 40 + seed * 7;
      std::vector<float> clip;
      std::vector<uint32_t> idx;
      for (size_t t = 0; t < tris; ++t) {  // t counts triangles, repeats included
        // Mostly small triangles near a random centre, some large ones.
        const float cx = U(rng) * float(W), cy = U(rng) * float(H);
        const float r = (t % 5 == 0 ? 0.7f : 0.06f) * float(std::max(W, H));
        for (int k = 0; k < 3; ++k) {
          float c[4];
          clipOf(cx + r * (U(rng) - 0.5f), cy + r * (U(rng) - 0.5f), Z(rng), W, H, c);
          idx.push_back(uint32_t(clip.size() / 4));
          clip.insert(clip.end(), c, c + 4);
        }
        if (t % 7 == 0) {  // the same triangle again: equal depths, where less-or-equal passes
          for (int k = 0; k < 3; ++k) idx.push_back(idx[idx.size() - 3]);
          ++t;
        }
      }
      emu::DrawInput in;
      in.clip = clip.data();
      in.indices = idx.data();
      in.triangles = idx.size() / 3;
      emu::Framebuffer a(W, H, 0), b(W, H, 0);
      emu::RasterStats sa, sb;
      emu::draw(p, a, in, emu::FragmentFn(), &sa);
      emu::draw(p, b, in, [](const emu::Quad&, float (*)[4]) {}, &sb);
      size_t firstDiff = a.depth.size();
      for (size_t i = 0; i < a.depth.size() && firstDiff == a.depth.size(); ++i)
        if (std::memcmp(&a.depth[i], &b.depth[i], 4) != 0) firstDiff = i;
      ASSERT_EQ(firstDiff, a.depth.size()) << "seed " << seed << " variant " << variant << " " << W << "x" << H << ": pixel ("
                                           << firstDiff % W << ", " << firstDiff / W << ") block path "
                                           << a.depth[firstDiff % a.depth.size()] << ", quad loop " << b.depth[firstDiff % a.depth.size()];
      EXPECT_EQ(sa.fragments, sb.fragments) << seed;
      EXPECT_EQ(sa.quads, sb.quads) << seed;
      EXPECT_GT(sa.fragments, 0u) << seed;
    }
  }
}

TEST(Raster, FragmentLanesSplitBlocksRunOncePerPrimitiveWithMaskedLanes) {
  // 8 x 4 target, lavapipe's 4 x 2 blocks, two primitives split along a staircase: block (0, 0) all
  // primitive 0, block (1, 0) split, row 2-3 blocks all primitive 1.
  const uint32_t w = 8, h = 4;
  std::vector<uint32_t> prim(w * h, 0);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) prim[y * w + x] = (y >= 2 || (y == 0 && x >= 6)) ? 1u : 0u;
  const auto& lp = emu::lavapipeProfile();
  const std::vector<emu::FragmentLane> lanes = emu::fragmentLanes(lp, w, h, prim.data(), 2);
  ASSERT_EQ(lanes.size(), size_t(w * h + 8));  // block (1, 0): its 8 pixels again, masked, in the other run
  for (uint32_t i = 0; i < w * h; ++i) {
    EXPECT_EQ(lanes[i].pixel, i);
    EXPECT_EQ(lanes[i].primitive, prim[i]);
    const uint32_t block = (i / w / 2) * 2 + (i % w) / 4;
    EXPECT_EQ(lanes[i].vector, block * 2 + prim[i]) << i;
  }
  std::vector<int> runLanes(8, 0);
  for (const auto& l : lanes) ++runLanes[l.vector];
  EXPECT_EQ(runLanes[0 * 2 + 0], 8);  // block 0, primitive 0 only
  EXPECT_EQ(runLanes[1 * 2 + 0], 8);  // block 1: 6 own + 2 masked lanes of primitive 1's pixels
  EXPECT_EQ(runLanes[1 * 2 + 1], 8);  // 2 own + 6 masked
  for (size_t k = w * h; k < lanes.size(); ++k) {
    EXPECT_NE(lanes[k].primitive, prim[lanes[k].pixel]);  // a masked lane runs in the other primitive's vector
    EXPECT_EQ(lanes[k].vector / 2, 1u);
  }
  emu::DeviceProfile skip = lp;
  emu::setProfileField(skip, "maskedFragmentLanes=skip");
  EXPECT_EQ(emu::fragmentLanes(skip, w, h, prim.data(), 2).size(), size_t(w * h));
  EXPECT_THROW(emu::fragmentLanes(lp, w, h, prim.data(), 0), std::invalid_argument);
  EXPECT_THROW(emu::fragmentLanes(lp, w, h, prim.data(), 33), std::invalid_argument);
}

TEST(GBufferPass, ThreadCountIndependent) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/spheres.json");
  s.width = 256, s.height = 96;
  std::vector<float> ref;
  for (int threads : {1, 2, 16}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(threads));
    shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev());
    if (ref.empty()) {
      ref = g.texels;
      size_t geom = 0;
      for (size_t p = 0; p < size_t(s.width) * s.height; ++p) geom += g.texels[p * shadetwin::kGbufFloats + 3] != 0.0f;
      EXPECT_GT(geom, 3000u);
    } else {
      ASSERT_EQ(0, std::memcmp(ref.data(), g.texels.data(), ref.size() * 4)) << threads << " threads";
    }
  }
}

TEST(GBufferPass, SphereNormalsAndPositions) {
  // Unit spheres: every G-buffer position lies on its sphere (within the tessellation's sagitta) and
  // the interpolated normal points along (p - centre).
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/spheres.json");
  s.width = 256, s.height = 96;
  shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev());
  int checked = 0;
  for (size_t p = 0; p < size_t(s.width) * s.height; ++p) {
    const float* t = g.texels.data() + p * shadetwin::kGbufFloats;
    if (t[3] == 0.0f) continue;
    const int id = int(std::fabs(t[3])) - 1;
    ASSERT_GE(id, 0);
    ASSERT_LT(id, 4);
    const float cx = s.objects[size_t(id)].model[12];
    const double dx = t[0] - cx, dy = t[1], dz = t[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    EXPECT_NEAR(r, 1.0, 2e-3);
    const double nl = std::sqrt(double(t[4]) * t[4] + double(t[5]) * t[5] + double(t[6]) * t[6]);
    EXPECT_GT((dx * t[4] + dy * t[5] + dz * t[6]) / (r * nl), 0.999);
    ++checked;
  }
  EXPECT_GT(checked, 3000);
}

TEST(Raster, SpanningTrianglesHoldAPixelCentreRow) {
  // RasterStats::trianglesSpanning (the performance model's count of triangles a rasterizer's set-up does not reject
  // before computing spans): a thin triangle between the pixel-centre rows 10.5 and 11.5 spans none, the same
  // triangle moved to hold row 10.5 spans one; both are set up (not culled). Window y = (y_ndc + 1) * 16.
  const uint32_t W = 32, H = 32;
  auto spanning = [&](float y0w, float y1w) {
    const float a = y0w / 16.0f - 1.0f, b = y1w / 16.0f - 1.0f;
    const float clip[12] = {-0.5f, a, 0.5f, 1.0f, 0.5f, a, 0.5f, 1.0f, 0.0f, b, 0.5f, 1.0f};
    emu::Framebuffer fb(W, H, 1);
    const emu::RasterStats st = drawOneTriangle(fb, clip);
    EXPECT_EQ(st.trianglesCulled, 0u);
    return st.trianglesSpanning;
  };
  EXPECT_EQ(spanning(10.6f, 11.4f), 0u);
  EXPECT_EQ(spanning(10.4f, 11.4f), 1u);
  EXPECT_EQ(spanning(10.6f, 11.6f), 1u);
  EXPECT_EQ(spanning(3.2f, 20.9f), 1u);
}

TEST(Raster, TrianglesOutsideAClipPlaneAreCountedOnBothSetups) {
  // RasterStats::trianglesOutside (the performance model charges a triangle rejected before set-up at its own cost):
  // a triangle behind the far plane, one beyond x = w (right of the view: outside where the device clips x and y, the
  // draw module; a guard-band device rejects it at set-up instead, culled) and one straddling the right border (not
  // outside) through lavapipe's and SwiftShader's set-up.
  for (const emu::DeviceProfile* p : {&emu::lavapipeProfile(), &emu::swiftshaderProfile()}) {
    const float right[12] = {1.5f, -0.5f, 0.5f, 1.0f, 2.5f, -0.5f, 0.5f, 1.0f, 2.0f, 0.5f, 0.5f, 1.0f};
    const float far[12] = {-0.5f, -0.5f, 1.5f, 1.0f, 0.5f, -0.5f, 1.5f, 1.0f, 0.0f, 0.5f, 1.5f, 1.0f};
    const float straddle[12] = {0.5f, -0.5f, 0.5f, 1.0f, 1.5f, -0.5f, 0.5f, 1.0f, 1.0f, 0.5f, 0.5f, 1.0f};
    const bool xy = p->raster.clip == emu::DeviceProfile::Raster::Clip::DrawModule;
    size_t outside = 0, frags = 0;
    for (const float* clip : {right, far, straddle}) {
      emu::Framebuffer fb(32, 32, 1);
      const emu::RasterStats st = drawOneTriangle(fb, clip, *p);
      outside += st.trianglesOutside, frags += st.fragments;
      if (clip == straddle) EXPECT_EQ(st.trianglesOutside, 0u) << p->name;
      if (clip == far) EXPECT_EQ(st.trianglesOutside, 1u) << p->name;
      if (clip == far) EXPECT_EQ(st.trianglesClipped, 1u) << p->name;  // an outside one is in trianglesClipped too
      if (clip == right) EXPECT_EQ(st.trianglesOutside + st.trianglesCulled, 1u) << p->name;
    }
    EXPECT_EQ(outside, xy ? 2u : 1u) << p->name;
    EXPECT_GT(frags, 0u) << p->name;  // the straddling one covers pixels
  }
}
}  // namespace

namespace {
// RasterStats::blocks and partialBlocks (the performance model's raster costs: llvmpipe runs a 4x4 block's fragment
// stage, depth test included, once whatever its coverage, and tests a partly covered block's pixels against the edges
// first): per triangle, the 4x4-aligned blocks holding a pixel it covers, and of those the ones it covers fewer than
// 16 pixels of. Random triangles of every size (radius 0.3 to 54 pixels) on 40 seeds, each through the shaded path (a
// fragment function: quads) and the depth-only path (lavapipe's blocks), against the quads' covered pixels.
TEST(Raster, BlocksAreTheFourByFourBlocksEachTriangleCovers) {
  const uint32_t W = 150, H = 110;
  size_t full = 0, partial = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    // Inside the view (a clipped triangle is several, each counting its own blocks).
    std::uniform_real_distribution<float> S(seed % 4 == 1 ? 0.3f : 0.5f, seed % 4 == 0 ? 54.0f : seed % 4 == 1 ? 1.5f : 12.0f),
        U(0.0f, 1.0f);
    for (int t = 0; t < 8; ++t) {
      float clip[12];
      const float r = S(rng), cx = r + U(rng) * (float(W) - 2 * r), cy = r + U(rng) * (float(H) - 2 * r);
      for (int v = 0; v < 3; ++v) clipOf(cx + r * std::cos(2.1f * float(v) + 0.3f * float(t)), cy + r * std::sin(2.1f * float(v) + float(seed)),
                                         0.5f, W, H, clip + 4 * v);
      const float vary[3] = {0, 0, 0};
      const uint32_t idx[3] = {0, 1, 2};
      emu::DrawInput in{clip, vary, 1, idx, 1};
      std::map<std::pair<int, int>, int> pixels;  // covered pixels per block
      emu::Framebuffer fb(W, H, 1, 2.0f);
      emu::RasterStats shaded;
      std::mutex m;  // the tiles run in parallel
      emu::draw(dev(), fb, in, [&](const emu::Quad& q, float (*out)[4]) {
        std::lock_guard<std::mutex> lock(m);
        for (int i = 0; i < 4; ++i) {
          out[0][i] = 1.0f;
          if (q.covered & (1u << i)) ++pixels[{(q.x + (i & 1)) >> 2, (q.y + (i >> 1)) >> 2}];
        }
      }, &shaded);
      size_t partly = 0;
      for (const auto& [block, n] : pixels) partly += n < 16;
      EXPECT_EQ(shaded.blocks, pixels.size()) << seed << " " << t;
      EXPECT_EQ(shaded.partialBlocks, partly) << seed << " " << t;
      emu::Framebuffer fb2(W, H, 1, 2.0f);
      emu::RasterStats depthOnly;
      emu::draw(emu::lavapipeProfile(), fb2, in, {}, &depthOnly);
      EXPECT_EQ(depthOnly.blocks, pixels.size()) << seed << " " << t;
      EXPECT_EQ(depthOnly.partialBlocks, partly) << seed << " " << t;
      EXPECT_LE(depthOnly.blocks, depthOnly.quads);
      full += pixels.size() - partly, partial += partly;
    }
  }
  EXPECT_GT(full, 200u);  // both kinds occur
  EXPECT_GT(partial, 200u);
}
}  // namespace
