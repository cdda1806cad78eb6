// Order-3 SH irradiance (shade/sh_irradiance.h, inputs/sh_irradiance.cpp): the projection against
// a double-precision sum of the same texels, a constant environment (E/pi = L), the SH
// approximation against brute-force irradiance on the real maps (Ramamoorthi & Hanrahan's error
// claim), thread-count independence, odd sizes, and the fis pass's diffuse term.
// Emulator-vs-GPU bits: ctest verify_sh_*.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>
#include <vector>

#include <tbb/global_control.h>

#include "emu/device_profile.h"
#include "passes/mips.h"
#include "passes/gbuffer.h"
#include "inputs/environment.h"
#include "inputs/sh_irradiance.h"
#include "inputs/visibility.h"
#include "scene/scene.h"

namespace {
using shadetwin::ShIrradiance;
const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }

struct EnvD {
  uint32_t w, h;
  std::vector<float> texels;  // RGBA level 0
};

emu::Texture textureOf(const std::vector<float>& level0, uint32_t w, uint32_t h) {
  return shadetwin::packTexture(emu::Format::RGBA32F, w, h, 1, shadetwin::mipChainCpu(level0, w, h, 1, 8));
}

// Direction and solid angle of texel (x, y), in double (the definitions of the header).
void texelDir(uint32_t x, uint32_t y, uint32_t w, uint32_t h, double d[3], double& dw) {
  const double pi = std::numbers::pi;
  const double th = pi * (y + 0.5) / h, u = (x + 0.5) / w;
  d[0] = -std::sin(th) * std::sin(2 * pi * u);
  d[1] = std::cos(th);
  d[2] = std::sin(th) * std::cos(2 * pi * u);
  dw = 2 * pi / w * (std::cos(pi * y / h) - std::cos(pi * (y + 1) / h));
}

void basis(const double d[3], double Y[9]) {
  const double x = d[0], y = d[1], z = d[2];
  Y[0] = 0.282094792;
  Y[1] = 0.488602512 * y, Y[2] = 0.488602512 * z, Y[3] = 0.488602512 * x;
  Y[4] = 1.092548431 * x * y, Y[5] = 1.092548431 * y * z, Y[6] = 0.315391565 * (3 * z * z - 1);
  Y[7] = 1.092548431 * x * z, Y[8] = 0.546274215 * (x * x - y * y);
}

// E/pi coefficients in double.
std::vector<double> projectDouble(const EnvD& e) {
  std::vector<double> c(27, 0.0);
  for (uint32_t y = 0; y < e.h; ++y)
    for (uint32_t x = 0; x < e.w; ++x) {
      double d[3], dw, Y[9];
      texelDir(x, y, e.w, e.h, d, dw);
      basis(d, Y);
      const float* t = &e.texels[4 * (size_t(y) * e.w + x)];
      for (int k = 0; k < 9; ++k)
        for (int ch = 0; ch < 3; ++ch) c[3 * k + ch] += t[ch] * Y[k] * dw;
    }
  for (int k = 0; k < 9; ++k)
    for (int ch = 0; ch < 3; ++ch) c[3 * k + ch] *= (k == 0 ? 1.0 : k < 4 ? 2.0 / 3.0 : 0.25);
  return c;
}

// Brute-force E(n)/pi = (1/pi) sum L max(n.w, 0) dw (green channel).
double irradianceBrute(const EnvD& e, const double n[3]) {
  double s = 0;
  for (uint32_t y = 0; y < e.h; ++y)
    for (uint32_t x = 0; x < e.w; ++x) {
      double d[3], dw;
      texelDir(x, y, e.w, e.h, d, dw);
      const double c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
      if (c > 0) s += e.texels[4 * (size_t(y) * e.w + x) + 1] * c * dw;
    }
  return s / std::numbers::pi;
}

EnvD loadEnv(const char* scene) {
  const shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/" + scene);
  std::ostringstream log;
  shadetwin::EnvironmentMap m = shadetwin::loadEnvironment(s.environment, log);
  return {m.width, m.height, m.levels[0]};
}
}  // namespace

TEST(ShIrradiance, ConstantEnvironmentGivesItsRadiance) {
  // E = pi L for a constant L, so E/pi = L at every normal; bands 1 and 2 vanish, up to the texel-centre
  // (midpoint) quadrature of the band-2 polynomials in theta, an O(1/H^2) error (measured: 7e-4 L for
  // H = 32), so the bounds are 1/H^2 plus float rounding.
  for (uint32_t h : {32u, 37u, 512u}) {
    const uint32_t w = 2 * h;
    std::vector<float> t(size_t(w) * h * 4);
    for (size_t i = 0; i < t.size(); i += 4) t[i] = 0.5f, t[i + 1] = 2.0f, t[i + 2] = 7.0f, t[i + 3] = 1.0f;
    const ShIrradiance sh = shadetwin::shIrradianceEmu(textureOf(t, w, h), dev());
    const double q = 1.0 / (double(h) * h) + 1e-5;
    for (int k = 1; k < 9; ++k) EXPECT_NEAR(sh.c[3 * k + 2], 0.0, 7.0 * q) << "h " << h << " k " << k;
    for (const std::array<float, 3> n : {std::array<float, 3>{0, 1, 0}, {0, -1, 0}, {0.6f, 0, 0.8f}, {-0.48f, 0.6f, -0.64f}}) {
      const auto e = shadetwin::shIrradianceAt(sh, n);
      EXPECT_NEAR(e[0], 0.5, 0.5 * q) << "h " << h;
      EXPECT_NEAR(e[1], 2.0, 2.0 * q) << "h " << h;
      EXPECT_NEAR(e[2], 7.0, 7.0 * q) << "h " << h;
    }
  }
}

