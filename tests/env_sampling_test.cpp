// The device's environment samplers (shade/env_sampling.h with inputs/env_sampling.h's tables): for the
// kd-tree (fitted block distribution), the alias table over the same blocks and the inversion method,
//   - samples pass a chi-square test against the texel probabilities the method promises, computed
//     independently in double (and the fitted distribution fails against the exact one: the test has
//     power),
//   - the pdf returned with a sample equals the pdf looked up for its direction (what MIS needs),
//   - the pdf integrates to 1 over the sphere,
//   - the scalar and the 8-lane builds give the same bits,
//   - hard cases: an environment without light, one bright pixel, n = 1, city's sun, negative texels.
#include "inputs/env_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include "emu/device_profile.h"
#include "passes/shade.h"
#include "inputs/environment.h"
#include "chi_square.h"
#include "lanes/instantiate.h"

namespace {
namespace sc = shadetwin::shade::scalar;
namespace x8 = shadetwin::shade::x8;
using shadetwin::EnvSamplingTables;
constexpr double kPi = std::numbers::pi;
const uint32_t kMethods[] = {sc::kEnvKdTree, sc::kEnvAlias, sc::kEnvInversion};

emu::Texture envTexture(uint32_t W, uint32_t H, const std::vector<float>& rgba) {
  return emu::floatTexture(emu::Format::RGBA32F, W, H, rgba.data());
}

// A 64 x 32 map: log-normal noise, a bright 2 x 2 spot, a band of 3 rows of negative texels (the
// middle row has no positive neighbour: weight 0).
emu::Texture syntheticEnv(uint32_t W = 64, uint32_t H = 32) {
  std::mt19937 rng(11);
  std::normal_distribution<float> N(0.0f, 1.5f);
  std::vector<float> t(size_t(W) * H * 4, 1.0f);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      float* p = &t[4 * (size_t(y) * W + x)];
      const float v = std::exp(N(rng));
      p[0] = v, p[1] = v * 0.8f, p[2] = v * 1.1f;
      if (y + 1 >= H / 4 && y <= H / 4 + 1) p[0] = p[1] = p[2] = -0.5f;  // negative texels (real in the CC0 maps)
      if ((x == W / 3 || x == W / 3 + 1) && (y == H / 2 || y == H / 2 + 1)) p[0] = p[1] = p[2] = 3000.0f;
    }
  return envTexture(W, H, t);
}

struct Bound {
  EnvSamplingTables T;
  shadetwin::shade::Sampler2D table, texels;
  sc::EnvSampling s;
};
Bound bind(const emu::Texture& env, uint32_t method, uint32_t blocks) {
  Bound b{shadetwin::envSamplingTables(env, method, blocks), {}, {}, {}};
  const auto& dev = emu::lavapipeProfile();
  b.table = shadetwin::environmentSampler(*b.T.table, dev, false);
  b.texels = shadetwin::environmentSampler(*b.T.texels, dev, false);
  const auto& u = b.T.uniforms;
  b.s = shadetwin::toEnvSampling<sc::EnvSampling>(u);
  return b;
}

sc::Float4 uniform4(uint32_t i, uint32_t seed) {
  return sc::philoxUniform4(sc::philox4x32(sc::Philox4{i, 0u, 0u, 0u}, seed, 99u));
}

// Texel of a direction, in double (independent of the shared equirectUv).
uint32_t texelOf(const sc::Float3& d, uint32_t W, uint32_t H) {
  double u = std::atan2(double(d.x), -double(d.z)) / (2 * kPi) + 0.5;
  u -= std::floor(u);
  const double v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / kPi;
  const uint32_t x = std::min(W - 1, uint32_t(u * W)), y = std::min(H - 1, uint32_t(v * H));
  return y * W + x;
}

