// MIP chain generation with the shared kernel: the polyphase box filter's values, non-finite
// isolation, shapes, errors, and host-side format packing.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "model/pass_counts.h"
#include "passes/mips.h"

using shadetwin::mipChainCpu;

namespace {
std::vector<float> rgbaRow(std::initializer_list<float> r) {
  std::vector<float> v;
  for (float x : r) v.insert(v.end(), {x, x, x, 1.0f});
  return v;
}
}  // namespace

TEST(Mips, EvenWidthIsPairAverage) {
  auto levels = mipChainCpu(rgbaRow({1, 3, 10, 20}), 4, 1, 1, 1);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_EQ(levels[1][0], 2.0f);
  EXPECT_EQ(levels[1][4], 15.0f);
  EXPECT_EQ(levels[2][0], 8.5f);
}

TEST(Mips, OddWidthIsExactAreaAverage) {
  // 5 -> 2: dst 0 = (2/5) s0 + (2/5) s1 + (1/5) s2, dst 1 = (1/5) s2 + (2/5) s3 + (2/5) s4
  auto levels = mipChainCpu(rgbaRow({5, 10, 20, 40, 80}), 5, 1, 1, 8);
  EXPECT_NEAR(levels[1][0], 0.4 * 5 + 0.4 * 10 + 0.2 * 20, 1e-5);
  EXPECT_NEAR(levels[1][4], 0.2 * 20 + 0.4 * 40 + 0.4 * 80, 1e-4);
  // the area average preserves the mean: (2.5 texels each)
  EXPECT_NEAR((levels[1][0] + levels[1][4]) / 2.0, (5 + 10 + 20 + 40 + 80) / 5.0, 1e-4);
  for (int w : {3, 7, 9, 101}) {  // a constant image stays constant to 1 ulp
    std::vector<float> c(size_t(w) * 4, 0.7f);
    auto l = mipChainCpu(c, uint32_t(w), 1, 1, 1);
    for (float v : l[1]) EXPECT_NEAR(v, v == 1.0f ? 1.0f : 0.7f, 1.2e-7f) << w;
  }
}

TEST(Mips, NonFiniteTexelsDoNotLeakAcrossEvenBlocks) {
  auto levels = mipChainCpu(rgbaRow({1, 1, INFINITY, 1}), 4, 1, 1, 8);
  EXPECT_EQ(levels[1][0], 1.0f);  // the weight-0 third tap is not read
  EXPECT_TRUE(std::isinf(levels[1][4]));
}

TEST(Mips, ChainShapesAndScalarSimdAgree) {
  std::vector<float> img(size_t(37) * 13 * 2 * 4);
  std::iota(img.begin(), img.end(), 0.0f);
  auto a = mipChainCpu(img, 37, 13, 2, 1), b = mipChainCpu(img, 37, 13, 2, 8);
  ASSERT_EQ(a.size(), 6u);  // 37x13, 18x6, 9x3, 4x1, 2x1, 1x1
  EXPECT_EQ(a[3].size(), size_t(4) * 1 * 2 * 4);
  EXPECT_EQ(a, b);
}

// The counted chain (the performance model's, lanes 0) does what every invocation of mip_downsample.glsl does: both
// axes' taps per 8-texel vector, none hoisted out of a row. A 256x2 source's first level is 16 vectors in one row, a
// 16x32 source's 16 vectors in 16 rows, and the rest of each chain is that of 128x2 and 8x16: the two first levels
// count the same. (With the row's taps hoisted out of the row, the one-row level counted 17 tap computations where
// the GPU runs 32: 51 of its 96 exact divisions; measured 10,686 ticks against 18,336.)
TEST(Mips, CountedChainComputesBothAxesTapsPerVectorAsTheShaderDoes) {
  auto ticks = [](uint32_t w, uint32_t h, bool divisions) {
    std::vector<float> img(size_t(w) * h * 4);
    std::iota(img.begin(), img.end(), 1.0f);
    const auto t = shadetwin::model::countedTicks([&] { mipChainCpu(img, w, h, 1, 0); });
    uint64_t alu = 0;
    for (int k = 0; k < opcount::kTexLookup; ++k) alu += t[size_t(k)];
    return divisions ? t[opcount::kExDiv] : alu;
  };
  const uint64_t oneRow = ticks(256, 2, false) - ticks(128, 2, false), sixteenRows = ticks(16, 32, false) - ticks(8, 16, false);
  // Two tap computations per vector, three exact divisions each: 96 for the level's 16 vectors.
  EXPECT_EQ(ticks(256, 2, true) - ticks(128, 2, true), 96u);
  EXPECT_EQ(ticks(16, 32, true) - ticks(8, 16, true), 96u);
  EXPECT_GT(oneRow, 16u * 100u);  // and the taps' other operations and four combines per vector
  EXPECT_EQ(oneRow, sixteenRows);
}

TEST(Mips, BadInputIsNamed) {
  EXPECT_THROW(mipChainCpu({}, 0, 4, 1), std::invalid_argument);
  try {
    mipChainCpu(std::vector<float>(10), 2, 2, 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected 16"), std::string::npos) << e.what();
  }
}

TEST(Mips, PackingToFormatsIsDefined) {
  std::vector<std::vector<float>> lv = {{0.5f, -1.0f, 2.0f, NAN}};
  auto t8 = shadetwin::packTexture(emu::Format::RGBA8_UNORM, 1, 1, 1, lv);
  auto b = t8.loadBytes(0, 0, 0, 0);
  EXPECT_EQ(b[0], 128);  // rint(127.5) = 128 (ties to even)
  EXPECT_EQ(b[1], 0);
  EXPECT_EQ(b[2], 255);
  EXPECT_EQ(b[3], 0);  // NaN -> 0
  auto t16 = shadetwin::packTexture(emu::Format::RGBA16F, 1, 1, 1, lv);
  EXPECT_EQ(t16.loadFloat(0, 0, 0, 0).r, 0.5f);
  auto r32 = shadetwin::packTexture(emu::Format::R32F, 1, 1, 1, lv);
  EXPECT_EQ(r32.loadFloat(0, 0, 0, 0).a, 1.0f);
}
