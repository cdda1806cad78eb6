// The directional lights of technique "env" (inputs/env_lights.cpp): weights of a constant
// environment, a single bright texel, an empty environment; and the env shading pass under a
// constant environment (diffuse only: kd L up to the lights' quadrature error).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "emu/device_profile.h"
#include "passes/mips.h"
#include "inputs/env_lights.h"
#include "passes/shade.h"
#include "scene/scene.h"
#include "lanes/instantiate.h"

namespace {
emu::Texture envOf(const std::vector<float>& level0, uint32_t w, uint32_t h) {
  return shadetwin::packTexture(emu::Format::RGBA32F, w, h, 1, shadetwin::mipChainCpu(level0, w, h, 1, 8));
}
}  // namespace

TEST(EnvLights, ConstantEnvironmentGivesEqualWeights) {
  // pdf proportional to sin(theta) = uniform on the sphere: p = 1/(4 pi) up to the texel-centre sine
  // sum, so each weight is 4 pi L / N; directions are unit vectors.
  const uint32_t W = 256, H = 128, N = 64;
  std::vector<float> t(size_t(W) * H * 4, 2.0f);
  const shadetwin::EnvLights L = shadetwin::envLights(envOf(t, W, H), N);
  ASSERT_EQ(L.count, N);
  ASSERT_EQ(L.data.size(), size_t(N) * 8);
  for (uint32_t j = 0; j < N; ++j) {
    const float* d = &L.data[8 * j];
    EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-6);
    EXPECT_NEAR(d[5], 4 * std::numbers::pi * 2.0 / N, 1e-4 * 4 * std::numbers::pi * 2.0 / N) << j;
  }
  // Stratified in the marginal: the mean of y = cos(theta) is near 0.
  double my = 0;
  for (uint32_t j = 0; j < N; ++j) my += L.data[8 * j + 1];
  EXPECT_NEAR(my / N, 0.0, 0.02);
}

TEST(EnvLights, SingleBrightTexelTakesEveryLight) {
  const uint32_t W = 64, H = 32;
  std::vector<float> t(size_t(W) * H * 4, 0.0f);
  for (size_t i = 0; i < t.size(); i += 4) t[i] = -0.01f;  // negative texels never carry a light
  float* sun = &t[4 * (size_t(9) * W + 40)];
  sun[0] = sun[1] = sun[2] = 30000.0f;
  const shadetwin::EnvLights L = shadetwin::envLights(envOf(t, W, H), 16);
  const double pi = std::numbers::pi, theta = pi * 9.5 / H, u = 40.5 / W;
  const double omega = 2 * pi / W * (std::cos(pi * 9 / H) - std::cos(pi * 10 / H));  // the texel's solid angle
  for (uint32_t j = 0; j < 16; ++j) {
    const float* d = &L.data[8 * j];
    EXPECT_NEAR(d[0], -std::sin(theta) * std::sin(2 * pi * u), 1e-6);
    EXPECT_NEAR(d[1], std::cos(theta), 1e-6);
    // weight = L / (N p), p = 1 / (texel solid angle, sine at the centre): the sum over N lights is L omega.
    EXPECT_NEAR(d[5] * 16, 30000.0 * omega, 30000.0 * omega * 2e-3);
  }
  std::vector<float> dark(size_t(W) * H * 4, -1.0f);
  EXPECT_EQ(shadetwin::envLights(envOf(dark, W, H), 16).count, 0u);
}

TEST(EnvPass, DiffuseUnderConstantEnvironmentApproachesKdTimesL) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/materials.json");
  s.width = 96, s.height = 40;
  s.technique = "env";
  s.fisSamples = 1024;
  for (shadetwin::Material& m : s.materials) m.specular = {0, 0, 0};
  const uint32_t W = 256, H = 128;
  const emu::Texture env = envOf(std::vector<float>(size_t(W) * H * 4, 1.5f), W, H);
  const emu::DeviceProfile& dev = emu::lavapipeProfile();
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev);
  const std::vector<float> img = shadetwin::shadeEmu(s, g, shadetwin::shadeInputsEmu(s, env, dev), dev);
  double worst = 0;
  int geometry = 0;
  for (size_t p = 0; p < size_t(s.width) * s.height; ++p) {
    const float* t = &g.texels[p * shadetwin::kGbufFloats];
    if (t[3] == 0.0f) continue;
    ++geometry;
    const shadetwin::Material& m = s.materials[shadetwin::shade::scalar::materialSlot(t[3], uint32_t(s.materials.size()))];
    const double want = m.diffuse[1] * 1.5 * s.environmentIntensity;
    worst = std::max(worst, std::fabs(img[4 * p + 1] - want) / want);
  }
  EXPECT_GT(geometry, 500);
  EXPECT_LT(worst, 0.005);  // measured 9e-4: 1024 stratified lights estimate the cosine integral closely
  std::cout << "worst relative error of kd L with 1024 lights: " << worst << "\n";
}
