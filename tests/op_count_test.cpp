// The counting build's texture cache (issue 19, model/op_count.h): which texels a lookup reads (Vulkan's texel
// selection), LRU replacement in a set-associative cache, and that the counted lookups of neighbouring pixels reuse
// lines where scattered lookups do not.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "model/op_count.h"

namespace {

emu::Texture rgba32f(uint32_t w, uint32_t h, uint32_t layers, bool chain) {
  std::vector<std::vector<uint8_t>> levels;
  for (uint32_t l = 0;; ++l) {
    const uint32_t lw = std::max(1u, w >> l), lh = std::max(1u, h >> l);
    levels.emplace_back(size_t(lw) * lh * layers * 16, uint8_t(l));
    if (!chain || (lw == 1 && lh == 1)) break;
  }
  return emu::Texture(emu::Format::RGBA32F, w, h, layers, std::move(levels));
}

uint64_t addr(const emu::Texture& t, uint32_t level, uint32_t layer, uint32_t x, uint32_t y) {
  return uint64_t(reinterpret_cast<uintptr_t>(t.texelPtr(level, layer, x, y)));
}

TEST(TexCache, LookupsReadTheTexelsOfTheirFilterFootprint) {
  const emu::Texture t = rgba32f(64, 32, 3, true);
  emu::SamplerDesc s;  // linear, linear mips, clamp
  uint64_t a[8];
  // Bilinear at level 0 about texel centre (10.5, 5.5) + (0.25, 0.25): texels (10..11, 5..6) of layer 2.
  ASSERT_EQ(opcount::texelAddresses(t, s, 10.75f / 64, 5.75f / 32, 2.0f, 0.0f, a), 4);
  EXPECT_EQ(a[0], addr(t, 0, 2, 10, 5));
  EXPECT_EQ(a[1], addr(t, 0, 2, 11, 5));
  EXPECT_EQ(a[2], addr(t, 0, 2, 10, 6));
  EXPECT_EQ(a[3], addr(t, 0, 2, 11, 6));
  // Trilinear between levels 1 and 2: four texels on each.
  ASSERT_EQ(opcount::texelAddresses(t, s, 0.5f, 0.5f, 0.0f, 1.5f, a), 8);
  EXPECT_EQ(a[0], addr(t, 1, 0, 15, 7));
  EXPECT_EQ(a[4], addr(t, 2, 0, 7, 3));
  // An integer LOD reads one level; a LOD past the chain the last level (1x1 here: one texel, four times).
  EXPECT_EQ(opcount::texelAddresses(t, s, 0.5f, 0.5f, 0.0f, 2.0f, a), 4);
  ASSERT_EQ(opcount::texelAddresses(t, s, 0.5f, 0.5f, 0.0f, 99.0f, a), 4);
  EXPECT_EQ(a[0], addr(t, 6, 0, 0, 0));
  EXPECT_EQ(a[3], addr(t, 6, 0, 0, 0));
  // Repeat wraps the footprint at u = 0 to the last column; clamp keeps it on the first.
  s.addressU = emu::AddressMode::Repeat;
  opcount::texelAddresses(t, s, 0.0f, 0.5f, 0.0f, 0.0f, a);
  EXPECT_EQ(a[0], addr(t, 0, 0, 63, 15));
  EXPECT_EQ(a[1], addr(t, 0, 0, 0, 15));
  // Nearest filtering, nearest mips: one texel, on the rounded level.
  s.magFilter = s.minFilter = emu::Filter::Nearest, s.mipmapMode = emu::MipmapMode::Nearest;
  ASSERT_EQ(opcount::texelAddresses(t, s, 0.99f, 0.01f, 1.0f, 1.6f, a), 1);
  EXPECT_EQ(a[0], addr(t, 2, 1, 15, 0));
}

TEST(TexCache, LeastRecentlyUsedLinesAreEvicted) {
  opcount::TexCache c;
  c.configure(64, 64.0 * 16);  // one set of 16 ways: fully associative
  ASSERT_EQ(c.sets, 1u);
  auto run = [&](int lines, int rounds) {
    opcount::counts = {};
    for (int r = 0; r < rounds; ++r)
      for (int i = 0; i < lines; ++i) c.touch(uint64_t(1000 + i));
    return opcount::counts[opcount::kTexMiss];
  };
  EXPECT_EQ(run(16, 3), 16u);       // fits: the first round's misses only
  c.configure(64, 64.0 * 16);
  EXPECT_EQ(run(17, 3), 51u);       // one line more than the ways, cyclic: LRU misses every time
  c.configure(64, 64.0 * 16);
  EXPECT_EQ(opcount::counts[opcount::kTexLine], 51u);  // configure leaves the counters, clears the lines
  EXPECT_EQ(run(4, 2), 4u);
  // Misses next to a recent miss are a stream (a prefetcher's): lines 1000..1003 above are one, their first miss not.
  EXPECT_EQ(opcount::counts[opcount::kTexStreamMiss], 3u);
  c.configure(64, 64.0 * 16);
  opcount::counts = {};
  for (uint64_t l : {10u, 30u, 50u, 70u, 31u, 90u}) c.touch(l);  // scattered, one neighbour of a recent miss (31)
  EXPECT_EQ(opcount::counts[opcount::kTexMiss], 6u);
  EXPECT_EQ(opcount::counts[opcount::kTexStreamMiss], 1u);
  // A lane's footprint counts each distinct line once: a 2x2 footprint on two rows of one line each.
  opcount::counts = {};
  const uint64_t fp[4] = {64 * 7 + 0, 64 * 7 + 16, 64 * 9 + 0, 64 * 9 + 16};
  c.lane(fp, 4);
  EXPECT_EQ(opcount::counts[opcount::kTexLine], 2u);
  // No capacity: lines are counted, nothing misses.
  c.configure(64, 0.0);
  opcount::counts = {};
  EXPECT_EQ(run(40, 2), 0u);
  EXPECT_EQ(opcount::counts[opcount::kTexLine], 80u);
}

// The counted bridge (shade::textureLodLanes over counting lanes) feeds the cache: 64x64 "pixels" looking up a 1024^2
// texture at their own texel (neighbours share lines) miss about once per line of the footprint, while the same number
// of lookups at random coordinates miss nearly every time in a cache smaller than the texture.
TEST(TexCache, NeighbouringLookupsReuseLinesScatteredOnesDoNot) {
  const emu::Texture t = rgba32f(1024, 1024, 1, false);  // 16 MiB
  shadetwin::shade::Sampler2D s{&t, emu::SamplerDesc{}, &emu::lavapipeProfile()};
  s.desc.magFilter = s.desc.minFilter = emu::Filter::Nearest;
  auto misses = [&](bool scattered, uint32_t seed) {
    opcount::counts = {};
    opcount::texCache.configure(64, 1 << 20);  // 1 MiB
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; x += 8) {
        opcount::F<8> u(0.0f), v(0.0f), lod(0.0f);
        for (int i = 0; i < 8; ++i) {
          u.set(i, scattered ? U(rng) : (float(x + i) + 0.5f) / 1024.0f);
          v.set(i, scattered ? U(rng) : (float(y) + 0.5f) / 1024.0f);
        }
        shadetwin::shade::textureLodLanes(s, u, v, lod);
      }
    EXPECT_EQ(opcount::counts[opcount::kTexLookup], 4096u);
    return opcount::counts[opcount::kTexMiss];
  };
  // Each row of 64 texels (1 KiB) is 16 lines, 17 where the level's storage does not start on a line.
  uint64_t rowLines = 0;
  for (uint32_t y = 0; y < 64; ++y) rowLines += (addr(t, 0, 0, 63, y) + 15) / 64 - addr(t, 0, 0, 0, y) / 64 + 1;
  ASSERT_GE(rowLines, 64u * 16u);
  ASSERT_LE(rowLines, 64u * 17u);
  for (uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
    EXPECT_EQ(misses(false, seed), rowLines);  // one miss per line of the footprint: 4 pixels per 64-byte line
    EXPECT_EQ(opcount::counts[opcount::kTexStreamMiss], rowLines - 64);  // each row a stream after its first line
    const uint64_t m = misses(true, seed);
    EXPECT_GT(m, 3900u) << seed;  // 4096 lookups over 262,144 lines, 16,384 of which fit
    EXPECT_LE(m, 4096u) << seed;
    EXPECT_LT(opcount::counts[opcount::kTexStreamMiss], 40u) << seed;  // scattered: hardly ever next to a recent miss
  }
}

}  // namespace

