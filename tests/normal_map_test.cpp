// Procedural and loaded normal maps for glints (src/inputs/normal_map.*).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <set>
#include <tuple>

#include "inputs/normal_map.h"
#include "util/image_io.h"

using shadetwin::NormalMap;
using shadetwin::NormalMapKind;
using shadetwin::NormalMapSpec;

namespace {

NormalMap gen(NormalMapKind k, uint32_t size, uint32_t seed, float spread = 0.15f) {
  NormalMapSpec s;
  s.kind = k, s.size = size, s.seed = seed, s.spread = spread;
  return shadetwin::generateNormalMap(s);
}

double slope2(const float* n) { return (double(n[0]) * n[0] + double(n[1]) * n[1]) / (double(n[2]) * n[2]); }

// Mean |n(x + 1) - n(x)| over all rows between columns x and x + 1 (mod width).
double columnStep(const NormalMap& m, uint32_t x) {
  double s = 0;
  for (uint32_t y = 0; y < m.height; ++y) {
    const float *a = m.at(x, y), *b = m.at((x + 1) % m.width, y);
    s += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) + double(a[1] - b[1]) * (a[1] - b[1]) + double(a[2] - b[2]) * (a[2] - b[2]));
  }
  return s / m.height;
}

std::string tmp(const std::string& name) { return (std::filesystem::temp_directory_path() / name).string(); }

void writeRaw(const std::string& path, uint32_t w, uint32_t h, int channels, const std::vector<float>& px) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(int(w), int(h), channels, path.ends_with(".png") ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open(path, spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
  out->close();
}

}  // namespace

TEST(NormalMap, EveryKindIsUnitUpwardDeterministicAndSeeded) {
  for (NormalMapKind k : {NormalMapKind::Flat, NormalMapKind::Flakes, NormalMapKind::Scratches, NormalMapKind::Brushed,
                          NormalMapKind::Bumps})
    for (uint32_t size : {1u, 7u, 64u, 256u}) {
      const NormalMap a = gen(k, size, 3), b = gen(k, size, 3), c = gen(k, size, 4);
      ASSERT_EQ(a.n.size(), 3u * size * size);
      EXPECT_EQ(std::memcmp(a.n.data(), b.n.data(), a.n.size() * 4), 0) << shadetwin::normalMapKindName(k) << " " << size;
      for (size_t i = 0; i < a.n.size(); i += 3) {
        const double l = std::sqrt(double(a.n[i]) * a.n[i] + double(a.n[i + 1]) * a.n[i + 1] + double(a.n[i + 2]) * a.n[i + 2]);
        ASSERT_NEAR(l, 1.0, 1e-6);
        ASSERT_GT(a.n[i + 2], 0.5f);
      }
      if (k != NormalMapKind::Flat && size >= 64) {
        EXPECT_NE(std::memcmp(a.n.data(), c.n.data(), a.n.size() * 4), 0) << shadetwin::normalMapKindName(k);
      }
    }
  EXPECT_EQ(shadetwin::normalMapKind("brushed"), NormalMapKind::Brushed);
  EXPECT_THROW(shadetwin::normalMapKind("velvet"), std::invalid_argument);
  EXPECT_THROW(gen(NormalMapKind::Bumps, 0, 1), std::invalid_argument);
  EXPECT_THROW(gen(NormalMapKind::Bumps, 64, 1, -0.1f), std::invalid_argument);
}

TEST(NormalMap, FlakesAreVoronoiCellsWithAHalfNormalTilt) {
  // 32 x 32 cells at 256^2: nearly every cell owns texels; over the cells' normals the mean tilt is
  // spread sqrt(2/pi) (half-normal); and the map tiles: across the wrap seam neighbouring texels are
  // as often in one cell as across an interior column.
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    NormalMapSpec s;
    s.kind = NormalMapKind::Flakes, s.size = 256, s.seed = seed, s.spread = 0.2f, s.cells = 32;
    const NormalMap m = shadetwin::generateNormalMap(s);
    std::set<std::tuple<float, float, float>> cells;
    for (size_t i = 0; i < m.n.size(); i += 3) cells.insert({m.n[i], m.n[i + 1], m.n[i + 2]});
    EXPECT_LE(cells.size(), 32u * 32u);
    EXPECT_GE(cells.size(), 1000u) << seed;
    double tilt = 0;
    for (const auto& [x, y, z] : cells) tilt += std::acos(double(z));
    tilt /= double(cells.size());
    EXPECT_NEAR(tilt, 0.2 * std::sqrt(2.0 / std::numbers::pi), 0.012) << seed;
    // Per column pair (x, x + 1 mod 256), the rows whose two texels share a cell: the seam's count
    // lies within the interior pairs' range (cells are 8 texels wide: ~7 of 8 rows share one).
    size_t lo = 256, hi = 0, seam = 0;
    for (uint32_t x = 0; x < 256; ++x) {
      size_t same = 0;
      for (uint32_t y = 0; y < 256; ++y) same += std::memcmp(m.at(x, y), m.at((x + 1) % 256, y), 12) == 0;
      if (x == 255) seam = same;
      else lo = std::min(lo, same), hi = std::max(hi, same);
    }
    EXPECT_GE(seam, lo) << seed;
    EXPECT_LE(seam, hi) << seed;
    EXPECT_GT(lo, 128u) << seed;
  }
}

