#include "emu/lanes.h"

#include <gtest/gtest.h>

#include <random>
#include <type_traits>

using emu::F32;
using emu::Mask;
using emu::U32;

static_assert(!std::is_convertible_v<Mask<8>, bool>, "a lane mask must not convert to bool");
static_assert(!std::is_constructible_v<bool, Mask<8>>, "a lane mask must not construct a bool");

TEST(Lanes, ArithmeticMatchesScalarPerLane) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(-1e3f, 1e3f);
  F32<8> a, b;
  for (int i = 0; i < 8; ++i) { a.set(i, U(rng)); b.set(i, U(rng)); }
  F32<8> s = a + b, d = a - b, p = a * b, n = -a;
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(s[i], a[i] + b[i]);
    EXPECT_EQ(d[i], a[i] - b[i]);
    EXPECT_EQ(p[i], a[i] * b[i]);
    EXPECT_EQ(n[i], -a[i]);
  }
}

TEST(Lanes, SelectPicksPerLane) {
  F32<4> a(1.0f), b(2.0f), x;
  for (int i = 0; i < 4; ++i) x.set(i, float(i));
  F32<4> r = select(x < 2.0f, a, b);
  EXPECT_EQ(r[0], 1.0f);
  EXPECT_EQ(r[1], 1.0f);
  EXPECT_EQ(r[2], 2.0f);
  EXPECT_EQ(r[3], 2.0f);
}

TEST(Lanes, MulHiAndShifts) {
  U32<8> a(0xffffffffu), b(0x80000001u);
  U32<8> h = mulHi(a, b);
  EXPECT_EQ(h[3], uint32_t((uint64_t(0xffffffffu) * 0x80000001u) >> 32));
  U32<8> s = a >> 28;
  EXPECT_EQ(s[0], 0xfu);
  emu::I32<8> m(-16);
  EXPECT_EQ((m >> 2)[5], -4);  // arithmetic shift, as GLSL int
}

TEST(Lanes, ConversionsAreGlslConversions) {
  F32<4> f;
  f.set(0, 2.7f); f.set(1, -2.7f); f.set(2, 16777217.0f); f.set(3, -0.5f);
  emu::I32<4> i(f);
  EXPECT_EQ(i[0], 2);
  EXPECT_EQ(i[1], -2);
  EXPECT_EQ(i[3], 0);
  U32<4> bits = floatBitsToUint(F32<4>(-0.0f));
  EXPECT_EQ(bits[2], 0x80000000u);
}
