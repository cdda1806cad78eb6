// MIS shading (shade/shade_env_mis.h): the weights of both strategies sum to one, the BRDF mixture's
// sampler and pdf agree, and the whole per-pixel estimator is unbiased: its mean over many frames
// (independent Philox keys) equals a dense quadrature of the same integrand, for each environment
// sampler (kd-tree, alias, inversion) and the balance and power heuristics.
#include <gtest/gtest.h>

#include <cstring>

#include <cmath>
#include <numbers>
#include <random>

#include "emu/device_profile.h"
#include "inputs/env_sampling.h"
#include "passes/shade.h"
#include "lanes/instantiate.h"

namespace {
namespace sc = shadetwin::shade::scalar;
constexpr double kPi = std::numbers::pi;

TEST(EnvMis, WeightsOfBothStrategiesSumToOne) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> E(-8.0f, 8.0f);
  for (int i = 0; i < 10000; ++i) {
    const float p = std::exp2(E(rng)), q = std::exp2(E(rng));
    for (uint32_t h : {sc::kMisBalance, sc::kMisPower}) {
      const float we = sc::misWeightOverPdf(h, true, p, q) * p, wb = sc::misWeightOverPdf(h, false, q, p) * q;
      EXPECT_NEAR(we + wb, 1.0f, 1e-5f) << h << " " << p << " " << q;
    }
    EXPECT_NEAR(sc::misWeightOverPdf(sc::kMisEnvOnly, true, p, q) * p, 1.0f, 1e-6f);
    EXPECT_EQ(sc::misWeightOverPdf(sc::kMisEnvOnly, false, q, p), 0.0f);
    EXPECT_NEAR(sc::misWeightOverPdf(sc::kMisBrdfOnly, false, q, p) * q, 1.0f, 1e-6f);
    EXPECT_EQ(sc::misWeightOverPdf(sc::kMisBrdfOnly, true, p, q), 0.0f);
  }
  // A strategy that could not have drawn the direction (p = 0) contributes nothing.
  EXPECT_EQ(sc::misWeightOverPdf(sc::kMisPower, true, 0.0f, 3.0f), 0.0f);
  EXPECT_EQ(sc::misWeightOverPdf(sc::kMisBalance, false, 0.0f, 3.0f), 0.0f);
}

TEST(EnvMis, DiffuseProbability) {
  EXPECT_EQ(sc::misDiffuseProbability(sc::Float3(0.5f, 0.5f, 0.5f), sc::Float3(0.0f, 0.0f, 0.0f)), 1.0f);
  EXPECT_EQ(sc::misDiffuseProbability(sc::Float3(0.0f, 0.0f, 0.0f), sc::Float3(0.5f, 0.5f, 0.5f)), 0.0f);
  EXPECT_EQ(sc::misDiffuseProbability(sc::Float3(0.0f, 0.0f, 0.0f), sc::Float3(0.0f, 0.0f, 0.0f)), 0.5f);
  EXPECT_NEAR(sc::misDiffuseProbability(sc::Float3(0.2f, 0.2f, 0.2f), sc::Float3(0.6f, 0.6f, 0.6f)), 0.25f, 1e-6f);
}

TEST(EnvMis, BrdfMixtureSamplerMatchesItsPdf) {
  // E[g / p_b] over samples of p_b = integral of g where p_b > 0: with g = cos / pi, 1. (With a diffuse
  // share pd > 0, g / p_b <= 1 / pd: a low-variance check. The glossy lobes alone are checked by
  // brdf_test's chi-square tests.)
  const sc::Float3 wo(0.3f, 0.1f, 0.948683f);
  const sc::BrdfParams brdfs[] = {sc::brdfParams(sc::kBrdfWard, 1.0f, 0.15f, 0.3f),
                                  sc::brdfParams(sc::kBrdfGgx, 1.0f, 0.3f, 0.3f),
                                  sc::brdfParams(sc::kBrdfPhong, 50.0f, 0.0f, 0.0f)};
  for (const auto& b : brdfs)
    for (float pd : {0.3f, 1.0f}) {
      double sum = 0;
      const int n = 200000;
      for (int i = 0; i < n; ++i) {
        const sc::Float4 u = sc::philoxUniform4(sc::philox4x32(sc::Philox4{uint32_t(i), 5u, 0u, 0u}, 1u, 2u));
        const sc::Float3 wi = sc::sampleMisBrdf(b, pd, wo, u);
        const float p = sc::misBrdfPdf(b, pd, wo, wi);
        if (p > 0 && wi.z > 0) sum += wi.z / kPi / p;
      }
      EXPECT_NEAR(sum / n, 1.0, 0.01) << b.kind << " pd " << pd;
      if (pd == 1.0f) {
        EXPECT_NEAR(sum / n, 1.0, 1e-3);  // cosine sampling: g / p = 1 exactly
      }
    }
}