// A block behind a false uniform condition (the dialect's uniformMask: a setting, a push constant) runs on a device
// that runs every block (lavapipe and SwiftShader: calibrate's branch kernel on a push constant, docs/RESULTS.md
// session 41), so its straight-line operations count there; a GPU skips it; and, unlike a false specialization
// constant on a device that folds one, no compiler removes it. Its effects are selects on the mask: no value changes.
TEST(OpCount, UntakenUniformBlocksCountWhereTheDeviceRunsEveryBlock) {
  const opcount::F<8> x(emu::F32<8>(1.5f));
  auto block = [&](bool spec, bool everyBlock, bool folds) {
    opcount::counts = {};
    opcount::executeEveryBlock = everyBlock, opcount::foldsSpecConstants = folds;
    const opcount::M<8> m = spec ? specConstantMask(x, false) : runtimeUniformMask(x, false);
    opcount::F<8> y = x;
    if (auto scope = ifAnyScope(m); scope) y = select(m, (y + x) * x, y);
    opcount::executeEveryBlock = false, opcount::foldsSpecConstants = true;
    EXPECT_EQ(y[0], 1.5f);  // untaken: the value is kept
    return opcount::counts[opcount::kFAdd] + opcount::counts[opcount::kFMul];
  };
  EXPECT_EQ(block(false, true, true), 2u);   // a uniform mask on a software device: the block runs
  EXPECT_EQ(block(false, true, false), 2u);
  EXPECT_EQ(block(false, false, true), 0u);  // GPU: skipped
  EXPECT_EQ(block(true, true, true), 0u);    // a folded specialization constant: compiled out
  EXPECT_EQ(block(true, true, false), 2u);   // SwiftShader keeps it
}

