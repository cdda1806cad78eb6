// Materials (inputs/material.h, shade/material.h): the record layout the kernels read, material maps
// as texture-array layers, the maps' LOD against the Vulkan scale-factor formula, and spatially
// varying materials against the reference renderer; Lafortune lobes from scene files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include "emu/device_profile.h"
#include "emu/format.h"
#include "util/image_io.h"
#include "passes/mips.h"
#include "passes/shade.h"
#include "inputs/material.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "lanes/instantiate.h"
#include "scene/scene.h"

namespace {
namespace sc = shadetwin::shade::scalar;
const emu::DeviceProfile& dev() { return emu::lavapipeProfile(); }
std::string src(const std::string& p) { return std::string(SHADETWIN_SOURCE_DIR) + "/" + p; }

TEST(MaterialRecords, MapLayersAndLafortuneLobes) {
  const shadetwin::Scene t = shadetwin::loadScene(src("scenes/textured.json"));
  const auto files = shadetwin::materialMapFiles(t);
  ASSERT_EQ(files.size(), 2u);  // checker, ramp: one layer per file, shared between materials
  EXPECT_NE(files[0].find("checker.exr"), std::string::npos);
  const auto r = shadetwin::materialRecords(t, true);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].maps[0], 1u);
  EXPECT_EQ(r[0].maps[1], 0u);
  EXPECT_EQ(r[0].maps[2], 0u);
  EXPECT_EQ(r[1].maps[0], 0u);
  EXPECT_EQ(r[1].maps[2], 2u);
  EXPECT_EQ(r[2].maps[1], 1u);
  EXPECT_EQ(r[2].maps[2], 2u);
  EXPECT_EQ(r[2].kind[0], sc::kBrdfWard);
  EXPECT_FLOAT_EQ(r[2].brdf[1], 0.3f);
  EXPECT_FLOAT_EQ(r[2].brdf[2], 0.1f);

  const shadetwin::Scene m = shadetwin::loadScene(src("scenes/materials.json"));
  const auto q = shadetwin::materialRecords(m, true);
  const shadetwin::MaterialGpu& lf = q.back();  // the two-lobe Lafortune sphere
  EXPECT_EQ(lf.kind[0], sc::kBrdfLafortune);
  EXPECT_FLOAT_EQ(lf.lobe0[0], -1.01f);
  EXPECT_FLOAT_EQ(lf.lobe0[3], 60.0f);
  EXPECT_FLOAT_EQ(lf.rho[0], 8.9f);
  EXPECT_FLOAT_EQ(lf.lobe1[2], 0.6f);
  EXPECT_FLOAT_EQ(lf.lobe1[3], 6.0f);
  EXPECT_FLOAT_EQ(lf.rho[1], 0.6f);
  for (const auto& rec : q) {
    EXPECT_EQ(rec.maps[0] + rec.maps[1] + rec.maps[2], 0u);
    if (rec.kind[0] != sc::kBrdfLafortune) {
      EXPECT_EQ(rec.rho[0] + rec.rho[1], 0.0f);  // no stray lobes
    }
  }

  // The mirror technique reads no maps: a scene with maps is an error naming material and technique.
  shadetwin::Scene mirror = t;
  mirror.technique = "mirror";
  try {
    shadetwin::materialRecords(mirror, false);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("checker_plastic"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mirror"), std::string::npos) << e.what();
  }
}

TEST(MaterialMaps, SizesMustMatchAndTheErrorNamesTheFile) {
  const auto dir = std::filesystem::temp_directory_path() / "shadetwin_material_test";
  std::filesystem::create_directories(dir);
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  shadetwin::writeExr(a, 8, 8, std::vector<float>(8 * 8 * 4, 0.5f));
  shadetwin::writeExr(b, 8, 4, std::vector<float>(8 * 4 * 4, 0.5f));
  shadetwin::Scene s;
  s.materials.resize(2);
  s.materials[0].name = "one", s.materials[0].diffuseMap = a;
  s.materials[1].name = "two", s.materials[1].specularMap = b;
  try {
    shadetwin::loadMaterialMaps(s);
    FAIL() << "no error";
  } catch (const shadetwin::FileError& e) {
    EXPECT_NE(std::string(e.what()).find(b), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("8x4"), std::string::npos) << e.what();
  }
  shadetwin::writeExr(b, 8, 8, std::vector<float>(8 * 8 * 4, 0.25f));
  const shadetwin::MaterialMapImages m = shadetwin::loadMaterialMaps(s);
  EXPECT_EQ(m.layers, 2u);
  const emu::Texture tex = shadetwin::materialMapsEmu(m);
  EXPECT_EQ(tex.levelCount(), 4u);  // 8, 4, 2, 1
  EXPECT_EQ(tex.loadFloat(3, 1, 0, 0).r, 0.25f);  // layer 1's 1x1 level: the average of a constant
  std::filesystem::remove_all(dir);
}