// The texel probabilities a method promises, in double: inversion w_t / total; blocks P_k / texels_k
// with P_k the exact sum_k / total (alias) or the fitted P_k(alpha) (kd-tree).
std::vector<double> promisedTexelProbabilities(const emu::Texture& env, uint32_t method, uint32_t blocks, bool fitted) {
  const uint32_t W = env.width(), H = env.height();
  std::vector<double> w = shadetwin::envSamplingWeights(reinterpret_cast<const float*>(env.levels()[0].data()), W, H);
  double total = 0;
  for (double v : w) total += v;
  std::vector<double> p(w.size(), 0.0);
  if (method == sc::kEnvInversion) {
    for (size_t i = 0; i < w.size(); ++i) p[i] = w[i] / total;
    return p;
  }
  const auto tree = shadetwin::buildEnvKdTree(w, W, H, blocks);
  const auto order = shadetwin::blocksByMean(tree);
  std::vector<double> e;
  for (uint32_t i : order) e.push_back(tree.blocks[i].sum / tree.total);
  const double alpha = shadetwin::fitBlockAlpha(e).alpha;
  for (uint32_t k = 0; k < order.size(); ++k) {
    const auto& b = tree.blocks[order[k]];
    const double P = fitted ? shadetwin::fittedBlockProbability(alpha, uint32_t(order.size()), k) : e[k];
    for (uint32_t y = b.y0; y < b.y1; ++y)
      for (uint32_t x = b.x0; x < b.x1; ++x) p[size_t(y) * W + x] = P / b.texels();
  }
  return p;
}

double chiSquarePValue(const std::vector<double>& prob, const std::vector<double>& observed, double n, int* dofOut = nullptr) {
  const shadetwin::test::ChiSquare c = shadetwin::test::pooledChiSquare(prob, observed, n);
  if (dofOut) *dofOut = c.dof;
  return c.pValue;
}

std::vector<double> histogram(const Bound& b, int n, uint32_t seed) {
  std::vector<double> h(size_t(b.s.width) * b.s.height, 0.0);
  for (int i = 0; i < n; ++i) {
    const sc::EnvSample e = sc::sampleEnv(b.table, b.texels, b.s, uniform4(uint32_t(i), seed));
    if (e.pdf > 0.0f) h[texelOf(e.dir, b.s.width, b.s.height)] += 1;
  }
  return h;
}

TEST(EnvSampling, SamplesPassChiSquareAgainstThePromisedProbabilities) {
  const emu::Texture env = syntheticEnv();
  const int n = 400000;
  for (uint32_t m : kMethods) {
    const Bound b = bind(env, m, 64);
    const auto p = promisedTexelProbabilities(env, m, 64, m == sc::kEnvKdTree);
    int dof = 0;
    const auto h = histogram(b, n, 5);
    const double pv = chiSquarePValue(p, h, n, &dof);
    if (m == sc::kEnvInversion)  // the middle negative row has weight 0: never drawn
      for (uint32_t x = 0; x < 64; ++x) EXPECT_EQ(h[8 * 64 + x], 0.0) << x;
    EXPECT_GT(pv, 1e-3) << "method " << m << " dof " << dof;
    EXPECT_GT(dof, 40) << m;
  }
}

TEST(EnvSampling, FittedDistributionIsNotTheExactOne) {
  // Power of the test above: the kd-tree's samples against the exact block probabilities are rejected
  // (the one-parameter fit does not reproduce them), the alias table's are not.
  const emu::Texture env = syntheticEnv();
  const int n = 400000;
  const auto exact = promisedTexelProbabilities(env, sc::kEnvAlias, 64, false);
  EXPECT_LT(chiSquarePValue(exact, histogram(bind(env, sc::kEnvKdTree, 64), n, 6), n), 1e-9);
  EXPECT_GT(chiSquarePValue(exact, histogram(bind(env, sc::kEnvAlias, 64), n, 6), n), 1e-3);
}

