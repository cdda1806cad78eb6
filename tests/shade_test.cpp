// The emulated deferred shading pass (src/passes/shade_emu.cpp shadeEmu): thread-count independence,
// background pixels equal the environment along the camera ray, a mirror sphere reflects the
// environment. Emulator vs lavapipe is the ctest `verify_shade_*` / `verify_frame_*`.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <sstream>

#include "emu/sampler.h"
#include "util/image_io.h"
#include "passes/shade.h"
#include "inputs/material.h"
#include "passes/mips.h"
#include "inputs/paraboloid.h"
#include "lanes/instantiate.h"
#include "inputs/environment.h"
#include "scene/scene.h"

namespace {

const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }

TEST(ShadingPass, ThreadCountIndependent) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/spheres.json");
  s.width = 256, s.height = 96;
  s.technique = "mirror";
  std::ostringstream log;
  shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev());
  std::vector<float> ref;
  for (int threads : {1, 2, 16}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(threads));
    std::vector<float> img = shadetwin::shadeEmu(s, g, shadetwin::shadeInputsEmu(s, *env.texture, dev()), dev());
    if (ref.empty()) {
      ref = img;
      double sum = 0;
      for (float v : img) sum += v;
      EXPECT_GT(sum, 1000.0);  // not black
    } else {
      ASSERT_EQ(0, std::memcmp(ref.data(), img.data(), ref.size() * 4)) << threads << " threads";
    }
  }
}

TEST(ShadingPass, BackgroundIsTheEnvironmentAlongTheRay) {
  // Empty scene: every pixel shows the environment at MIP level 0 along its camera ray.
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/bunny.json");
  s.objects.clear();
  s.width = 64, s.height = 48;
  s.technique = "mirror";
  std::ostringstream log;
  shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev());
  std::vector<float> img = shadetwin::shadeEmu(s, g, shadetwin::shadeInputsEmu(s, *env.texture, dev()), dev());
  const shadetwin::CameraRays cam = shadetwin::cameraRays(s);
  emu::SamplerDesc sd;
  sd.addressU = emu::AddressMode::Repeat;
  int close = 0;
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x) {
      const double nx = (x + 0.5) / s.width * 2 - 1, ny = (y + 0.5) / s.height * 2 - 1;
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = cam.fwd[k] + cam.right[k] * nx + cam.down[k] * ny;
      const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double u = std::atan2(d[0] / l, -d[2] / l) / (2 * std::acos(-1.0)) + 0.5, v = std::acos(d[1] / l) / std::acos(-1.0);
      emu::Texel4 t = emu::textureLod(*env.texture, sd, dev(), float(u), float(v), 0.0f, 0.0f);
      const float* p = &img[4 * (size_t(y) * s.width + x)];
      const double ref = s.environmentIntensity * t.g;
      if (std::fabs(p[1] - ref) <= 1e-3 * std::fabs(ref) + 1e-5) ++close;
    }
  // Double-precision rays land on the same texels except within float rounding of texel edges.
  EXPECT_GT(close, int(0.97 * s.width * s.height));
}

}  // namespace
