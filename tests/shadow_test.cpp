// Shadow-map passes on the emulator (src/passes/shadow.cpp): light frames, coverage of the bounding
// sphere, analytic depth of a sphere's pole, thread-count independence. The emulator-vs-lavapipe
// comparison is the ctest `verify_shadow_*` (shadetwin verify shadow).
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "passes/shadow.h"
#include "scene/scene.h"

namespace {

const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }

shadetwin::Scene unitSphereScene() {
  shadetwin::Scene s;
  s.meshes.push_back(shadetwin::makeSphere(192, 96));
  s.materials.push_back({});
  shadetwin::Object o;
  o.model = shadetwin::identity();
  s.objects.push_back(o);
  return s;
}

TEST(ShadowDirections, UnitAndBalanced) {
  auto d = shadetwin::sphereDirections(256);
  ASSERT_EQ(d.size(), 256u);
  double sum[3] = {0, 0, 0};
  for (auto& v : d) {
    EXPECT_NEAR(std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]), 1.0, 1e-6);
    for (int k = 0; k < 3; ++k) sum[k] += v[size_t(k)];
  }
  for (double s : sum) EXPECT_LT(std::fabs(s) / 256.0, 0.01);
}

TEST(ShadowViewProjection, BoundsInsideTheViewVolume) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/teapot.json");
  const auto [lo, hi] = s.bounds();
  for (const auto& d : shadetwin::sphereDirections(64)) {
    const shadetwin::Mat4 m = shadetwin::shadowViewProjection(s, d);
    for (int c = 0; c < 8; ++c) {
      const float p[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]};
      float q[4];
      for (int r = 0; r < 4; ++r) q[r] = m[size_t(r)] * p[0] + m[size_t(4 + r)] * p[1] + m[size_t(8 + r)] * p[2] + m[size_t(12 + r)];
      EXPECT_EQ(q[3], 1.0f);
      EXPECT_LT(std::fabs(q[0]), 1.0f);
      EXPECT_LT(std::fabs(q[1]), 1.0f);
      EXPECT_GT(q[2], 0.0f);
      EXPECT_LT(q[2], 1.0f);
    }
  }
  // Straight up and straight down (the frame's helper axis switches) also work.
  for (float y : {1.0f, -1.0f}) {
    const shadetwin::Mat4 m = shadetwin::shadowViewProjection(s, {0.0f, y, 0.0f});
    for (float v : m) EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(ShadowMaps, UnitSphereFromAbove) {
  // Bounding sphere radius r = 1.02 * sqrt(3); the unit sphere covers pi / (4 r^2) of the map and
  // its pole (0, 1, 0) is at depth 1/2 - 1 / (2 r).
  shadetwin::Scene s = unitSphereScene();
  const uint32_t N = 512;
  shadetwin::ShadowMaps sm = shadetwin::shadowEmu(s, {{0.0f, 1.0f, 0.0f}}, N, dev());
  const double r = 1.02 * std::sqrt(3.0);
  size_t covered = 0;
  float minDepth = 1.0f;
  for (size_t p = 0; p < size_t(N) * N; ++p) {
    covered += sm.map(0)[p] < 1.0f;
    minDepth = std::min(minDepth, sm.map(0)[p]);
  }
  EXPECT_NEAR(double(covered) / (N * N), std::acos(-1.0) / (4 * r * r), 0.005);
  EXPECT_NEAR(minDepth, 0.5 - 1.0 / (2 * r), 2e-4);
  const float centre = sm.map(0)[size_t(N / 2) * N + N / 2];
  EXPECT_NEAR(centre, 0.5 - 1.0 / (2 * r), 2e-4);
  // From below the pole (0, -1, 0) is nearest: same depth by symmetry.
  shadetwin::ShadowMaps below = shadetwin::shadowEmu(s, {{0.0f, -1.0f, 0.0f}}, N, dev());
  EXPECT_NEAR(below.map(0)[size_t(N / 2) * N + N / 2], 0.5 - 1.0 / (2 * r), 2e-4);
}

TEST(ShadowMaps, ThreadCountIndependent) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/bunny.json");
  const auto dirs = shadetwin::sphereDirections(6);
  std::vector<std::vector<float>> ref;
  for (int threads : {1, 2, 16}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(threads));
    shadetwin::ShadowStats st;
    shadetwin::ShadowMaps sm = shadetwin::shadowEmu(s, dirs, 256, dev(), &st);
    if (ref.empty()) {
      ref = sm.maps;
      EXPECT_GT(st.raster.fragments, 6u * 3000u);
      EXPECT_EQ(st.raster.trianglesClipped, 0u);
    } else {
      ASSERT_EQ(ref, sm.maps) << threads << " threads";  // float ==: no NaN depths
    }
  }
}

// The pass's statistics are the sum of its maps' (the performance model costs every counted class; session 34 found
// trianglesSpanning and trianglesOutside left out of the sum, so the shadow pass counted 0 spanning triangles): each
// direction alone, then all at once, for map sizes from 32^2 (few triangles span a pixel row) to 1024^2 (nearly all).
TEST(ShadowMaps, StatisticsAreTheSumOfTheMaps) {
  const shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/bunny.json");
  const auto dirs = shadetwin::sphereDirections(5);
  size_t triangles = 0;
  for (const auto& o : s.objects) triangles += s.meshes[o.mesh].indices.size() / 3;
  double previous = 0.0;
  for (uint32_t size : {32u, 128u, 1024u}) {
    shadetwin::ShadowStats all;
    shadetwin::shadowEmu(s, dirs, size, dev(), &all);
    size_t spanning = 0, outside = 0, fragments = 0;
    for (const auto& d : dirs) {
      shadetwin::ShadowStats one;
      shadetwin::shadowEmu(s, {d}, size, dev(), &one);
      spanning += one.raster.trianglesSpanning, outside += one.raster.trianglesOutside, fragments += one.raster.fragments;
    }
    EXPECT_EQ(all.raster.trianglesSpanning, spanning) << size;
    EXPECT_EQ(all.raster.trianglesOutside, outside) << size;  // the maps enclose the scene: 0
    EXPECT_EQ(all.raster.fragments, fragments) << size;
    EXPECT_EQ(all.raster.trianglesIn, triangles * dirs.size()) << size;
    const double share = double(spanning) / double(all.raster.trianglesIn);
    EXPECT_GT(share, previous) << size;  // larger maps: more of the bunny's triangles span a row
    EXPECT_LE(share, 1.0) << size;
    previous = share;
  }
  EXPECT_GT(previous, 0.95);  // at 1024^2 nearly every triangle spans a row (bunny.json's 16 maps: 58,797 of 58,816)
}

}  // namespace