// Shifts are a class of their own (SwiftShader's Subzero runs a vector shift as four scalar ones: calibrate measures
// ~6 fadds a shift, where an add or xor costs less than one): counted as shift, never as ialu, and the values unchanged.
TEST(OpCount, ShiftsCountApartFromIntegerAlu) {
  std::mt19937 rng(19);
  for (int seed = 0; seed < 5; ++seed) {
    opcount::counts = {};
    emu::U32<8> raw;
    for (int i = 0; i < 8; ++i) raw.set(i, uint32_t(rng()));
    const opcount::U<8> u(raw), k(uint32_t(rng()) | 1u);
    const opcount::U<8> a = (u >> 3) + (u << k.x[0] % 31);         // 2 shifts by a constant, 1 add
    const opcount::U<8> b = (u ^ k) & (u >> opcount::U<8>(5u)) | k;  // xor, and, or, 1 shift by a vector
    const opcount::I<8> c = opcount::I<8>(u) >> 7;                    // an arithmetic shift
    EXPECT_EQ(opcount::counts[opcount::kShift], 4u);
    EXPECT_EQ(opcount::counts[opcount::kIAlu], 4u);
    for (int i = 0; i < 8; ++i) {
      const uint32_t x = raw[i], kk = k.x[0];
      EXPECT_EQ(a[i], (x >> 3) + (x << kk % 31));
      EXPECT_EQ(b[i], ((x ^ kk) & (x >> 5)) | kk);
      EXPECT_EQ(c[i], int32_t(x) >> 7);
    }
  }
}

