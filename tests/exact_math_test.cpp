// Exact-math layer: correct rounding of div/sqrt, max ULP of the others against correctly rounded
// (double) results, edge cases, scalar/SIMD agreement at every lane width and on tails, and the
// per-stage denormal mode.
#include <gtest/gtest.h>

#include "emu/fpenv.h"
#include "lanes/instantiate.h"

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "lanes/instantiate.h"
#include "lanes/kernels.h"
#include "cli/verify/verify.h"

namespace sc = shadetwin::shade::scalar;
using shadetwin::ulpDistance;

namespace {
float fromBits(uint32_t b) { float f; std::memcpy(&f, &b, 4); return f; }
uint32_t toBits(float f) { uint32_t b; std::memcpy(&b, &f, 4); return b; }
bool same(float a, float b) { return toBits(a) == toBits(b); }
}  // namespace

TEST(ExactMath, DivIsCorrectlyRoundedOnAnyBits) {
  // exDivPortable is what a GPU runs (exDiv without the C++ builds' native fast path): random bit
  // patterns (NaN, inf, zero, subnormal operands and quotients, overflow) in the scalar and 8-lane builds.
  namespace x8 = shadetwin::shade::x8;
  using F8 = emu::F32<8>;
  std::mt19937 rng(11);
  F8 va, vb;
  for (int i = 0; i < 4000000; ++i) {
    float a = fromBits(rng()), b = fromBits(rng());
    if (i % 3 == 0) b = fromBits(rng() & 0x807fffffu);  // subnormal divisors
    if (i % 5 == 0) a = fromBits(rng() & 0x807fffffu);  // subnormal dividends
    float want = float(double(a) / double(b));            // double division then rounding is exact
    float got = sc::exDivPortable(a, b);
    if (std::isnan(want)) ASSERT_EQ(toBits(got), 0x7fc00000u) << a << " / " << b;
    else ASSERT_TRUE(same(got, want)) << a << " / " << b << " got " << got << " want " << want;
    va.set(i % 8, a), vb.set(i % 8, b);
    if (i % 8 == 7) {
      const F8 q = x8::exDivPortable(va, vb);
      for (int l = 0; l < 8; ++l) ASSERT_TRUE(same(q[l], sc::exDivPortable(va[l], vb[l])));
    }
  }
}

TEST(ExactMath, DivIsCorrectlyRoundedAtQuotientBoundaries) {
  // Where an estimate-and-correct division goes wrong if its correction is short: exact quotients
  // (a = q b with small integers q and 24-bit b), quotients next to them (a one ulp off q b), equal
  // significands, the largest and smallest significands, and every divisor significand against a few
  // dividends; each at exponents that give normal, subnormal (ties included) and overflowing results.
  // (The exact quotients are where the upward correction acts: without it 72 of them come out wrong.)
  std::mt19937 rng(29);
  auto check = [](float a, float b) {
    const float want = float(double(a) / double(b)), got = sc::exDivPortable(a, b);
    if (std::isnan(want)) return toBits(got) == 0x7fc00000u;
    return same(got, want);
  };
  const int exps[] = {0, 1, -1, 100, -100, 126, -126, 140, -140, 150, -150};
  for (int i = 0; i < 400000; ++i) {
    const uint32_t mb = 0x00800000u | (rng() & 0x007fffffu);
    const uint32_t qi = 1u + rng() % 255u;
    const float b = fromBits(0x3f800000u | (mb & 0x007fffffu));
    const float prod = float(qi) * b;                   // exact when it fits 24 bits, else rounded
    const uint32_t pb = toBits(prod);
    const int e = exps[i % 11];
    const float s = std::ldexp(1.0f, e / 2), t = std::ldexp(1.0f, e - e / 2);
    for (uint32_t bits : {pb - 1u, pb, pb + 1u}) {
      const float a = fromBits(bits);
      ASSERT_TRUE(check(a * s, b / t)) << a << " * 2^" << e / 2 << " / " << b;
      ASSERT_TRUE(check(a, b)) << a << " / " << b;
    }
  }
  // Remainders at their extremes (1, 2, 3, Mb - 1, Mb - 2, Mb - 3) and at the guard bit's boundary
  // (Mb / 2, Mb / 2 + 1): Ma 2^k = qa Mb + rem with qa = -rem Mb^-1 mod 2^k for odd Mb.
  int built = 0;
  for (int i = 0; i < 400000; ++i) {
    const uint64_t mb = 0x00800001u | (rng() & 0x007ffffeu);
    uint64_t inv = mb;
    for (int it = 0; it < 5; ++it) inv = inv * (2 - mb * inv);  // Mb^-1 mod 2^64 (Newton, 5 -> 64 bits)
    const uint64_t rems[] = {1, 2, 3, mb - 1, mb - 2, mb - 3, mb / 2, mb / 2 + 1};
    const uint64_t rem = rems[i % 8];
    for (int k : {23, 24}) {
      const uint64_t mask = (1ull << k) - 1;
      const uint64_t qa = ((0 - rem * inv) & mask) + (k == 23 ? (1ull << 23) : 0);
      if (qa < (1ull << 23) || qa >= (1ull << 24)) continue;
      const uint64_t ma = (qa * mb + rem) >> k;
      if (ma < (1ull << 23) || ma >= (1ull << 24) || (k == 24) != (ma < mb)) continue;
      const float a = fromBits(0x3f800000u | uint32_t(ma & 0x7fffffu)), b = fromBits(0x3f800000u | uint32_t(mb & 0x7fffffu));
      ASSERT_TRUE(check(a, b)) << a << " / " << b;
      ASSERT_TRUE(check(a * 1e-20f, b * 1e20f)) << a << " / " << b;  // the same significands, subnormal
      ++built;
    }
  }
  EXPECT_GT(built, 200000);
  const uint32_t dividends[] = {0x00800000u, 0x00800001u, 0x00c00000u, 0x00ffffffu, 0x00fffffeu, 0x00aaaaabu};
  for (uint32_t mb = 0x00800000u; mb < 0x01000000u; mb += 3) {
    const float b = fromBits(0x3f800000u | (mb & 0x007fffffu));
    for (uint32_t ma : dividends) {
      const float a = fromBits(0x3f800000u | (ma & 0x007fffffu));
      ASSERT_TRUE(check(a, b)) << a << " / " << b;
      ASSERT_TRUE(check(a * 1e-30f, b * 1e10f)) << a << " / " << b;  // subnormal quotient
    }
  }
}