TEST(EnvSampling, SamplePdfEqualsLookedUpPdf) {
  const emu::Texture env = syntheticEnv();
  for (uint32_t m : kMethods) {
    const Bound b = bind(env, m, 64);
    int agree = 0, total = 0;
    for (uint32_t i = 0; i < 20000; ++i) {
      const sc::EnvSample e = sc::sampleEnv(b.table, b.texels, b.s, uniform4(i, 8));
      if (!(e.pdf > 0.0f)) continue;
      ++total;
      const float q = sc::envPdf(b.table, b.texels, b.s, e.dir);
      agree += std::fabs(q - e.pdf) <= 1e-3f * e.pdf;
    }
    // Directions on a texel boundary may round into the neighbour: at most 0.5%.
    EXPECT_GE(agree, total * 0.995) << m;
    EXPECT_GT(total, 19000) << m;
  }
}

double pdfIntegral(const Bound& b, int sub) {
  // Midpoint rule over a grid `sub` times finer than the texels: sum pdf 2 pi^2 sin(theta) du dv.
  const uint32_t W = b.s.width * uint32_t(sub), H = b.s.height * uint32_t(sub);
  double sum = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const double u = (x + 0.5) / W, v = (y + 0.5) / H, phi = (u - 0.5) * 2 * kPi, th = v * kPi;
      const sc::Float3 d(float(std::sin(th) * std::sin(phi)), float(std::cos(th)),
                         float(-std::sin(th) * std::cos(phi)));
      sum += double(sc::envPdf(b.table, b.texels, b.s, d)) * 2 * kPi * kPi * std::sin(th) / (double(W) * H);
    }
  return sum;
}

TEST(EnvSampling, PdfIntegratesToOne) {
  const emu::Texture env = syntheticEnv();
  for (uint32_t m : kMethods) EXPECT_NEAR(pdfIntegral(bind(env, m, 64), 4), 1.0, 2e-3) << m;
}

TEST(EnvSampling, ScalarAndSimdBuildsAgree) {
  const emu::Texture env = syntheticEnv();
  using F8 = emu::F32<8>;
  for (uint32_t m : kMethods) {
    const Bound b = bind(env, m, 64);
    const auto s8 = shadetwin::toEnvSampling<x8::EnvSampling>(b.T.uniforms);
    for (uint32_t i = 0; i < 4096; i += 8) {
      emu::U32<8> ctr;
      for (int l = 0; l < 8; ++l) ctr.set(l, i + uint32_t(l));
      const x8::Float4 u = x8::philoxUniform4(x8::philox4x32(
          x8::Philox4{ctr, emu::U32<8>(0u), emu::U32<8>(0u), emu::U32<8>(0u)}, emu::U32<8>(3u), emu::U32<8>(99u)));
      const x8::EnvSample e = x8::sampleEnv(b.table, b.texels, s8, u);
      const F8 q = x8::envPdf(b.table, b.texels, s8, e.dir);
      for (int l = 0; l < 8; ++l) {
        const sc::EnvSample r = sc::sampleEnv(b.table, b.texels, b.s, sc::Float4(u.x[l], u.y[l], u.z[l], u.w[l]));
        ASSERT_EQ(std::bit_cast<uint32_t>(e.dir.x[l]), std::bit_cast<uint32_t>(r.dir.x));
        ASSERT_EQ(std::bit_cast<uint32_t>(e.dir.y[l]), std::bit_cast<uint32_t>(r.dir.y));
        ASSERT_EQ(std::bit_cast<uint32_t>(e.dir.z[l]), std::bit_cast<uint32_t>(r.dir.z));
        ASSERT_EQ(std::bit_cast<uint32_t>(e.pdf[l]), std::bit_cast<uint32_t>(r.pdf));
        ASSERT_EQ(std::bit_cast<uint32_t>(q[l]), std::bit_cast<uint32_t>(sc::envPdf(b.table, b.texels, b.s, r.dir)));
      }
    }
  }
}