// Integer compares and selects of integers or masks are classes of their own (icmp, iselect: SwiftShader runs the pair
// at ~14x an integer add, a float compare and select at ~4x); float compares and selects stay fcmp and select. The
// values are unchanged.
TEST(OpCount, IntegerComparesAndSelectsCountApartFromFloatOnes) {
  std::mt19937 rng(22);
  for (int seed = 0; seed < 5; ++seed) {
    opcount::counts = {};
    emu::U32<8> raw;
    emu::F32<8> rawf;
    for (int i = 0; i < 8; ++i) raw.set(i, uint32_t(rng())), rawf.set(i, float(int32_t(rng() % 2001u) - 1000) * 0.01f);
    const opcount::U<8> u(raw), k{uint32_t(rng())};
    const opcount::F<8> x(rawf), c{float(int32_t(rng() % 2001u) - 1000) * 0.01f};
    const opcount::M<8> lt = u < k;                                         // 1 icmp
    const opcount::U<8> a = select(lt, u, k);                               // 1 iselect
    const opcount::I<8> b = select(opcount::I<8>(u) >= opcount::I<8>(k), opcount::I<8>(u), opcount::I<8>(k));  // icmp, iselect
    const opcount::M<8> fm = x < c;                                         // 1 fcmp
    const opcount::F<8> y = select(fm, x, c);                               // 1 select
    const opcount::M<8> both = select(fm, lt, !lt);                         // a mask op (!) and 1 iselect (masks are integers)
    EXPECT_EQ(opcount::counts[opcount::kICmp], 2u);
    EXPECT_EQ(opcount::counts[opcount::kISel], 3u);
    EXPECT_EQ(opcount::counts[opcount::kFCmp], 1u);
    EXPECT_EQ(opcount::counts[opcount::kSel], 1u);
    EXPECT_EQ(opcount::counts[opcount::kIAlu], 0u);
    EXPECT_EQ(opcount::counts[opcount::kMaskOp], 1u);
    for (int i = 0; i < 8; ++i) {
      const uint32_t xu = raw[i], ku = k.x[0];
      const float xf = rawf[i], cf = c.x[0];
      EXPECT_EQ(a[i], xu < ku ? xu : ku);
      EXPECT_EQ(b[i], int32_t(xu) >= int32_t(ku) ? int32_t(xu) : int32_t(ku));
      EXPECT_EQ(y[i], xf < cf ? xf : cf);
      EXPECT_EQ(both.m.lane(i), xf < cf ? (xu < ku) : !(xu < ku));
    }
  }
}

// The dialect's arrayGet / arraySet (shade/prelude.h) through the counting hooks: one private_read or private_write per
// vector access, the value unchanged; with the schedule on, a read is ready one read latency after its element was and
// the write one write latency after its value (a read of a written element waits for both).
TEST(OpCount, PrivateArrayAccessesCountApartAndKeepTheirValues) {
  std::mt19937 rng(33);
  for (int seed = 0; seed < 5; ++seed) {
    opcount::counts = {};
    emu::F32<8> raw;
    for (int i = 0; i < 8; ++i) raw.set(i, float(int32_t(rng() % 2001u) - 1000) * 0.01f);
    const opcount::F<8> x(raw);
    const opcount::F<8> r = opcount::indexedRead(x);
    const opcount::F<8> w = opcount::indexedWrite(x + r);                  // 1 fadd, 1 write
    const opcount::U<8> u = opcount::indexedRead(opcount::U<8>(uint32_t(rng())));
    const opcount::I<8> k = opcount::indexedWrite(opcount::I<8>(int32_t(rng() % 100u)));
    EXPECT_EQ(opcount::counts[opcount::kPrivRead], 2u);
    EXPECT_EQ(opcount::counts[opcount::kPrivWrite], 2u);
    EXPECT_EQ(opcount::counts[opcount::kFAdd], 1u);
    EXPECT_EQ(opcount::counts[opcount::kIAlu], 0u);
    for (int i = 0; i < 8; ++i) {
      EXPECT_EQ(r[i], raw[i]);
      EXPECT_EQ(w[i], raw[i] + raw[i]);
    }
    (void)u, (void)k;
  }
  opcount::counts = {};
  opcount::sched.on = true;
  opcount::sched.latency = {}, opcount::sched.interval = {};
  opcount::sched.latency[opcount::kPrivRead] = 3.0, opcount::sched.latency[opcount::kPrivWrite] = 5.0;
  opcount::sched.latency[opcount::kFAdd] = 1.0;
  opcount::sched.start();
  const opcount::F<8> v(emu::F32<8>(1.0f), 2.0);               // ready at 2
  const opcount::F<8> written = opcount::indexedWrite(v + v);  // fadd done at 3, the write at 8
  const opcount::F<8> again = opcount::indexedRead(written);   // 11
  opcount::sched.on = false;
  EXPECT_DOUBLE_EQ(written.t, 8.0);
  EXPECT_DOUBLE_EQ(again.t, 11.0);
}