TEST(ExactMath, EstimatesMeetTheirBounds) {
  // The Newton estimates under exDivPortable / exSqrtPortable (and the log's reciprocal): relative error
  // below 2^-22.6 / 2^-22.5 for every float of their ranges; the corrections cover the rest with wide margins.
  double rcp = 0, rsqrt = 0;
  for (uint32_t b = 0x3f800000u; b <= 0x40200000u; ++b) {  // [1, 2.5]
    const double d = fromBits(b);
    rcp = std::max(rcp, std::fabs(double(sc::xmRcpApprox(fromBits(b))) * d - 1.0));
  }
  for (uint32_t b = 0x3f800000u; b <= 0x40800000u; ++b) {  // [1, 4]
    const double n = fromBits(b);
    rsqrt = std::max(rsqrt, std::fabs(double(sc::xmRsqrtApprox(fromBits(b))) * std::sqrt(n) - 1.0));
  }
  EXPECT_LT(rcp, std::exp2(-22.6));  // the bounds exact_math.h's derivations use
  EXPECT_LT(rsqrt, std::exp2(-22.5));
  EXPECT_GT(rcp, std::ldexp(1.0, -25));  // not exact: the corrections are what make the results exact
  EXPECT_GT(rsqrt, std::ldexp(1.0, -25));
}

TEST(ExactMath, PortableSqrtIsCorrectlyRoundedOnEveryInputClass) {
  // exSqrtPortable depends only on the significand and the exponent's parity: every float in [1, 4)
  // covers all of them; plus every subnormal and the specials.
  for (uint32_t b = 0x3f800000u; b < 0x40800000u; ++b)
    ASSERT_TRUE(same(sc::exSqrtPortable(fromBits(b)), float(std::sqrt(double(fromBits(b)))))) << fromBits(b);
  for (uint32_t b = 1u; b < 0x00800000u; ++b)
    ASSERT_TRUE(same(sc::exSqrtPortable(fromBits(b)), float(std::sqrt(double(fromBits(b)))))) << fromBits(b);
  for (uint32_t b : {0x7f7fffffu, 0x00800000u, 0x00000001u})
    ASSERT_TRUE(same(sc::exSqrtPortable(fromBits(b)), float(std::sqrt(double(fromBits(b))))));
  EXPECT_TRUE(same(sc::exSqrtPortable(-0.0f), -0.0f));
  EXPECT_TRUE(same(sc::exSqrtPortable(0.0f), 0.0f));
  EXPECT_EQ(sc::exSqrtPortable(INFINITY), INFINITY);
  EXPECT_EQ(toBits(sc::exSqrtPortable(-1e-45f)), 0x7fc00000u);
  EXPECT_EQ(toBits(sc::exSqrtPortable(-INFINITY)), 0x7fc00000u);
}

