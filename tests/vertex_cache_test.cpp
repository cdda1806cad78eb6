// The performance model's post-transform vertex cache (issue 19, model/vertex_cache.h): SwiftShader's direct-mapped
// cache over each batch of a draw's index stream, a miss shading a SIMD width of consecutive entries.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "model/vertex_cache.h"
#include "scene/mesh.h"

namespace {
using shadetwin::model::vertexCacheRuns;
using shadetwin::model::VertexCacheDesc;

TEST(VertexCache, RunsFollowTheDirectMappedCache) {
  EXPECT_EQ(vertexCacheRuns({0, 1, 2}, VertexCacheDesc{}), 0u);  // not simulated
  // A miss shades the next 4 entries: 0 misses (0, 1, 2, 2 shaded), then only 3 misses.
  EXPECT_EQ(vertexCacheRuns({0, 1, 2, 2, 1, 3}, {64, 128, 4}), 2u);
  // 0 and 64 share a slot of 64: each evicts the other.
  EXPECT_EQ(vertexCacheRuns({0, 64, 0, 64, 0, 64}, {64, 128, 1}), 6u);
  EXPECT_EQ(vertexCacheRuns({0, 64, 0, 64, 0, 64}, {128, 128, 1}), 2u);
  // Every batch starts cold.
  EXPECT_EQ(vertexCacheRuns({0, 1, 2, 0, 1, 2}, {64, 1, 1}), 6u);
  EXPECT_EQ(vertexCacheRuns({0, 1, 2, 0, 1, 2}, {64, 2, 1}), 3u);
}

TEST(VertexCache, BoundsOnRandomMeshes) {
  for (uint32_t seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    const uint32_t vertices = 8 + rng() % 500, triangles = 1 + rng() % 2000;
    std::vector<uint32_t> idx(size_t(triangles) * 3);
    for (auto& i : idx) i = rng() % vertices;
    const size_t unique = std::set<uint32_t>(idx.begin(), idx.end()).size();
    // A cache larger than the index range, one batch, one lane a run: every vertex once.
    EXPECT_EQ(vertexCacheRuns(idx, {1024, triangles, 1}), unique) << seed;
    for (uint32_t lanes : {1u, 4u}) {
      const uint64_t r = vertexCacheRuns(idx, {64, 128, lanes});
      EXPECT_LE(r, idx.size()) << seed;
      EXPECT_GE(r * lanes, unique) << seed;  // every vertex is shaded at least once, `lanes` a run
    }
    // More entries never miss more often with one lane a run (a direct-mapped cache of 2^k+1 slots refines 2^k's).
    EXPECT_LE(vertexCacheRuns(idx, {128, 128, 1}), vertexCacheRuns(idx, {64, 128, 1})) << seed;
  }
}

// calibrate's two spheres: the same triangles, 1.5 runs a triangle in makeSphere's numbering (a row of 257 vertices
// puts a and a + 257 in one slot of 64) against 0.5 numbered in strips.
TEST(VertexCache, StripNumberingHoldsTheSameTrianglesInFewerRuns) {
  const shadetwin::Mesh a = shadetwin::makeSphere(256, 128), b = shadetwin::makeSphereStrips(256, 128, 8);
  ASSERT_EQ(a.indices.size(), b.indices.size());
  auto triangles = [](const shadetwin::Mesh& m) {
    std::multiset<std::array<float, 9>> t;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
      std::array<float, 9> p{};
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) p[size_t(3 * k + c)] = m.positions[m.indices[i + size_t(k)]][size_t(c)];
      t.insert(p);
    }
    return t;
  };
  EXPECT_EQ(triangles(a), triangles(b));
  const VertexCacheDesc swiftshader{64, 128, 4};
  const double ra = double(vertexCacheRuns(a.indices, swiftshader)) / a.triangles();
  const double rb = double(vertexCacheRuns(b.indices, swiftshader)) / b.triangles();
  EXPECT_NEAR(ra, 1.50, 0.02);
  EXPECT_NEAR(rb, 0.51, 0.02);
}

}  // namespace