TEST(MapLod, MatchesTheVulkanScaleFactor) {
  // lambda = log2(max(|(du/dx w, dv/dx h)|, |(du/dy w, dv/dy h)|)) (Vulkan spec, isotropic scale
  // factor), clamped below at 0; the shared exact-math version within 2^-16 of the double formula.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f), E(-14.0f, 2.0f);
  const float w = 512, h = 256;
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    const float d[4] = {U(rng) * std::exp2(E(rng)), U(rng) * std::exp2(E(rng)), U(rng) * std::exp2(E(rng)),
                        U(rng) * std::exp2(E(rng))};
    const double rx = std::hypot(double(d[0]) * w, double(d[1]) * h), ry = std::hypot(double(d[2]) * w, double(d[3]) * h);
    const double ref = std::max(0.0, std::log2(std::max(rx, ry)));
    const float got = sc::mapLod(shadetwin::shade::V4<float>(d[0], d[1], d[2], d[3]), shadetwin::shade::V2<float>(w, h));
    worst = std::max(worst, std::fabs(double(got) - ref));
  }
  EXPECT_LT(worst, 1.0 / 65536);
  EXPECT_EQ(sc::mapLod(shadetwin::shade::V4<float>(0, 0, 0, 0), shadetwin::shade::V2<float>(w, h)), 0.0f);
  EXPECT_EQ(sc::mapLod(shadetwin::shade::V4<float>(1.0f / 2048, 0, 0, 1.0f / 2048), shadetwin::shade::V2<float>(w, h)), 0.0f);
  EXPECT_EQ(sc::mapLod(shadetwin::shade::V4<float>(8.0f / 512, 0, 0, 0), shadetwin::shade::V2<float>(w, h)), 3.0f);
}

// The textured scene with ks = 0 under a constant environment L: every sphere pixel is kd * map * L
// (the SH irradiance of a constant map is L to 2e-5). The FIS pass filters the map over the pixel's
// footprint (trilinear at the LOD of the G-buffer's uv derivatives); the expectation point-samples it
// at the pixel's uv as the reference renderer does (mapBilinear: double, level 0). They agree away
// from checker edges, which catches a flipped or shifted uv or a wrong layer; without the map most
// pixels are far off.
TEST(MaterialMaps, DiffuseMapIsKdTimesMapTimesL) {
  shadetwin::Scene s = shadetwin::loadScene(src("scenes/textured.json"));
  s.width = 576, s.height = 192;  // checker squares about 12 pixels wide: filtering blurs only their edges
  for (shadetwin::Material& m : s.materials) m.specular = {0, 0, 0}, m.diffuseMap = s.materials[0].diffuseMap;
  const uint32_t W = 256, H = 128;
  const float L = 2.0f;
  std::vector<float> level0(size_t(W) * H * 4, L);
  const emu::Texture env = shadetwin::packTexture(emu::Format::RGBA32F, W, H, 1, shadetwin::mipChainCpu(level0, W, H, 1, 8));
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev());
  const std::vector<float> fis = shadetwin::shadeEmu(s, g, shadetwin::shadeInputsEmu(s, env, dev()), dev());
  const shadetwin::MaterialMapImages map = shadetwin::loadMaterialMaps(s);
  ASSERT_NE(shadetwin::materialMapFiles(s)[0].find("checker"), std::string::npos);  // layer 0
  std::vector<double> rel, relPlain;
  for (size_t p = 0; p < size_t(s.width) * s.height; ++p) {
    const float* t = &g.texels[p * shadetwin::kGbufFloats];
    if (t[3] == 0.0f) continue;
    const shadetwin::Material& m = s.materials[sc::materialSlot(t[3], 3)];
    for (int k = 0; k < 3; ++k) {
      const double want = m.diffuse[size_t(k)] * shadetwin::mapBilinear(map, 0, t[7], t[11], k) * L;
      rel.push_back(std::fabs(fis[4 * p + size_t(k)] - want) / want);
      relPlain.push_back(std::fabs(m.diffuse[size_t(k)] * L - want) / want);
    }
  }
  ASSERT_GT(rel.size(), 30000u);
  std::sort(rel.begin(), rel.end());
  std::sort(relPlain.begin(), relPlain.end());
  // Measured: 60% of channels exact to 1e-4 (inside the squares), 70th percentile 1.1%, 90th 25% (the
  // filtered checker edges and silhouettes, where the footprint is large).
  EXPECT_LT(rel[rel.size() / 2], 1e-3);
  EXPECT_LT(rel[rel.size() * 7 / 10], 0.03);
  EXPECT_GT(relPlain[rel.size() / 2], 0.3);   // the map matters
}

TEST(MaterialMaps, RoughnessMapChangesOnlyTheGlossyTerm) {
  // The ramp metal's pixels change with its roughness map (alpha times the ramp); the background and
  // the plastic sphere (no roughness map) stay bit-identical.
  shadetwin::Scene s = shadetwin::loadScene(src("scenes/textured.json"));
  s.width = 192, s.height = 64;
  s.fisSamples = 16;
  std::ostringstream log;
  shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev());
  const auto with = shadetwin::shadeEmu(s, g, shadetwin::shadeInputsEmu(s, *env.texture, dev()), dev());
  shadetwin::Scene c = s;
  for (shadetwin::Material& m : c.materials) m.roughnessMap.clear();
  const auto without = shadetwin::shadeEmu(c, g, shadetwin::shadeInputsEmu(c, *env.texture, dev()), dev());
  size_t changed = 0, metal = 0;
  for (size_t p = 0; p < size_t(s.width) * s.height; ++p) {
    const float id = g.texels[p * shadetwin::kGbufFloats + 3];
    if (sc::materialSlot(id, 3) != 1 || id == 0.0f) {
      if (id == 0.0f || sc::materialSlot(id, 3) == 0) {  // background and the plastic (no roughness map): unchanged
        for (int k = 0; k < 3; ++k) ASSERT_EQ(with[4 * p + size_t(k)], without[4 * p + size_t(k)]) << p;
      }
      continue;
    }
    ++metal;
    changed += with[4 * p + 1] != without[4 * p + 1];
  }
  EXPECT_GT(metal, 500u);
  EXPECT_GT(changed, metal * 9 / 10);
}

}  // namespace