TEST(ExactMath, NativeFastPathsGiveThePortableBits) {
  // The C++ builds divide / take square roots natively when every lane is normal (lanes/native_exact.h).
  // Vectors of 8 whose lanes are random normals, or mixed with one special lane (zero, subnormal, inf,
  // NaN: the whole vector takes the portable path), in the default mode and under FTZ/DAZ (a flushing
  // stage): every lane equals the correctly rounded result, subnormal quotients included.
  namespace x8 = shadetwin::shade::x8;
  using F8 = emu::F32<8>;
  std::mt19937 rng(23);
  const uint32_t specials[] = {0u, 0x80000000u, 1u, 0x007fffffu, 0x7f800000u, 0x7fc00000u, 0x00800000u};
  for (bool flush : {false, true}) {
    emu::DenormalScope mode(flush);
    for (int v = 0; v < 200000; ++v) {
      F8 a, b, x;
      for (int l = 0; l < 8; ++l) {
        // normal exponents in [1, 254]; quotients then range over subnormal to overflow
        a.set(l, fromBits((rng() & 0x807fffffu) | ((1u + rng() % 254u) << 23)));
        b.set(l, fromBits((rng() & 0x807fffffu) | ((1u + rng() % 254u) << 23)));
        x.set(l, fromBits((rng() & 0x007fffffu) | ((1u + rng() % 254u) << 23)));
      }
      if (v % 4 == 1) a.set(int(rng() % 8), fromBits(specials[rng() % 7]));
      if (v % 4 == 2) b.set(int(rng() % 8), fromBits(specials[rng() % 7]));
      if (v % 4 == 3) x.set(int(rng() % 8), fromBits(specials[rng() % 7]));
      const F8 q = x8::exDiv(a, b), r = x8::exSqrt(x);
      for (int l = 0; l < 8; ++l) {
        float wq, wr;
        {
          emu::DenormalScope exact(false);  // the reference: double result rounded to float, no flushing
          wq = float(double(a[l]) / double(b[l]));
          wr = float(std::sqrt(double(x[l])));
        }
        if (std::isnan(wq)) ASSERT_EQ(toBits(q[l]), 0x7fc00000u);
        else ASSERT_TRUE(same(q[l], wq)) << a[l] << " / " << b[l] << " flush " << flush;
        if (std::isnan(wr)) ASSERT_EQ(toBits(r[l]), 0x7fc00000u);
        else ASSERT_TRUE(same(r[l], wr)) << x[l] << " flush " << flush;
        ASSERT_TRUE(same(sc::exDiv(a[l], b[l]), q[l]));  // scalar build (fast path or not): the same bits
        ASSERT_TRUE(same(sc::exSqrt(x[l]), r[l]));
      }
    }
  }
}

