// The NDF histogram SAT (src/inputs/ndf_histogram.*, src/shade/ndf_histogram.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "inputs/ndf_histogram.h"
#include "inputs/normal_map.h"
#include "lanes/instantiate.h"

using shadetwin::NdfBinningSpec;
using shadetwin::NormalMap;
using shadetwin::NormalMapKind;

namespace {

NormalMap gen(NormalMapKind k, uint32_t size, uint32_t seed, float spread) {
  shadetwin::NormalMapSpec s;
  s.kind = k, s.size = size, s.seed = seed, s.spread = spread, s.cells = std::max(1u, size / 8);
  return shadetwin::generateNormalMap(s);
}

// A w x h map cut from a generated square one (the generators make square maps).
NormalMap crop(const NormalMap& m, uint32_t w, uint32_t h) {
  NormalMap c;
  c.width = w, c.height = h;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) c.n.insert(c.n.end(), m.at(x, y), m.at(x, y) + 3);
  return c;
}

std::vector<uint32_t> bruteCounts(const NormalMap& m, const NdfBinningSpec& b, int64_t x0, int64_t y0, int64_t x1, int64_t y1) {
  std::vector<uint32_t> c(size_t(b.rings) * b.sectors, 0);
  for (int64_t y = y0; y <= y1; ++y)
    for (int64_t x = x0; x <= x1; ++x) {
      const int64_t u = ((x % m.width) + m.width) % m.width, v = ((y % m.height) + m.height) % m.height;
      ++c[shadetwin::ndfBinOf(b, m.at(uint32_t(u), uint32_t(v)))];
    }
  return c;
}

}  // namespace

TEST(NdfHistogram, BinsFollowThetaAndPhi) {
  const NdfBinningSpec b;  // 9 x 32 over [0, pi/2]
  const float up[3] = {0, 0, 1};
  EXPECT_EQ(shadetwin::ndfBinOf(b, up), 0u);
  auto dir = [](double thetaDeg, double phiDeg, float n[3]) {
    const double t = thetaDeg * std::numbers::pi / 180, p = phiDeg * std::numbers::pi / 180;
    n[0] = float(std::sin(t) * std::cos(p)), n[1] = float(std::sin(t) * std::sin(p)), n[2] = float(std::cos(t));
  };
  float n[3];
  dir(45.5, 100.0, n);  // ring 4 (40-50 degrees), sector 8 (90-101.25 degrees)
  EXPECT_EQ(shadetwin::ndfBinOf(b, n), 4u * 32 + 8);
  dir(89.9, 359.9, n);
  EXPECT_EQ(shadetwin::ndfBinOf(b, n), 8u * 32 + 31);
  dir(120.0, 10.0, n);  // below the surface: the last ring
  EXPECT_EQ(shadetwin::ndfBinOf(b, n), 8u * 32 + 0);
  // Against double precision for random normals: the same bin except within 1e-5 of a boundary.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  size_t differ = 0;
  for (int i = 0; i < 200000; ++i) {
    const double t = std::acos(1.0 - U(rng)), p = 2 * std::numbers::pi * U(rng);
    float m[3] = {float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t))};
    const double th = std::acos(double(m[2])), ph = std::fmod(std::atan2(double(m[1]), double(m[0])) + 2 * std::numbers::pi, 2 * std::numbers::pi);
    const double ft = th * 9 / (std::numbers::pi / 2), fp = ph * 32 / (2 * std::numbers::pi);
    const uint32_t expect = uint32_t(std::min(8.0, std::floor(ft))) * 32 + uint32_t(std::min(31.0, std::floor(fp)));
    if (shadetwin::ndfBinOf(b, m) != expect) {
      ++differ;
      const double dt = std::fabs(ft - std::round(ft)), dp = std::fabs(fp - std::round(fp));
      EXPECT_LT(std::min(dt, dp), 1e-4) << t << " " << p;
    }
  }
  EXPECT_LT(differ, 20u);
}