TEST(EnvSampling, EnvironmentWithoutLightIsSampledUniformly) {
  std::vector<float> t(32 * 16 * 4, 0.0f);
  for (size_t i = 0; i < t.size(); i += 4)
    t[i] = t[i + 1] = t[i + 2] = (i / 4) % 3 ? 0.0f : -1.0f;  // zeros and negatives
  const emu::Texture env = envTexture(32, 16, t);
  for (uint32_t m : kMethods) {
    const Bound b = bind(env, m, 64);
    EXPECT_NEAR(pdfIntegral(b, 4), 1.0, 2e-3) << m;
    // Uniform over the sphere: the pdf at the equator is 1 / (4 pi) up to the row's sin(theta) step.
    const float p = sc::envPdf(b.table, b.texels, b.s, sc::Float3(1.0f, 0.0f, 0.0f));
    EXPECT_NEAR(p * 4 * kPi, 1.0, 0.01) << m;
  }
}

TEST(EnvSampling, SingleBrightPixelAndOneBlock) {
  std::vector<float> t(64 * 32 * 4, 0.0f);
  for (size_t i = 0; i < t.size(); i += 4) t[i] = t[i + 1] = t[i + 2] = 0.01f;
  float* sun = &t[4 * (size_t(10) * 64 + 40)];
  sun[0] = sun[1] = sun[2] = 50000.0f;
  const emu::Texture env = envTexture(64, 32, t);
  const int n = 20000;
  for (uint32_t m : kMethods) {
    const Bound b = bind(env, m, 64);
    const auto h = histogram(b, n, 4);
    // Weights are the 3 x 3 neighbourhood maxima (inputs/env_kdtree.h): the pixel and its 8 neighbours
    // hold 99.9% of the weight; the alias table and inversion draw them that often, the kd-tree as
    // often as its fitted distribution gives their blocks.
    const auto p = promisedTexelProbabilities(env, m, 64, m == sc::kEnvKdTree);
    double hit = 0, promised = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        hit += h[size_t(10 + dy) * 64 + size_t(40 + dx)] / n, promised += p[size_t(10 + dy) * 64 + size_t(40 + dx)];
    EXPECT_NEAR(hit, promised, 4 * std::sqrt(promised * (1 - promised) / n) + 1e-4) << m;
    if (m != sc::kEnvKdTree) {
      EXPECT_GT(hit, 0.99) << m;
    }
  }
  // n = 1: one block, the whole map, uniform in (u, v): pdf 1 / (2 pi^2 sin theta).
  const Bound one = bind(env, sc::kEnvKdTree, 1);
  EXPECT_EQ(one.T.uniforms.count, 1u);
  EXPECT_NEAR(sc::envPdf(one.table, one.texels, one.s, sc::Float3(0.0f, 0.0f, -1.0f)) * 2 * kPi * kPi, 1.0, 1e-5);
  EXPECT_NEAR(pdfIntegral(one, 2), 1.0, 1e-3);
}

TEST(EnvSampling, CitySunAndNegativeTexels) {
  std::ostringstream quiet;
  const shadetwin::EnvironmentMap m =
      shadetwin::loadEnvironment(std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/city.exr", quiet);
  const emu::Texture env = envTexture(m.width, m.height, m.levels[0]);
  for (uint32_t method : kMethods) {
    const Bound b = bind(env, method, 6144);
    EXPECT_NEAR(pdfIntegral(b, 1), 1.0, 2e-3) << method;
    const auto p = promisedTexelProbabilities(env, method, 6144, method == sc::kEnvKdTree);
    // Inversion never draws a texel of zero weight (negative or zero luminance in its whole 3 x 3
    // neighbourhood); the block samplers draw one only as part of a block with positive mass,
    // uniformly (the chi-square test below checks that rate).
    const auto h = histogram(b, 200000, 12);
    const auto w = shadetwin::envSamplingWeights(m.levels[0].data(), m.width, m.height);
    double zeroHits = 0;
    for (size_t i = 0; i < h.size(); ++i)
      if (w[i] == 0 && method == sc::kEnvInversion) zeroHits += h[i];
    EXPECT_EQ(zeroHits, 0.0) << method;
    int dof = 0;
    EXPECT_GT(chiSquarePValue(p, h, 200000, &dof), 1e-3) << method << " dof " << dof;
  }
}

}  // namespace