TEST(ExactMath, MinAndMaxReadASubnormalAsZeroInAFlushingStage) {
  // GLSL min/max are the machine's min/max instruction in the C++ builds (emu/lanes.h minMachine), as they are in the
  // devices' x86 back ends: under a flushing stage's DAZ a subnormal operand reads as a zero of its sign, in the compare
  // and in the value returned. Written as a compare and a select they were that only where GCC made a MINSS of it (-O1
  // and above): at -Og the sanitizer build's atan2 kept a subnormal y, and 33 of 2000 fragment-stage atan2 in verify
  // math differed from lavapipe. Every pair of subnormal, zero and normal operands, both modes, scalar and 8 lanes.
  namespace x8 = shadetwin::shade::x8;
  const uint32_t vals[] = {1u, 0x007fffffu, 0x80000001u, 0x807fffffu, 0x00400000u, 0u, 0x80000000u,
                           0x3f800000u, 0xbf800000u, 0x00800000u, 0x80800000u, 0x7f800000u, 0xff800000u};
  int flushedSome = 0;
  for (bool flush : {false, true}) {
    emu::DenormalScope mode(flush);
    const auto daz = [&](uint32_t b) { return flush && (b & 0x7f800000u) == 0u ? (b & 0x80000000u) : b; };
    for (uint32_t xb : vals)
      for (uint32_t yb : vals) {
        const float x = fromBits(xb), y = fromBits(yb);
        const float dx = fromBits(daz(xb)), dy = fromBits(daz(yb));
        // GLSL: min(x, y) = y < x ? y : x, max(x, y) = x < y ? y : x, on the operands as the stage reads them
        uint32_t wantMin, wantMax;
        {
          emu::DenormalScope exact(false);
          wantMin = dy < dx ? daz(yb) : daz(xb);
          wantMax = dx < dy ? daz(yb) : daz(xb);
        }
        flushedSome += wantMin != (y < x ? yb : xb);
        EXPECT_EQ(toBits(sc::min(x, y)), wantMin) << std::hex << xb << " " << yb << " flush " << flush;
        EXPECT_EQ(toBits(sc::max(x, y)), wantMax) << std::hex << xb << " " << yb << " flush " << flush;
        const emu::F32<8> mn = x8::min(emu::F32<8>(x), emu::F32<8>(y)), mx = x8::max(emu::F32<8>(x), emu::F32<8>(y));
        for (int l = 0; l < 8; ++l) {
          EXPECT_EQ(toBits(mn[l]), wantMin) << std::hex << xb << " " << yb << " flush " << flush;
          EXPECT_EQ(toBits(mx[l]), wantMax) << std::hex << xb << " " << yb << " flush " << flush;
        }
      }
    // The verify math input that showed it: atan2 of a subnormal y is a signed zero where the stage flushes.
    EXPECT_EQ(toBits(sc::exAtan2(-5.929870507587935e-39f, 4.002964626437233e-10f)), flush ? 0x80000000u : 0x8f963a8eu);
  }
  EXPECT_GT(flushedSome, 20);  // the flushing mode changes the answer on many of these pairs
}

TEST(ExactMath, SqrtIsCorrectlyRoundedDenseSweep) {
  // every float in [1, 4) (all 2^24 significands, both exponent parities) and every 97th subnormal
  std::vector<float> in, out;
  for (uint32_t b = 0x3f800000u; b < 0x40800000u; ++b) in.push_back(fromBits(b));
  for (uint32_t b = 1; b < 0x00800000u; b += 97) in.push_back(fromBits(b));
  std::vector<float> in3(3 * in.size(), 0.0f), out3(3 * in.size());
  for (size_t i = 0; i < in.size(); ++i) in3[3 * i] = in[i];
  shadetwin::evalMathKernel(1, in3.data(), out3.data(), in.size(), 8);
  for (size_t i = 0; i < in.size(); ++i)
    ASSERT_TRUE(same(out3[3 * i], float(std::sqrt(double(in[i]))))) << in[i];
}