TEST(NdfHistogram, BoxCountsEqualBruteForceWithWrapAround) {
  // Maps of several kinds and sizes (square, not powers of two, cropped non-square), random boxes:
  // single texels, boxes crossing the tile seam, starting at negative coordinates, wider and taller
  // than the map (whole periods), up to 65,535 texels.
  std::mt19937 rng(11);
  int cases = 0;
  for (uint32_t seed = 1; seed <= 6; ++seed)
    for (NormalMapKind k : {NormalMapKind::Flakes, NormalMapKind::Bumps, NormalMapKind::Scratches}) {
      const uint32_t sizes[] = {37, 64, 100};
      NormalMap m = gen(k, sizes[seed % 3], seed, 0.35f);
      if (seed % 2 == 0) m = crop(m, m.width - 5, m.height - 11);
      NdfBinningSpec b;
      if (seed == 3) b.rings = 4, b.sectors = 8, b.thetaMax = 0.6f;
      const shadetwin::NdfSat sat = shadetwin::buildNdfSat(m, b);
      std::uniform_int_distribution<int> pos(-300, 300), side(1, 250);
      std::vector<uint32_t> got(size_t(b.rings) * b.sectors);
      for (int i = 0; i < 40; ++i) {
        int64_t x0 = pos(rng), y0 = pos(rng), w = i < 5 ? 1 : side(rng), h = i < 5 ? 1 : side(rng);
        if (i == 5) x0 = m.width - 2, y0 = m.height - 3, w = 5, h = 7;  // across both seams
        if (w * h >= 65536) h = 65535 / w;
        shadetwin::ndfBoxCounts(sat, x0, y0, x0 + w - 1, y0 + h - 1, got.data());
        const auto want = bruteCounts(m, b, x0, y0, x0 + w - 1, y0 + h - 1);
        ASSERT_EQ(got, want) << "seed " << seed << " box " << x0 << "," << y0 << " " << w << "x" << h;
        uint64_t sum = 0;
        for (uint32_t c : got) sum += c;
        EXPECT_EQ(sum, uint64_t(w * h));
        ++cases;
      }
    }
  EXPECT_EQ(cases, 6 * 3 * 40);
}

TEST(NdfHistogram, ExactUpToTheModulusAndRefusesLargerBoxes) {
  // A flat map: every texel in bin 0. A box of 65,535 texels counts 65,535 (the largest value the
  // 16-bit modular table returns exactly); a small tiled map under a box of many periods too.
  const NormalMap flat = gen(NormalMapKind::Flat, 300, 1, 0.0f);
  const NdfBinningSpec b;
  const shadetwin::NdfSat sat = shadetwin::buildNdfSat(flat, b);
  EXPECT_EQ(sat.storedRings, 1u);
  std::vector<uint32_t> got(288);
  shadetwin::ndfBoxCounts(sat, 10, 20, 10 + 255 - 1, 20 + 257 - 1, got.data());
  EXPECT_EQ(got[0], 65535u);
  const NormalMap small = gen(NormalMapKind::Flakes, 16, 2, 0.4f);
  const shadetwin::NdfSat s2 = shadetwin::buildNdfSat(small, b);
  shadetwin::ndfBoxCounts(s2, -7, 3, -7 + 16 * 12 - 1, 3 + 16 * 21 - 1, got.data());  // 12 x 21 whole tiles
  for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], s2.totals[i] * 12 * 21) << i;
  EXPECT_THROW(shadetwin::ndfBoxCounts(sat, 0, 0, 255, 255, got.data()), std::invalid_argument);  // 65,536
  EXPECT_THROW(shadetwin::ndfBoxCounts(sat, 5, 0, 4, 0, got.data()), std::invalid_argument);      // empty
}

TEST(NdfHistogram, StoresOnlyUsedRingsAndFailsEarlyWhenTooLarge) {
  // Narrow flakes (tilt scale 0.1 rad) use the first rings only; the table holds those: bytes =
  // stored rings x 32 x W x H x 2, and the totals count every texel once.
  const NormalMap m = gen(NormalMapKind::Flakes, 128, 4, 0.1f);
  const shadetwin::NdfSat sat = shadetwin::buildNdfSat(m, NdfBinningSpec{});
  uint64_t total = 0;
  for (uint32_t c : sat.totals) total += c;
  EXPECT_EQ(total, 128u * 128u);
  EXPECT_GE(sat.storedRings, 2u);
  EXPECT_LE(sat.storedRings, 4u);
  EXPECT_EQ(sat.bytes(), size_t(sat.storedRings) * 32 * 128 * 128 * 2);
  EXPECT_EQ(sat.fullBytes(), size_t(9) * 32 * 128 * 128 * 2);
  EXPECT_EQ(shadetwin::ndfSatFullBytes(1024, 1024, NdfBinningSpec{}), size_t(576) << 20);  // the paper's 576 MB
  for (int32_t t = 0; t < 9; ++t) {
    bool used = false;
    for (uint32_t p = 0; p < 32; ++p) used = used || sat.totals[size_t(t) * 32 + p] > 0;
    EXPECT_EQ(sat.slot[size_t(t)] >= 0, used) << t;
  }
  try {
    shadetwin::buildNdfSat(m, NdfBinningSpec{}, 1 << 20);
    FAIL() << "no error";
  } catch (const std::length_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("would need"), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::to_string(sat.bytes()) + " bytes"), std::string::npos) << msg;
  }
  NdfBinningSpec bad;
  bad.sectors = 0;
  EXPECT_THROW(shadetwin::buildNdfSat(m, bad), std::invalid_argument);
  bad = NdfBinningSpec{};
  bad.thetaMax = 4.0f;
  EXPECT_THROW(shadetwin::buildNdfSat(m, bad), std::invalid_argument);
}

