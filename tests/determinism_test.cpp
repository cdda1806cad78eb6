// Determinism (issue 20, item 5): every technique's frame on the emulator (G-buffer, shadow maps and SH visibility where
// the scene has them, technique inputs, shading) is byte-identical across repeated runs and TBB thread counts 1, 2, 16.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstring>
#include <memory>
#include <sstream>

#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "passes/gbuffer.h"
#include "passes/shade.h"
#include "passes/visibility.h"
#include "scene/scene.h"

namespace {

std::vector<float> frame(const shadetwin::Scene& s, const shadetwin::EnvironmentMap& env) {
  const emu::DeviceProfile& dev = emu::lavapipeProfile();
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev);
  const shadetwin::ShadeInputs in = shadetwin::shadeInputsEmu(s, *env.texture, dev);
  std::unique_ptr<shadetwin::VisibilityImage> vis;
  if (in.visibility) vis = std::make_unique<shadetwin::VisibilityImage>(shadetwin::visibilityEmu(s, g, *in.visibility, dev));
  std::vector<float> img;
  shadetwin::shadeEmu(s, g, in, dev, img, vis.get());
  img.insert(img.end(), g.texels.begin(), g.texels.end());  // the G-buffer's bits too
  return img;
}

struct Case {
  const char* scene;
  const char* technique;
};

class Determinism : public testing::TestWithParam<Case> {};

TEST_P(Determinism, FramesAreByteIdenticalAcrossRunsAndThreadCounts) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/" + GetParam().scene);
  shadetwin::setTechnique(s, GetParam().technique);
  s.width = 40, s.height = 24;
  if (s.visMaps) s.visMaps = 4, s.visSize = 64;
  if (s.technique == "glints") s.glintViewRings = 5, s.glintViewSectors = 8;  // a small lighting table
  std::ostringstream log;
  const shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  std::vector<float> ref;
  for (int threads : {1, 2, 16, 16}) {  // 16 twice: a repeated run
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const std::vector<float> img = frame(s, env);
    if (ref.empty()) {
      ref = img;
      double sum = 0;
      for (size_t i = 0; i < size_t(s.width) * s.height * 4; ++i) sum += img[i];
      EXPECT_GT(sum, 0.0);  // not black
      continue;
    }
    ASSERT_EQ(img.size(), ref.size());
    size_t differing = 0;
    for (size_t i = 0; i < img.size(); ++i) differing += std::memcmp(&img[i], &ref[i], 4) != 0;
    EXPECT_EQ(differing, 0u) << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, Determinism,
                         testing::Values(Case{"bunny.json", "fis"}, Case{"bunny.json", "unfiltered"},
                                         Case{"bunny.json", "stochastic"}, Case{"spheres.json", "env"},
                                         Case{"spheres.json", "mirror"}, Case{"ward_spheres.json", "kdtree-mis"},
                                         Case{"ward_spheres.json", "alias-mis"}, Case{"ward_spheres.json", "inversion-mis"},
                                         Case{"textured.json", "fis"}, Case{"contact.json", "fis"},
                                         Case{"glints.json", "glints"}),
                         [](const testing::TestParamInfo<Case>& i) {
                           std::string n = std::string(i.param.scene) + "_" + i.param.technique;
                           for (char& c : n)
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
