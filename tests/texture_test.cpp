// Emulated texture unit: format decoding, texture validation, sampler model spot checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "emu/device_profile.h"
#include "emu/format.h"
#include "emu/sampler.h"
#include "emu/texture.h"

namespace {
std::vector<uint8_t> floats(std::initializer_list<float> v) {
  std::vector<uint8_t> b(v.size() * 4);
  std::memcpy(b.data(), v.begin(), b.size());
  return b;
}
}  // namespace

TEST(Format, HalfRoundTripsExhaustively) {
  for (uint32_t h = 0; h < 65536; ++h) {
    float f = emu::halfToFloat(uint16_t(h));
    if (std::isnan(f)) continue;
    ASSERT_EQ(emu::floatToHalf(f), h) << std::hex << h;
  }
  EXPECT_EQ(emu::halfToFloat(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(emu::halfToFloat(0x7bff), 65504.0f);
}

TEST(Format, UnknownFormatNamesTheValue) {
  try {
    emu::parseFormat("rgb565");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rgb565"), std::string::npos);
  }
  EXPECT_EQ(emu::parseFormat("RGBA16F"), emu::Format::RGBA16F);
}

TEST(Texture, RejectsBadShapesWithClearErrors) {
  EXPECT_THROW(emu::Texture(emu::Format::R32F, 0, 4, 1, {{}}), std::invalid_argument);
  EXPECT_THROW(emu::Texture(emu::Format::R32F, 4, 4, 1, {}), std::invalid_argument);
  std::vector<std::vector<uint8_t>> tooMany(4, std::vector<uint8_t>(4));
  EXPECT_THROW(emu::Texture(emu::Format::R32F, 2, 2, 1, tooMany), std::invalid_argument);
  try {
    emu::Texture(emu::Format::RGBA8_UNORM, 4, 4, 1, {std::vector<uint8_t>(64), std::vector<uint8_t>(15)});
    FAIL();
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("level 1 has 15 bytes, expected 16"), std::string::npos) << m;
  }
}

TEST(Sampler, BilinearAtTexelCentresReturnsTexels) {
  emu::Texture t(emu::Format::R32F, 2, 1, 1, {floats({1.0f, 3.0f})});
  emu::SamplerDesc s;
  s.minFilter = s.magFilter = emu::Filter::Linear;
  const auto& lp = emu::lavapipeProfile();
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.25f, 0.5f, 0, 0).r, 1.0f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.75f, 0.5f, 0, 0).r, 3.0f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0).r, 2.0f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0).a, 1.0f);  // R32F alpha
  s.addressU = emu::AddressMode::Repeat;
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.0f, 0.5f, 0, 0).r, 2.0f);  // wraps between texel 1 and 0
}

TEST(Sampler, Unorm8FixedPointPathMatchesLavapipeFacts) {
  // 2x1 RGBA8 texture (0, 255); u = 0.3 -> s = rint(0.6 * 256) - 128 = 26, w = 26:
  // 0 + ((26 * 255 + 128) >> 8) = 26 -> 26 * (1/255f).
  std::vector<uint8_t> px = {0, 0, 0, 0, 255, 255, 255, 255};
  emu::Texture t(emu::Format::RGBA8_UNORM, 2, 1, 1, {px});
  emu::SamplerDesc s;
  emu::Texel4 r = emu::textureLod(t, s, emu::lavapipeProfile(), 0.3f, 0.5f, 0, 0);
  EXPECT_EQ(r.r, 26.0f * (1.0f / 255.0f));
  // The float path (nvidia profile, 8-bit weights) filters the same lookup differently.
  emu::Texel4 n = emu::textureLod(t, s, emu::nvidiaProfile(), 0.3f, 0.5f, 0, 0);
  EXPECT_NE(n.r, r.r);
}

TEST(Sampler, TrilinearBlendsLevelsWithFma) {
  emu::Texture t(emu::Format::R32F, 2, 2, 1, {floats({1, 1, 1, 1}), floats({3})});
  emu::SamplerDesc s;
  const auto& lp = emu::lavapipeProfile();
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0.25f).r, 1.5f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 5.0f).r, 3.0f);   // clamped to the last level
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, -3.0f).r, 1.0f);  // magnified
  s.lodBias = 0.5f;
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0.25f).r, 2.5f);
  s.maxLod = 0.5f;
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0.25f).r, 2.0f);
}

TEST(DeviceProfile, LookupAndUnknownNames) {
  EXPECT_TRUE(emu::profileByName("lavapipe").verified);
  EXPECT_FALSE(emu::profileByName("nvidia").verified);
  EXPECT_EQ(emu::profileForDevice("llvmpipe (LLVM 15.0.6, 256 bits)").name, "lavapipe");
  EXPECT_THROW(emu::profileByName("voodoo2"), std::invalid_argument);
  EXPECT_EQ(emu::lavapipeProfile().denorm(emu::Stage::Fragment), emu::DenormMode::Flush);
  EXPECT_EQ(emu::lavapipeProfile().denorm(emu::Stage::Compute), emu::DenormMode::Preserve);
}
