// Technique inputs across frames (inputs/shade_inputs.h ShadeInputsCache): rebuilt when the
// environment changes, reused when it does not, and a rebuild equals a fresh build; the environment
// turn of `render --env-rotate` (cli/render.h) moves whole texel columns.
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "scene/scene.h"

namespace {
const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }

bool sameTexture(const emu::Texture& a, const emu::Texture& b) {
  if (a.levelCount() != b.levelCount()) return false;
  for (uint32_t l = 0; l < a.levelCount(); ++l)
    if (a.levels()[l] != b.levels()[l]) return false;
  return true;
}

TEST(EnvironmentTurn, MovesWholeColumns) {
  EXPECT_EQ(shadetwin::environmentShift(1024, 90), 256u);
  EXPECT_EQ(shadetwin::environmentShift(1024, -90), 768u);
  EXPECT_EQ(shadetwin::environmentShift(1024, 360), 0u);
  EXPECT_EQ(shadetwin::environmentShift(1024, 0.1), 0u);   // 0.28 columns: rounds to none
  EXPECT_EQ(shadetwin::environmentShift(1024, 450), 256u);
  // One bright texel at column 100 of a 64-row map: a 90 degree turn moves it to column 100 - 256 (mod 1024).
  const uint32_t W = 1024, H = 64;
  std::vector<float> t(size_t(W) * H * 4, 0.0f);
  for (int k = 0; k < 4; ++k) t[4 * (size_t(10) * W + 100) + size_t(k)] = 5.0f;
  const shadetwin::EnvironmentMap e = shadetwin::environmentFromLevel0(t, W, H);
  const shadetwin::EnvironmentMap r = shadetwin::rotateEnvironment(e, 90);
  const std::vector<float>& l0 = r.levels[0];
  EXPECT_EQ(l0[4 * (size_t(10) * W + 868)], 5.0f);
  double sum = 0;
  for (size_t i = 0; i < l0.size(); i += 4) sum += l0[i];
  EXPECT_EQ(sum, 5.0);
  EXPECT_EQ(r.texture->levelCount(), e.texture->levelCount());
}

TEST(ShadeInputsCache, RebuildsOnlyWhenTheEnvironmentChanges) {
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/materials.json");
  s.fisFaceSize = 64;
  std::ostringstream log;
  const shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  shadetwin::ShadeInputsCache cache;
  const shadetwin::ShadeInputs& a = cache.emu(s, *env.texture, dev());
  EXPECT_TRUE(cache.lastRebuilt());
  const auto atlas0 = a.atlas;
  // The same texels in a new texture object (a frame whose environment did not change): reused.
  const shadetwin::EnvironmentMap same = shadetwin::rotateEnvironment(env, 360);
  const shadetwin::ShadeInputs& b = cache.emu(s, *same.texture, dev());
  EXPECT_FALSE(cache.lastRebuilt());
  EXPECT_EQ(b.atlas, atlas0);
  EXPECT_EQ(b.environment, same.texture.get());
  EXPECT_EQ(cache.builds(), 1u);
  // Turned: rebuilt, and equal to a fresh build for that environment (atlas bits and SH).
  const shadetwin::EnvironmentMap turned = shadetwin::rotateEnvironment(env, 45);
  const shadetwin::ShadeInputs& c = cache.emu(s, *turned.texture, dev());
  EXPECT_TRUE(cache.lastRebuilt());
  EXPECT_EQ(cache.builds(), 2u);
  const shadetwin::ShadeInputs fresh = shadetwin::shadeInputsEmu(s, *turned.texture, dev());
  EXPECT_TRUE(sameTexture(*c.atlas, *fresh.atlas));
  EXPECT_FALSE(sameTexture(*c.atlas, *atlas0));
  EXPECT_EQ(0, std::memcmp(c.sh.c.data(), fresh.sh.c.data(), sizeof(float) * 27));
  // A setting that shapes the inputs (face size) also rebuilds.
  s.fisFaceSize = 32;
  cache.emu(s, *turned.texture, dev());
  EXPECT_TRUE(cache.lastRebuilt());
  EXPECT_EQ(cache.emu(s, *turned.texture, dev()).atlas->width(), 64u);  // 2S x S
  EXPECT_EQ(cache.builds(), 3u);
}
}  // namespace