TEST(ShIrradiance, ProjectionMatchesDoublePrecision) {
  // Float rows summed left to right, then the pairwise tree: within 1e-5 of the double sum
  // (relative to the DC term), on every map the tests use, the city sun included.
  for (const char* scene : {"bunny.json", "spheres.json", "teapot.json", "materials.json"}) {
    const EnvD e = loadEnv(scene);
    const ShIrradiance sh = shadetwin::shIrradianceEmu(textureOf(e.texels, e.w, e.h), dev());
    const std::vector<double> ref = projectDouble(e);
    for (int i = 0; i < 27; ++i) EXPECT_NEAR(sh.c[i], ref[i], 1e-5 * std::fabs(ref[i % 3])) << scene << " coefficient " << i;
  }
}

TEST(ShIrradiance, Band3RadianceMatchesDoublePrecision) {
  // Band 3 (raw radiance, the lighting of SH visibility's diffuse product) against the double sum with
  // inputs/visibility.h's double basis; and 0 for a constant environment (up to the midpoint rule).
  for (const char* scene : {"bunny.json", "materials.json"}) {
    const EnvD e = loadEnv(scene);
    const ShIrradiance sh = shadetwin::shIrradianceEmu(textureOf(e.texels, e.w, e.h), dev());
    std::vector<double> ref(21, 0.0);
    for (uint32_t y = 0; y < e.h; ++y)
      for (uint32_t x = 0; x < e.w; ++x) {
        double d[3], dw;
        texelDir(x, y, e.w, e.h, d, dw);
        const auto Y = shadetwin::sh16BasisDouble({float(d[0]), float(d[1]), float(d[2])});
        const float* t = &e.texels[4 * (size_t(y) * e.w + x)];
        for (int k = 9; k < 16; ++k)
          for (int ch = 0; ch < 3; ++ch) ref[size_t(3 * (k - 9) + ch)] += t[ch] * Y[size_t(k)] * dw;
      }
    const std::vector<double> low = projectDouble(e);
    for (int i = 0; i < 21; ++i) EXPECT_NEAR(sh.band3[size_t(i)], ref[size_t(i)], 2e-5 * std::fabs(low[size_t(i % 3)])) << scene << " " << i;
  }
  const uint32_t w = 128, h = 64;
  std::vector<float> t(size_t(w) * h * 4, 1.0f);
  const ShIrradiance c = shadetwin::shIrradianceEmu(textureOf(t, w, h), dev());
  for (float x : c.band3) EXPECT_NEAR(x, 0.0f, 1e-3f);
}

TEST(ShIrradiance, ApproximatesBruteForceIrradiance) {
  // Ramamoorthi & Hanrahan: order 3 keeps the irradiance within a few percent of its mean for
  // natural lighting (the clamped-cosine kernel's bands l > 2 carry little energy). Measured on 26
  // normals, error relative to the mean E: forest worst 7.0% (mean 3.0%), courtyard 8.6% (3.5%),
  // city (sun > 30,000) 7.7% (2.8%), studio 21% (6.2%: its sharp light panels put energy in
  // higher bands). Bounds: the measured values with a margin; E stays finite and >= 0.
  const double pi = std::numbers::pi;
  struct Case {
    const char* scene;
    double worst, mean;
  };
  for (const Case c : {Case{"bunny.json", 0.09, 0.04}, Case{"teapot.json", 0.25, 0.075}, Case{"spheres.json", 0.11, 0.045},
                       Case{"materials.json", 0.10, 0.04}}) {
    const EnvD e = loadEnv(c.scene);
    const ShIrradiance sh = shadetwin::shIrradianceEmu(textureOf(e.texels, e.w, e.h), dev());
    double worst = 0, mean = 0;
    int count = 0;
    for (int i = 0; i < 26; ++i) {  // directions spread over the sphere (spherical Fibonacci)
      const double z = 1 - (2 * i + 1) / 26.0, r = std::sqrt(1 - z * z), phi = i * pi * (3 - std::sqrt(5.0));
      const double n[3] = {r * std::cos(phi), z, r * std::sin(phi)};
      const double brute = irradianceBrute(e, n);
      const auto s = shadetwin::shIrradianceAt(sh, {float(n[0]), float(n[1]), float(n[2])});
      ASSERT_TRUE(std::isfinite(s[1]) && s[1] >= 0) << c.scene;
      // Relative to the mean irradiance (dark directions would make a relative error meaningless).
      const double err = std::fabs(s[1] - brute) / (sh.c[1] * 0.282094792);
      worst = std::max(worst, err), mean += err, ++count;
    }
    std::cout << c.scene << ": SH irradiance error, relative to the mean: worst " << worst << ", mean " << mean / count << "\n";
    EXPECT_LT(worst, c.worst) << c.scene;
    EXPECT_LT(mean / count, c.mean) << c.scene;
  }
}

TEST(ShIrradiance, IndependentOfThreadCountAndRowGrouping) {
  const EnvD e = loadEnv("materials.json");
  const emu::Texture tex = textureOf(e.texels, e.w, e.h);
  ShIrradiance ref;
  for (int threads : {1, 2, 16}) {
    tbb::global_control g(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const ShIrradiance sh = shadetwin::shIrradianceEmu(tex, dev());
    if (threads == 1) ref = sh;
    else EXPECT_EQ(0, std::memcmp(ref.c.data(), sh.c.data(), sizeof ref.c)) << threads << " threads";
  }
  EXPECT_THROW(shadetwin::shIrradianceEmu(shadetwin::packTexture(emu::Format::RGBA16F, 4, 2, 1, shadetwin::mipChainCpu(
                                                                       std::vector<float>(32, 1.0f), 4, 2, 1, 8)),
                                           dev()),
               std::invalid_argument);
}
