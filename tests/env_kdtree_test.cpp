// Kd-tree partition of the environment (inputs/env_kdtree.h, issue 5 item 1): a partition of the map,
// the greedy split is the best cut, and the hard cases of the issue: a constant environment, a single
// bright pixel, blocks of one pixel, n = 1, negative texels, the sun of city.exr.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "inputs/env_kdtree.h"
#include "inputs/environment.h"

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

// ---- block distribution (item 2) ----

TEST(EnvBlockFit, FittedProbabilitiesSumToOneAndDecrease) {
  for (uint32_t n : {1u, 2u, 7u, 6144u})
    for (double alpha : {1e-6, 0.3, 17.0, 5000.0, 1e9}) {
      double s = 0, prev = 2;
      for (uint32_t k = 0; k < n; ++k) {
        const double p = shadetwin::fittedBlockProbability(alpha, n, k);
        EXPECT_GT(p, 0.0);
        EXPECT_LE(p, prev * (1 + 1e-12));
        prev = p, s += p;
      }
      EXPECT_NEAR(s, 1.0, 1e-9) << n << " " << alpha;
    }
  EXPECT_DOUBLE_EQ(shadetwin::fittedBlockProbability(0.5, 1, 0), 1.0);  // n = 1: the only block
}

TEST(EnvBlockFit, InversionDrawsTheBlockProbabilities) {
  // x = alpha ((1 + n/alpha)^xi - 1) at xi on a fine grid: the share of xi landing in [k, k+1) is P_k.
  const uint32_t n = 50;
  const double alpha = 2.5;
  std::vector<double> hits(n, 0);
  const int M = 1000000;
  for (int i = 0; i < M; ++i) {
    const double xi = (i + 0.5) / M;
    const double x = alpha * (std::pow(1 + n / alpha, xi) - 1);
    ++hits[std::min(n - 1, uint32_t(x))];
  }
  for (uint32_t k = 0; k < n; ++k) EXPECT_NEAR(hits[k] / M, shadetwin::fittedBlockProbability(alpha, n, k), 2.0 / M);
}

TEST(EnvBlockFit, RecoversAlphaOfExactData) {
  const uint32_t n = 6144;
  for (double alpha : {0.3, 17.0, 5000.0}) {
    std::vector<double> e(n);
    for (uint32_t k = 0; k < n; ++k) e[k] = shadetwin::fittedBlockProbability(alpha, n, k);
    const auto fit = shadetwin::fitBlockAlpha(e);
    EXPECT_NEAR(fit.alpha / alpha, 1.0, 1e-5) << alpha;
    EXPECT_LT(fit.l1, 1e-6) << alpha;
  }
}

// The optimizer against a brute-force scan of 20,000 log-spaced alphas over the same range: never
// worse than the scan (up to the scan's resolution it finds the global minimum), on real maps and on
// noisy non-monotone data.
TEST(EnvBlockFit, OptimizerIsAtLeastAsGoodAsABruteForceScan) {
  std::vector<std::vector<double>> cases;
  for (const char* name : {"city", "studio"}) {
    std::ostringstream quiet;
    const shadetwin::EnvironmentMap env =
        shadetwin::loadEnvironment(std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/" + name + ".exr", quiet);
    const auto w = shadetwin::envSamplingWeights(env.levels[0].data(), env.width, env.height);
    const auto t = shadetwin::buildEnvKdTree(w, env.width, env.height, 1024);
    std::vector<double> e;
    for (uint32_t i : shadetwin::blocksByMean(t)) e.push_back(t.blocks[i].sum / t.total);
    cases.push_back(e);
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> e(300);
    double s = 0;
    for (auto& v : e) v = std::pow(U(rng), 3 + 3 * c), s += v;
    for (auto& v : e) v /= s;
    cases.push_back(e);
  }
  for (size_t c = 0; c < cases.size(); ++c) {
    const auto& e = cases[c];
    const auto fit = shadetwin::fitBlockAlpha(e);
    EXPECT_NEAR(fit.l1, shadetwin::blockFitL1(e, fit.alpha), 1e-12);
    const double lo = std::log(1e-6), hi = std::log(1e6 * double(e.size()));
    double best = 1e300;
    for (int i = 0; i < 20000; ++i) best = std::min(best, shadetwin::blockFitL1(e, std::exp(lo + (hi - lo) * i / 19999.0)));
    EXPECT_LE(fit.l1, best + 1e-9) << "case " << c;
    EXPECT_GE(fit.l1, 0.0);
  }
}

TEST(EnvBlockFit, BlocksByMeanIsSortedAndAPermutation) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<double> w(64 * 32);
  for (auto& v : w) v = std::pow(U(rng), 6);
  const auto t = shadetwin::buildEnvKdTree(w, 64, 32, 100);
  const auto order = shadetwin::blocksByMean(t);
  ASSERT_EQ(order.size(), t.blocks.size());
  std::vector<int> seen(order.size(), 0);
  for (size_t i = 0; i < order.size(); ++i) {
    ++seen[order[i]];
    if (i) {
      const auto& a = t.blocks[order[i - 1]];
      const auto& b = t.blocks[order[i]];
      EXPECT_GE(a.sum / a.texels(), b.sum / b.texels());
    }
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

}  // namespace