TEST(NdfHistogram, SharedBoxCountsFromTheTextureEqualTheHost) {
  // The shaders' lookup (shade/ndf_histogram.h ndfBoxCounts8 on the RGBA32UI texture), scalar and
  // 8-lane builds, against the host's counts: maps of several sizes (smaller than a box, so whole
  // periods occur), boxes anywhere, 6 bins per sector group padded (P = 12: groups 2, sectors 12-15 0).
  namespace sc = shadetwin::shade::scalar;
  namespace x8 = shadetwin::shade::x8;
  std::mt19937 rng(17);
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    const uint32_t size = seed == 1 ? 13 : 40 * seed;
    const NormalMap m = gen(NormalMapKind::Bumps, size, seed, 0.45f);
    NdfBinningSpec b;
    if (seed == 2) b.rings = 5, b.sectors = 12, b.thetaMax = 0.9f;
    const shadetwin::NdfSat sat = shadetwin::buildNdfSat(m, b);
    const emu::Texture tex = shadetwin::ndfSatTexture(sat);
    const shadetwin::shade::USampler2DArray s{&tex};
    const int groups = int(shadetwin::ndfSatGroups(b));
    ASSERT_EQ(tex.width(), size * uint32_t(groups));
    const float invW = 1.0f / float(size), invH = 1.0f / float(size);
    std::uniform_int_distribution<int> pos(-3000, 3000), side(1, 255);
    std::vector<uint32_t> host(size_t(b.rings) * b.sectors);
    for (int i = 0; i < 64; ++i) {
      int x0[8], y0[8], x1[8], y1[8];
      for (int l = 0; l < 8; ++l) x0[l] = pos(rng), y0[l] = pos(rng), x1[l] = x0[l] + side(rng) - 1, y1[l] = y0[l] + side(rng) - 1;
      emu::I32<8> X0, Y0, X1, Y1;
      for (int l = 0; l < 8; ++l) X0.set(l, x0[l]), Y0.set(l, y0[l]), X1.set(l, x1[l]), Y1.set(l, y1[l]);
      for (uint32_t t = 0; t < b.rings; ++t) {
        if (sat.slot[t] < 0) continue;
        for (int g = 0; g < groups; ++g) {
          const x8::UintTexel4 v8 = x8::ndfBoxCounts8(s, sat.slot[t], g, groups, int(size), int(size), invW, invH, X0, Y0, X1, Y1);
          for (int l = 0; l < 8; ++l) {
            shadetwin::ndfBoxCounts(sat, x0[l], y0[l], x1[l], y1[l], host.data());
            const sc::UintTexel4 v = sc::ndfBoxCounts8(s, sat.slot[t], g, groups, int(size), int(size), invW, invH, x0[l], y0[l], x1[l], y1[l]);
            const uint32_t packed[4] = {v.x, v.y, v.z, v.w}, lanes[4] = {v8.x[l], v8.y[l], v8.z[l], v8.w[l]};
            for (int j = 0; j < 4; ++j) {
              ASSERT_EQ(packed[j], lanes[j]) << seed << " " << i << " lane " << l;
              for (int h = 0; h < 2; ++h) {
                const uint32_t p = uint32_t(g) * 8 + uint32_t(2 * j + h);
                const uint32_t want = p < b.sectors ? host[size_t(t) * b.sectors + p] : 0u;
                ASSERT_EQ((packed[j] >> (16 * h)) & 0xffffu, want) << "seed " << seed << " box " << i << " ring " << t << " sector " << p;
              }
            }
          }
        }
      }
    }
  }
}