emu::Texture smallEnv() {
  // 64 x 32, smooth sky-like gradient, a bright 2 x 2 sun and a dark band.
  const uint32_t W = 64, H = 32;
  std::vector<float> t(size_t(W) * H * 4, 1.0f);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      float* p = &t[4 * (size_t(y) * W + x)];
      const float v = 0.2f + 1.5f * float(H - y) / H + 0.5f * std::sin(float(x) * 0.3f);
      p[0] = v, p[1] = v * 0.9f, p[2] = v * 1.2f;
      if (y >= 20 && y < 23) p[0] = p[1] = p[2] = 0.0f;
      if ((x == 20 || x == 21) && (y == 9 || y == 10)) p[0] = p[1] = p[2] = 400.0f;
    }
  return emu::floatTexture(emu::Format::RGBA32F, W, H, t.data());
}

TEST(EnvMis, EstimatorIsUnbiased) {
  constexpr uint32_t kWrongAlpha = 99;
  const emu::Texture env = smallEnv();
  const auto& dev = emu::lavapipeProfile();
  const shadetwin::shade::Sampler2D envS = shadetwin::environmentSampler(env, dev, true);
  // A surface point facing the sun's side, viewed obliquely.
  const sc::Float4 g0(0.0f, 0.0f, 0.0f, 1.0f), g1(0.0f, 0.6f, 0.8f, 0.0f), g2(1.0f, 0.0f, 0.0f, 0.0f);
  const sc::Float3 eye(0.5f, 1.0f, 2.0f), diffuse(0.2f, 0.2f, 0.2f), specular(0.6f, 0.6f, 0.6f);
  struct Mat {
    const char* name;
    sc::BrdfParams b;
  };
  const Mat mats[] = {{"ward 0.15 x 0.3", sc::brdfParams(sc::kBrdfWard, 1.0f, 0.15f, 0.3f)},
                      {"ggx 0.3", sc::brdfParams(sc::kBrdfGgx, 1.0f, 0.3f, 0.3f)}};
  for (const Mat& m : mats) {
    const sc::FisFrame F = sc::envFrame(g0, g1, g2, eye);
    // Quadrature of the integrand (the same misIntegrand) on a grid 8x finer than the texels.
    double ref = 0;
    const uint32_t QW = 512, QH = 256;
    for (uint32_t y = 0; y < QH; ++y)
      for (uint32_t x = 0; x < QW; ++x) {
        const double u = (x + 0.5) / QW, v = (y + 0.5) / QH, phi = (u - 0.5) * 2 * kPi, th = v * kPi;
        const sc::Float3 d(float(std::sin(th) * std::sin(phi)), float(std::cos(th)),
                           float(-std::sin(th) * std::cos(phi)));
        const sc::Float3 c = sc::misIntegrand(envS, F, m.b, diffuse, specular, d, sc::basisToLocal(F.basis, d));
        ref += double(c.y) * 2 * kPi * kPi * std::sin(th) / (double(QW) * QH);
      }
    for (uint32_t method : {sc::kEnvKdTree, sc::kEnvAlias, sc::kEnvInversion, kWrongAlpha}) {
      const auto T = shadetwin::envSamplingTables(env, method == kWrongAlpha ? sc::kEnvKdTree : method, 64);
      const auto table = shadetwin::environmentSampler(*T.table, dev, false),
                 texels = shadetwin::environmentSampler(*T.texels, dev, false);
      const auto& U = T.uniforms;
      auto es = shadetwin::toEnvSampling<sc::EnvSampling>(U);
      if (method == kWrongAlpha)  // negative control: sampling with another alpha than the pdf's
        es.alpha *= 0.05f, es.log2Span = float(std::log2(1.0 + U.count / double(es.alpha)));
      const shadetwin::shade::V4<float> z4(0.0f, 0.0f, 0.0f, 0.0f);
      const sc::Sh16 noVis{z4, z4, z4, z4};
      for (uint32_t h : {sc::kMisBalance, sc::kMisPower}) {
        const int frames = 3000;
        double s = 0, s2 = 0;
        for (int f = 0; f < frames; ++f) {
          const sc::MisSettings ms{h, 4u, uint32_t(f), 7u};
          const float c =
              sc::shadeEnvMis(envS, table, texels, es, ms, 1.0f, 123u, g0, g1, g2, eye, eye, diffuse, specular, m.b,
                              sc::kFisVisNone, noVis).y;
          s += c, s2 += double(c) * c;
        }
        const double mean = s / frames, sd = std::sqrt(std::max(0.0, s2 / frames - mean * mean) / frames);
        if (method == kWrongAlpha) {
          EXPECT_GT(std::fabs(mean - ref), 4 * sd + 0.005 * ref) << m.name << " heuristic " << h;  // the test has power
          continue;
        }
        EXPECT_NEAR(mean, ref, 4 * sd + 0.005 * ref)
            << m.name << " method " << method << " heuristic " << h << " sd " << sd;
        EXPECT_LT(sd, 0.02 * ref) << m.name << " method " << method;  // and it is informative
      }
    }
  }
}

}  // namespace