TEST(ExactMath, EdgeCases) {
  const float inf = INFINITY;
  EXPECT_EQ(sc::exDiv(1.0f, 0.0f), inf);
  EXPECT_EQ(sc::exDiv(1.0f, -0.0f), -inf);
  EXPECT_TRUE(std::isnan(sc::exDiv(0.0f, 0.0f)));
  EXPECT_TRUE(std::isnan(sc::exDiv(inf, inf)));
  EXPECT_TRUE(same(sc::exDiv(-0.0f, 5.0f), -0.0f));
  EXPECT_TRUE(same(sc::exDiv(1e-45f, 2.0f), 0.0f));          // ties to even at the smallest subnormal
  EXPECT_TRUE(same(sc::exDiv(fromBits(3), 2.0f), fromBits(2)));  // 1.5 quanta -> 2 (even)
  EXPECT_EQ(sc::exDiv(3.4028235e38f, 0.5f), inf);
  EXPECT_TRUE(same(sc::exSqrt(-0.0f), -0.0f));
  EXPECT_TRUE(std::isnan(sc::exSqrt(-1.0f)));
  EXPECT_TRUE(std::isnan(sc::exSqrt(-inf)));
  EXPECT_EQ(sc::exSqrt(inf), inf);
  EXPECT_EQ(sc::exInverseSqrt(0.0f), inf);
  EXPECT_EQ(sc::exInverseSqrt(-0.0f), -inf);
  EXPECT_EQ(sc::exInverseSqrt(inf), 0.0f);
  EXPECT_EQ(sc::exExp(-inf), 0.0f);
  EXPECT_EQ(sc::exExp(inf), inf);
  EXPECT_EQ(sc::exExp(89.0f), inf);
  EXPECT_EQ(sc::exExp2(128.0f), inf);
  EXPECT_EQ(sc::exExp2(-10.0f), 1.0f / 1024.0f);
  EXPECT_TRUE(same(sc::exExp2(-149.0f), 1e-45f));  // subnormal result (compute stage preserves)
  EXPECT_EQ(sc::exExp(0.0f), 1.0f);
  EXPECT_EQ(sc::exLog(0.0f), -inf);
  EXPECT_EQ(sc::exLog2(-0.0f), -inf);
  EXPECT_TRUE(std::isnan(sc::exLog(-1.0f)));
  EXPECT_EQ(sc::exLog(inf), inf);
  EXPECT_EQ(sc::exLog2(1.0f), 0.0f);
  EXPECT_EQ(sc::exLog2(1024.0f), 10.0f);
  EXPECT_EQ(sc::exLog2(1e-45f), -149.0f);
  EXPECT_EQ(sc::exPow(2.0f, 10.0f), 1024.0f);
  EXPECT_EQ(sc::exPow(0.0f, 2.0f), 0.0f);
  EXPECT_EQ(sc::exPow(0.0f, -1.0f), inf);
  EXPECT_EQ(sc::exPow(-0.0f, -3.0f), -inf);  // C99: odd integer y keeps the sign of -0
  EXPECT_TRUE(same(sc::exPow(-0.0f, 3.0f), -0.0f));
  EXPECT_EQ(sc::exPow(-0.0f, -2.0f), inf);
  EXPECT_LE(ulpDistance(sc::exPow(0.99999994f, -1e8f), float(std::pow(double(0.99999994f), -1e8))), 2);  // y log2 m large
  EXPECT_LE(ulpDistance(sc::exPow(1.0000001f, 5e8f), float(std::pow(double(1.0000001f), 5e8))), 2);
  EXPECT_EQ(sc::exPow(5.0f, 0.0f), 1.0f);
  EXPECT_EQ(sc::exPow(1.0f, NAN), 1.0f);
  EXPECT_TRUE(std::isnan(sc::exPow(-2.0f, 2.0f)));  // GLSL: undefined; shadetwin: NaN
  EXPECT_TRUE(std::isnan(sc::exSin(inf)));
  EXPECT_TRUE(std::isnan(sc::exCos(NAN)));
  EXPECT_TRUE(same(sc::exSin(-0.0f), -0.0f));
  EXPECT_EQ(sc::exCos(-0.0f), 1.0f);
  EXPECT_TRUE(same(sc::exSin(1e-30f), 1e-30f));
  EXPECT_TRUE(same(sc::exAtan2(0.0f, -0.0f), 3.14159274f));
  EXPECT_TRUE(same(sc::exAtan2(-0.0f, -0.0f), -3.14159274f));
  EXPECT_TRUE(same(sc::exAtan2(-0.0f, 0.0f), -0.0f));
  EXPECT_TRUE(same(sc::exAtan2(inf, inf), 0.785398185f));
  EXPECT_TRUE(same(sc::exAtan2(1.0f, -inf), 3.14159274f));
  EXPECT_TRUE(same(sc::exAtan2(0.0f, 1e-45f), 0.0f));  // denormal x: no 0/0-style reduction
  EXPECT_LE(ulpDistance(sc::exAtan2(1e-45f, -0.0f), 1.57079637f), 1);  // pi - pi/2, rounded
  EXPECT_LE(ulpDistance(sc::exAtan2(fromBits(1), fromBits(2)), float(std::atan2(1.0, 2.0))), 2);
  EXPECT_TRUE(std::isnan(sc::exAcos(1.5f)));
  EXPECT_EQ(sc::exAcos(1.0f), 0.0f);
  auto n = sc::exNormalize(shadetwin::shade::V3<float>(1.5e38f, 2e38f, 0.0f));  // no overflow
  EXPECT_LE(ulpDistance(n.x, 0.6f), 1);
  EXPECT_LE(ulpDistance(n.y, 0.8f), 1);
  auto z = sc::exNormalize(shadetwin::shade::V3<float>(1e-45f, 0.0f, 0.0f));  // denormal input scales up
  EXPECT_EQ(z.x, 1.0f);
}

TEST(ExactMath, SinCosOfHugeArgumentsUsePayneHanek) {
  // Arguments where naive reduction fails; double libm reduces exactly.
  for (float x : {1e30f, 3.4028235e38f, 1.0e22f, 12345678.0f, 3.14159274e15f, 102951.6797f}) {
    EXPECT_LE(ulpDistance(sc::exSin(x), float(std::sin(double(x)))), 1) << x;
    EXPECT_LE(ulpDistance(sc::exCos(x), float(std::cos(double(x)))), 1) << x;
  }
}