namespace {
// The counted exDiv and exSqrt (the exact-math layer's fast path in the counting build) are one ex_div or ex_sqrt
// operation a vector, with the emulator's own correctly rounded bits: random bit patterns of every class (subnormals,
// zeros, infinities, NaNs, normals), against the scalar build's exDiv / exSqrt (lanes/kernels.h evalMathKernel).
TEST(OpCount, ExactDivisionAndSquareRootAreOneOperationWithTheEmulatorsBits) {
  std::mt19937 rng(19);
  for (int round = 0; round < 20000; ++round) {
    float a[8], b[8], in[24], want[24];
    for (int i = 0; i < 8; ++i) {
      uint32_t ua = rng(), ub = rng();
      if (round % 4 == 1) ua &= 0x807fffffu;  // subnormals and zeros
      if (round % 4 == 2) ub = (ub & 0x80000000u) | (rng() % 3 == 0 ? 0x7f800000u : ub & 0x007fffffu);
      std::memcpy(&a[i], &ua, 4), std::memcpy(&b[i], &ub, 4);
      in[3 * i] = a[i], in[3 * i + 1] = b[i], in[3 * i + 2] = 0.0f;
    }
    opcount::F<8> va(0.0f), vb(0.0f);
    for (int i = 0; i < 8; ++i) va.set(i, a[i]), vb.set(i, b[i]);
    opcount::counts = {};
    const auto q = shadetwin::shade::nativeDiv(va, vb);
    const auto r = shadetwin::shade::nativeSqrt(va);
    ASSERT_TRUE(q.ok && r.ok);
    EXPECT_EQ(opcount::counts[opcount::kExDiv], 1u);
    EXPECT_EQ(opcount::counts[opcount::kExSqrt], 1u);
    uint64_t others = 0;
    for (int k = 0; k < opcount::kTexLookup; ++k) others += k == opcount::kExDiv || k == opcount::kExSqrt ? 0 : opcount::counts[size_t(k)];
    EXPECT_EQ(others, 0u);
    shadetwin::evalMathKernel(0, in, want, 8, 1);  // kMathDiv
    for (int i = 0; i < 8; ++i) ASSERT_EQ(std::memcmp(&want[3 * i], &q.value.x.v[i], 4), 0) << a[i] << " / " << b[i];
    shadetwin::evalMathKernel(1, in, want, 8, 1);  // kMathSqrt
    for (int i = 0; i < 8; ++i) ASSERT_EQ(std::memcmp(&want[3 * i], &r.value.x.v[i], 4), 0) << "sqrt " << a[i];
  }
  // One lane (the scalar drivers' counted build).
  opcount::F<1> x(2.0f), y(3.0f);
  float one[3] = {2.0f, 3.0f, 0.0f}, oneWant[3];
  shadetwin::evalMathKernel(0, one, oneWant, 1, 1);
  EXPECT_EQ(shadetwin::shade::nativeDiv(x, y).value[0], oneWant[0]);
  // Counting the portable routine instead (exactMathMix): the fast path is off, nothing is counted here.
  opcount::counts = {};
  opcount::countPortableExactMath = true;
  EXPECT_FALSE(shadetwin::shade::nativeDiv(x, y).ok);
  EXPECT_FALSE(shadetwin::shade::nativeSqrt(x).ok);
  opcount::countPortableExactMath = false;
  EXPECT_EQ(opcount::counts[opcount::kExDiv] + opcount::counts[opcount::kExSqrt], 0u);
}

// Value numbering (model/op_count.h): an operation whose operands carry the numbers of an earlier one's counts once
// (commuted operands too), where the earlier one dominates it: before the loop, or in the same iteration; a loop
// repeats an expression of unchanged operands in every iteration (gallivm runs no LICM); a new invocation starts over;
// a lane-wise set() is a new value. Off, everything counts. The values are the lanes' own either way.
TEST(OpCount, ValueNumberingCountsARepeatedExpressionOncePerIteration) {
  using F8 = opcount::F<8>;
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> U(-4.0f, 4.0f);
  for (int round = 0; round < 200; ++round) {
    opcount::valueNumbering = round % 2 == 0;
    const bool on = opcount::valueNumbering;
    opcount::vnTable.reset();
    F8 a(0.0f), b(0.0f), c(0.0f);
    for (int i = 0; i < 8; ++i) a.set(i, U(rng)), b.set(i, U(rng)), c.set(i, U(rng));
    opcount::counts = {};
    const F8 p = a * b + c, q = a * b + c, r = b * a;
    EXPECT_EQ(opcount::counts[opcount::kFMul], on ? 1u : 3u);
    EXPECT_EQ(opcount::counts[opcount::kFAdd], on ? 1u : 2u);
    const F8 d = a - b, e = b - a;  // not commutative: two operations
    EXPECT_EQ(opcount::counts[opcount::kFAdd], on ? 3u : 4u);
    for (int i = 0; i < 8; ++i) {
      EXPECT_EQ(p[i], a[i] * b[i] + c[i]);
      EXPECT_EQ(q[i], p[i]);
      EXPECT_EQ(r[i], b[i] * a[i]);
      EXPECT_EQ(d[i], a[i] - b[i]);
      EXPECT_EQ(e[i], b[i] - a[i]);
    }
    {
      opcount::counts = {};
      auto loop = opcount::loopScope(F8(0.0f));
      for (int it = 0; it < 5; ++it) {
        opcount::loopIteration(F8(0.0f));
        const F8 x = a * b;      // computed before the loop: dominates every iteration
        const F8 y = a * c, z = c * a;  // first computed here: once per iteration
        EXPECT_EQ(x[0], a[0] * b[0]);
        EXPECT_EQ(y[3], z[3]);
      }
      EXPECT_EQ(opcount::counts[opcount::kFMul], on ? 5u : 15u);
    }
    opcount::counts = {};
    (void)(a * c);  // after the loop: the loop's product does not reach here
    EXPECT_EQ(opcount::counts[opcount::kFMul], 1u);
    F8 a2 = a;
    a2.set(0, a[0]);  // the same lanes, but a new value (a load)
    (void)(a2 * b);
    EXPECT_EQ(opcount::counts[opcount::kFMul], 2u);
    opcount::startInvocation();
    (void)(a * b);  // the next invocation computes it again
    EXPECT_EQ(opcount::counts[opcount::kFMul], 3u);
    const F8 k1 = a * 2.0f, k2 = a * F8(2.0f), k3 = a * 3.0f;  // constants are numbered by their bits
    EXPECT_EQ(opcount::counts[opcount::kFMul], on ? 5u : 6u);
    EXPECT_EQ(k1[1], k2[1]);
    EXPECT_EQ(k3[1], a[1] * 3.0f);
  }
  opcount::valueNumbering = false;
}
}  // namespace