TEST(EnvMis, VisibilityWeightsBothStrategies) {
  // SH visibility (issue 16) in the MIS estimator: a fit that is 1 everywhere (the V fit's prior,
  // sqrt(4 pi) Y00) reproduces the unshadowed estimate bit for bit; a fit of 0 makes every sample's
  // contribution 0; the V max(0, n.w) fit at its prior (the clamped cosine's SH at n) is V = 1 too.
  const emu::Texture env = smallEnv();
  const auto& dev = emu::lavapipeProfile();
  const auto envS = shadetwin::environmentSampler(env, dev, true);
  const auto T = shadetwin::envSamplingTables(env, sc::kEnvInversion, 64);
  const auto table = shadetwin::environmentSampler(*T.table, dev, false), texels = shadetwin::environmentSampler(*T.texels, dev, false);
  const auto es = shadetwin::toEnvSampling<sc::EnvSampling>(T.uniforms);
  const sc::Float4 g0(0.0f, 0.0f, 0.0f, 1.0f), g1(0.0f, 0.6f, 0.8f, 0.0f), g2(1.0f, 0.0f, 0.0f, 0.0f);
  const sc::Float3 eye(0.5f, 1.0f, 2.0f), diffuse(0.2f, 0.2f, 0.2f), specular(0.6f, 0.6f, 0.6f);
  const sc::BrdfParams b = sc::brdfParams(sc::kBrdfGgx, 1.0f, 0.3f, 0.3f);
  const sc::MisSettings ms{sc::kMisPower, 8u, 0u, 3u};
  const shadetwin::shade::V4<float> z4(0.0f, 0.0f, 0.0f, 0.0f);
  const sc::Sh16 zero{z4, z4, z4, z4}, one{shadetwin::shade::V4<float>(3.54490781f, 0.0f, 0.0f, 0.0f), z4, z4, z4};
  auto shade = [&](uint32_t mode, sc::Sh16 v) {
    return sc::shadeEnvMis(envS, table, texels, es, ms, 1.0f, 77u, g0, g1, g2, eye, eye, diffuse, specular, b, mode, v);
  };
  const sc::Float4 plain = shade(sc::kFisVisNone, zero), open = shade(sc::kFisVisV, one), dark = shade(sc::kFisVisV, zero);
  EXPECT_GT(plain.y, 0.0f);
  EXPECT_EQ(0, std::memcmp(&plain, &open, sizeof plain));
  EXPECT_EQ(dark.x, 0.0f);
  EXPECT_EQ(dark.y, 0.0f);
  // The V max(0, n.w) fit at its prior t(n): V = 1 up to the prior's band-3-free form (within 1%).
  const sc::VisSettings vs{1u, 16u, sc::kVisFitVCos, 0.0f, 0.0f};
  const sc::Sh16 t = sc::visPrior(vs, sc::exNormalize(sc::Float3(g1.x, g1.y, g1.z)));
  const sc::Float4 prior = shade(sc::kFisVisCos, t);
  EXPECT_NEAR(prior.y, plain.y, 0.01f * plain.y);
}