TEST(NormalMap, ScratchesAreGroovesAcrossTheirLine) {
  // One scratch: every tilted texel is tilted by exactly `spread`, all along one axis (the scratch's
  // normal), both ways (the two walls of the groove), and about as many each way.
  for (uint32_t seed = 1; seed <= 8; ++seed) {
    NormalMapSpec s;
    s.kind = NormalMapKind::Scratches, s.size = 256, s.seed = seed, s.spread = 0.3f, s.count = 1, s.width = 4.0f;
    const NormalMap m = shadetwin::generateNormalMap(s);
    size_t tilted = 0, pos = 0;
    double ax = 0, ay = 0;
    for (size_t i = 0; i < m.n.size(); i += 3) {
      if (m.n[i + 2] == 1.0f) continue;
      EXPECT_NEAR(std::acos(double(m.n[i + 2])), 0.3, 1e-5);
      if (tilted++ == 0) ax = m.n[i], ay = m.n[i + 1];
      const double cross = ax * m.n[i + 1] - ay * m.n[i], dot = ax * m.n[i] + ay * m.n[i + 1];
      EXPECT_NEAR(cross, 0.0, 1e-6);
      pos += dot > 0;
    }
    // length 0.1 to 0.6 of 256, width 4: 100 to 620 texels
    EXPECT_GT(tilted, 90u) << seed;
    EXPECT_LT(tilted, 700u) << seed;
    EXPECT_NEAR(double(pos) / double(tilted), 0.5, 0.1) << seed;
  }
  NormalMapSpec many;
  many.kind = NormalMapKind::Scratches, many.size = 512, many.count = 40;
  const NormalMap m = shadetwin::generateNormalMap(many);
  size_t tilted = 0;
  for (size_t i = 2; i < m.n.size(); i += 3) tilted += m.n[i] != 1.0f;
  EXPECT_GT(tilted, m.n.size() / 3 / 100);  // scratches, not a dense field: 1-10% of the texels
  EXPECT_LT(tilted, m.n.size() / 3 / 10);
}

TEST(NormalMap, NoisesHaveTheirRmsSlopeAnisotropyAndTile) {
  for (uint32_t seed = 1; seed <= 4; ++seed)
    for (NormalMapKind k : {NormalMapKind::Brushed, NormalMapKind::Bumps}) {
      const NormalMap m = gen(k, 256, seed, 0.2f);
      double ms = 0, vx = 0, vy = 0;
      for (size_t i = 0; i < m.n.size(); i += 3) {
        ms += slope2(&m.n[i]);
        vx += double(m.n[i]) * m.n[i], vy += double(m.n[i + 1]) * m.n[i + 1];
      }
      const double texels = double(m.n.size() / 3);
      EXPECT_NEAR(std::sqrt(ms / texels), 0.2, 2e-4) << seed;
      if (k == NormalMapKind::Brushed) {
        EXPECT_GT(vy, 20.0 * vx) << seed;  // the grooves run along u: slopes across them (v)
      } else {
        EXPECT_GT(vy / vx, 0.5) << seed;
        EXPECT_LT(vy / vx, 2.0) << seed;
      }
      // Seamless: the step across the wrap seam lies within the steps between interior columns.
      double lo = 1e9, hi = 0;
      for (uint32_t x = 0; x + 1 < 256; ++x) lo = std::min(lo, columnStep(m, x)), hi = std::max(hi, columnStep(m, x));
      EXPECT_GE(columnStep(m, 255), lo) << seed;
      EXPECT_LE(columnStep(m, 255), hi) << seed;
    }
}

TEST(NormalMap, LoadsFilesAndNamesTheProblem) {
  const NormalMap g = gen(NormalMapKind::Bumps, 64, 9, 0.4f);
  std::vector<float> enc(3 * 64 * 64), raw(g.n.begin(), g.n.end());
  for (size_t i = 0; i < enc.size(); ++i) enc[i] = 0.5f * (g.n[i] + 1.0f);
  const std::string png = tmp("shadetwin_nm.png"), exr = tmp("shadetwin_nm.exr");
  writeRaw(png, 64, 64, 3, enc);
  writeRaw(exr, 64, 64, 3, raw);  // float with negative values: read as the components
  const NormalMap a = shadetwin::loadNormalMap(png), b = shadetwin::loadNormalMap(exr);
  ASSERT_EQ(a.width, 64u);
  ASSERT_EQ(b.height, 64u);
  double worstA = 0, worstB = 0;
  for (size_t i = 0; i < g.n.size(); ++i) {
    worstA = std::max(worstA, std::fabs(double(a.n[i]) - g.n[i]));
    worstB = std::max(worstB, std::fabs(double(b.n[i]) - g.n[i]));
  }
  EXPECT_LT(worstA, 0.01);  // 8-bit quantisation, renormalised
  EXPECT_GT(worstA, 1e-4);
  EXPECT_LT(worstB, 1e-6);

  auto message = [](const std::string& path) {
    try {
      shadetwin::loadNormalMap(path);
    } catch (const shadetwin::FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing = tmp("shadetwin_no_such_map.png");
  EXPECT_NE(message(missing).find(missing), std::string::npos);
  const std::string gray = tmp("shadetwin_nm_gray.exr");
  writeRaw(gray, 4, 4, 1, std::vector<float>(16, 0.5f));
  EXPECT_NE(message(gray).find("three channels"), std::string::npos) << message(gray);
  std::vector<float> down(3 * 4 * 4, 0.0f);
  for (size_t i = 2; i < down.size(); i += 3) down[i] = 1.0f;
  down[3 * 6 + 2] = -1.0f;  // texel (2, 1) points into the surface
  const std::string bad = tmp("shadetwin_nm_down.exr");
  writeRaw(bad, 4, 4, 3, down);
  EXPECT_NE(message(bad).find("texel (2, 1)"), std::string::npos) << message(bad);
  EXPECT_NE(message(bad).find(bad), std::string::npos);
}
