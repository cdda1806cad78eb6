// Philox4x32-10 in shared integer code (shade/philox.h): the Random123 known-answer vectors
// (kat_vectors, "philox4x32 10" lines: counter, key -> output), the scalar and 8-lane builds agree,
// and the 24-bit floats are uniform (first and second moments, bit balance).
#include <gtest/gtest.h>

#include <cmath>

#include "lanes/instantiate.h"

namespace {
namespace sc = shadetwin::shade::scalar;
namespace x8 = shadetwin::shade::x8;

TEST(Philox, Random123KnownAnswers) {
  struct Kat {
    uint32_t ctr[4], key[2], out[4];
  };
  const Kat kats[] = {
      {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}},
      {{~0u, ~0u, ~0u, ~0u}, {~0u, ~0u}, {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}},
      {{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u},
       {0xa4093822u, 0x299f31d0u},
       {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}},
  };
  for (const Kat& k : kats) {
    const sc::Philox4 r = sc::philox4x32(sc::Philox4{k.ctr[0], k.ctr[1], k.ctr[2], k.ctr[3]}, k.key[0], k.key[1]);
    EXPECT_EQ(r.x, k.out[0]);
    EXPECT_EQ(r.y, k.out[1]);
    EXPECT_EQ(r.z, k.out[2]);
    EXPECT_EQ(r.w, k.out[3]);
  }
}

TEST(Philox, LanesMatchScalar) {
  using U8 = emu::U32<8>;
  for (uint32_t base = 0; base < 4096; base += 8) {
    U8 c0, c1;
    for (int l = 0; l < 8; ++l) c0.set(l, base + uint32_t(l)), c1.set(l, (base + uint32_t(l)) * 2654435761u);
    const x8::Philox4 r = x8::philox4x32(x8::Philox4{c0, c1, U8(7u), U8(0u)}, U8(12345u), U8(base));
    for (int l = 0; l < 8; ++l) {
      const sc::Philox4 s = sc::philox4x32(sc::Philox4{c0[l], c1[l], 7u, 0u}, 12345u, base);
      ASSERT_EQ(r.x[l], s.x);
      ASSERT_EQ(r.y[l], s.y);
      ASSERT_EQ(r.z[l], s.z);
      ASSERT_EQ(r.w[l], s.w);
    }
  }
}

TEST(Philox, UniformFloatsHaveTheRightMoments) {
  // 4 x 250k numbers from consecutive counters: mean 1/2, variance 1/12 (within 5 sigma), every output
  // bit set about half the time, and every value a multiple of 2^-24 in [0, 1).
  const int n = 250000;
  double s = 0, s2 = 0;
  int bits[32] = {};
  for (int i = 0; i < n; ++i) {
    const sc::Philox4 r = sc::philox4x32(sc::Philox4{uint32_t(i), 0u, 0u, 0u}, 1u, 2u);
    for (uint32_t v : {r.x, r.y, r.z, r.w}) {
      const float u = sc::unitFloat24(v);
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      ASSERT_EQ(u * 16777216.0f, std::floor(u * 16777216.0f));
      s += u, s2 += double(u) * u;
      for (int b = 0; b < 32; ++b) bits[b] += (v >> b) & 1u;
    }
  }
  const double m = s / (4.0 * n), var = s2 / (4.0 * n) - m * m;
  EXPECT_NEAR(m, 0.5, 5 * std::sqrt(1.0 / 12 / (4.0 * n)));
  EXPECT_NEAR(var, 1.0 / 12, 0.002);
  for (int b = 0; b < 32; ++b) EXPECT_NEAR(bits[b] / (4.0 * n), 0.5, 5 * 0.5 / std::sqrt(4.0 * n)) << b;
}

}  // namespace