struct UlpCase {
  int fn;
  float lo, hi;
  int64_t maxUlp;  // measured bound, see docs/DESIGN.md
};

class ExactMathUlp : public ::testing::TestWithParam<UlpCase> {};

TEST_P(ExactMathUlp, WithinDocumentedBound) {
  const UlpCase c = GetParam();
  std::mt19937 rng(uint32_t(c.fn) + 100);
  std::uniform_real_distribution<float> U(c.lo, c.hi);
  const size_t n = 300000;
  std::vector<float> in(3 * n), out(3 * n);
  for (auto& v : in) v = U(rng);
  shadetwin::evalMathKernel(c.fn, in.data(), out.data(), n, 8);
  int64_t worst = 0;
  for (size_t i = 0; i < n; ++i) {
    double a = in[3 * i], b = in[3 * i + 1], z = in[3 * i + 2], r = 0;
    switch (c.fn) {
      case 2: r = 1 / std::sqrt(a); break;
      case 3: r = a / std::sqrt(a * a + b * b + z * z); break;
      case 4: r = std::exp(a); break;
      case 5: r = std::exp2(a); break;
      case 6: r = std::log(a); break;
      case 7: r = std::log2(a); break;
      case 8: r = std::pow(a, b); break;
      case 9: r = std::sin(a); break;
      case 10: r = std::cos(a); break;
      case 11: r = std::atan2(a, b); break;
      case 12: r = std::acos(a); break;
    }
    worst = std::max(worst, ulpDistance(out[3 * i], float(r)));
  }
  EXPECT_LE(worst, c.maxUlp) << shadetwin::mathKernelName(c.fn);
  EXPECT_GE(worst, 0);
}

INSTANTIATE_TEST_SUITE_P(Functions, ExactMathUlp,
                         ::testing::Values(UlpCase{2, 1e-30f, 1e30f, 1}, UlpCase{3, -100.0f, 100.0f, 3},
                                           UlpCase{4, -87.0f, 88.0f, 1}, UlpCase{5, -126.0f, 127.0f, 1},
                                           UlpCase{6, 1e-20f, 1e20f, 1}, UlpCase{7, 0.5f, 2.0f, 1},
                                           UlpCase{8, 0.5f, 4.0f, 2}, UlpCase{9, -1e4f, 1e4f, 1},
                                           UlpCase{10, -1e4f, 1e4f, 1}, UlpCase{11, -10.0f, 10.0f, 2},
                                           UlpCase{12, -1.0f, 1.0f, 2}));

TEST(ExactMath, ScalarAndSimdAgreeAtEveryWidthAndOnTails) {
  std::mt19937 rng(5);
  const size_t n = 20011;  // not a multiple of any lane width
  std::vector<float> in(3 * n);
  for (auto& v : in) v = (rng() % 3) ? std::uniform_real_distribution<float>(-50.0f, 50.0f)(rng) : fromBits(rng());
  for (int fn = 0; fn < shadetwin::mathKernelCount(); ++fn) {
    std::vector<float> ref(3 * n), out(3 * n);
    shadetwin::evalMathKernel(fn, in.data(), ref.data(), n, 1);
    for (int lanes : {4, 8, 16}) {
      shadetwin::evalMathKernel(fn, in.data(), out.data(), n, lanes);
      ASSERT_EQ(0, std::memcmp(ref.data(), out.data(), ref.size() * 4)) << shadetwin::mathKernelName(fn) << " x" << lanes;
    }
  }
}

TEST(ExactMath, FlushingStageFlushesPolynomialResultsButDivStaysExact) {
  float in[3] = {-140.0f, 0.0f, 0.0f}, out[3];
  shadetwin::evalMathKernel(5, in, out, 1, 8, /*flushDenormals=*/false);
  EXPECT_GT(out[0], 0.0f);  // 2^-140, subnormal, preserved
  shadetwin::evalMathKernel(5, in, out, 1, 8, /*flushDenormals=*/true);
  EXPECT_EQ(out[0], 0.0f);  // flushed, as lavapipe's fragment stage does
  float d[3] = {1e-40f, 2.0f, 0.0f};
  shadetwin::evalMathKernel(0, d, out, 1, 1, true);
  EXPECT_TRUE(same(out[0], 5e-41f));  // integer division: denormals honoured in every stage
}
