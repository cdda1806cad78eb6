// Kd-tree partition of the environment (render/env_kdtree.h, issue 5 item 1): a partition of the map,
// the greedy split is the best cut, and the hard cases of the issue: a constant environment, a single
// bright pixel, blocks of one pixel, n = 1, negative texels, the sun of city.exr.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "render/env_kdtree.h"
#include "render/render.h"

namespace {

void expectPartition(const shadetwin::EnvKdTree& t, const std::vector<double>& w) {
  std::vector<int> cover(size_t(t.width) * t.height, 0);
  double sum = 0;
  for (const auto& b : t.blocks) {
    ASSERT_LT(b.x0, b.x1);
    ASSERT_LT(b.y0, b.y1);
    ASSERT_LE(b.x1, t.width);
    ASSERT_LE(b.y1, t.height);
    double s = 0;
    for (uint32_t y = b.y0; y < b.y1; ++y)
      for (uint32_t x = b.x0; x < b.x1; ++x) ++cover[size_t(y) * t.width + x], s += w[size_t(y) * t.width + x];
    EXPECT_NEAR(b.sum, s, 1e-9 * (std::fabs(t.total) + 1e-30));
    sum += b.sum;
  }
  for (int c : cover) ASSERT_EQ(c, 1);
  EXPECT_NEAR(sum, t.total, 1e-9 * (t.total + 1e-30));
}

TEST(EnvKdTree, FirstSplitIsTheBestCut) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  const uint32_t W = 16, H = 8;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> w(W * H);
    for (auto& v : w) v = std::pow(U(rng), 4) * 10;
    const auto t = shadetwin::buildEnvKdTree(w, W, H, 2);
    ASSERT_EQ(t.blocks.size(), 2u);
    // Brute force: every vertical and horizontal cut, sums by direct loops.
    auto sumOf = [&](uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
      double s = 0;
      for (uint32_t y = y0; y < y1; ++y)
        for (uint32_t x = x0; x < x1; ++x) s += w[y * W + x];
      return s;
    };
    double best = -1;
    for (uint32_t x = 1; x < W; ++x) {
      const double l = sumOf(0, 0, x, H), r = sumOf(x, 0, W, H);
      best = std::max(best, l * l / (x * H) + r * r / ((W - x) * H));
    }
    for (uint32_t y = 1; y < H; ++y) {
      const double l = sumOf(0, 0, W, y), r = sumOf(0, y, W, H);
      best = std::max(best, l * l / (y * W) + r * r / ((H - y) * W));
    }
    const auto& a = t.blocks[0];
    const auto& b = t.blocks[1];
    EXPECT_NEAR(a.sum * a.sum / a.texels() + b.sum * b.sum / b.texels(), best, 1e-9 * best) << trial;
    expectPartition(t, w);
  }
}

TEST(EnvKdTree, ConstantWeightsStayOneBlockAndNIsOne) {
  std::vector<double> w(64 * 32, 2.5);
  EXPECT_EQ(shadetwin::buildEnvKdTree(w, 64, 32, 6144).blocks.size(), 1u);  // SSE 0: nothing to split
  std::mt19937 rng(5);
  for (auto& v : w) v = double(rng() % 100);
  const auto one = shadetwin::buildEnvKdTree(w, 64, 32, 1);
  ASSERT_EQ(one.blocks.size(), 1u);
  EXPECT_EQ(one.blocks[0].texels(), 64u * 32u);
}

TEST(EnvKdTree, ConstantEnvironmentSplitsOnlyRows) {
  // A constant radiance gives w = L sin(theta): constant along rows, so every cut is between rows and
  // every block spans the whole width; the partition stops when every block is one row.
  const uint32_t W = 64, H = 32;
  std::vector<float> rgba(size_t(W) * H * 4, 1.0f);
  const auto w = shadetwin::envSamplingWeights(rgba.data(), W, H);
  const auto t = shadetwin::buildEnvKdTree(w, W, H, 6144);
  EXPECT_LE(t.blocks.size(), size_t(H));
  for (const auto& b : t.blocks) {
    EXPECT_EQ(b.x0, 0u);
    EXPECT_EQ(b.x1, W);
  }
  expectPartition(t, w);
}

TEST(EnvKdTree, SingleBrightPixelIsIsolated) {
  const uint32_t W = 64, H = 32;
  std::vector<double> w(W * H, 0.0);
  w[size_t(11) * W + 40] = 30000.0;
  const auto t = shadetwin::buildEnvKdTree(w, W, H, 6144);
  EXPECT_LE(t.blocks.size(), 5u);  // at most four cuts isolate it; then every block has SSE 0
  int single = 0;
  for (const auto& b : t.blocks)
    if (b.texels() == 1 && b.x0 == 40 && b.y0 == 11 && b.sum == 30000.0) ++single;
  EXPECT_EQ(single, 1);
  expectPartition(t, w);
}

TEST(EnvKdTree, BlocksOfOnePixel) {
  // As many blocks as texels on a random map: the partition ends with every texel its own block.
  std::mt19937 rng(9);
  std::vector<double> w(8 * 4);
  for (auto& v : w) v = 1.0 + double(rng() % 1000);
  const auto t = shadetwin::buildEnvKdTree(w, 8, 4, 32);
  ASSERT_EQ(t.blocks.size(), 32u);
  for (const auto& b : t.blocks) EXPECT_EQ(b.texels(), 1u);
  expectPartition(t, w);
}

TEST(EnvKdTree, RealMapsWithSunAndNegativeTexels) {
  for (const char* name : {"city", "forest"}) {
    std::ostringstream quiet;
    const shadetwin::EnvironmentMap env =
        shadetwin::loadEnvironment(std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/" + name + ".exr", quiet);
    const auto w = shadetwin::envSamplingWeights(env.levels[0].data(), env.width, env.height);
    for (double v : w) ASSERT_GE(v, 0.0);  // negative luminance carries no probability
    const auto t = shadetwin::buildEnvKdTree(w, env.width, env.height, 6144);
    EXPECT_EQ(t.blocks.size(), 6144u) << name;
    expectPartition(t, w);
    if (std::string(name) == "city") {
      // The sun (> 30,000) is resolved: the block holding the brightest texel is small.
      size_t arg = 0;
      for (size_t i = 0; i < w.size(); ++i)
        if (w[i] > w[arg]) arg = i;
      const uint32_t sx = uint32_t(arg % env.width), sy = uint32_t(arg / env.width);
      for (const auto& b : t.blocks) {
        if (sx >= b.x0 && sx < b.x1 && sy >= b.y0 && sy < b.y1) {
          EXPECT_LE(b.texels(), 16u);
        }
      }
    }
  }
}

}  // namespace
