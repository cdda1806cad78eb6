// The performance model's coverage (issue 19): every device pass an emulated frame runs has a counted run
// (model/pass_counts.h countFrame), the counted runs give the emulator's bits, and the counts are the work's real
// shape (lanes, helpers, dispatches). A pass added to the frame without a counting run fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "model/pass_counts.h"
#include "passes/gbuffer.h"
#include "passes/shade.h"
#include "passes/visibility.h"
#include "scene/scene.h"
#include "util/pass_log.h"

namespace {
using namespace shadetwin;

struct Case {
  const char* scene;
  const char* technique;  // "" : the scene's
};

Scene small(const Case& c) {
  Scene s = loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/" + c.scene);
  s.width = 40, s.height = 24;
  if (*c.technique) s.technique = c.technique;
  s.fisSamples = std::min(s.fisSamples, 8u);
  s.misSamples = std::min(s.misSamples, 4u);
  s.glintOrder = std::min(s.glintOrder, 6u);  // a small lighting table: the counted run is one thread
  s.glintViewRings = std::min(s.glintViewRings, 9u), s.glintViewSectors = std::min(s.glintViewSectors, 16u);
  return s;
}

// The passes the emulated frame runs (cli/render.cpp's emulator branch), by the names they note.
std::set<std::string> framePasses(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev) {
  PassLog log;
  const GBuffer g = gbufferEmu(scene, dev);
  const ShadeInputs in = shadeInputsEmu(scene, env, dev);
  std::unique_ptr<VisibilityImage> vis;
  if (in.visibility) vis = std::make_unique<VisibilityImage>(visibilityEmu(scene, g, *in.visibility, dev));
  if (scene.technique != "glints-gxd") shadeEmu(scene, g, in, dev, vis.get());
  return {log.names.begin(), log.names.end()};
}

class PassCountsCoverage : public ::testing::TestWithParam<Case> {};

TEST_P(PassCountsCoverage, EveryPassTheFrameRunsIsCountedWithTheEmulatorsBits) {
  const Scene scene = small(GetParam());
  std::ostringstream quiet;
  const EnvironmentMap env = loadEnvironment(scene.environment, quiet);
  for (const emu::DeviceProfile* dev : {&emu::lavapipeProfile(), &emu::swiftshaderProfile()}) {
    const std::set<std::string> ran = framePasses(scene, *env.texture, *dev);
    const model::FrameCounts f = model::countFrame(scene, *env.texture, *dev);
    std::set<std::string> counted;
    for (const model::PassCounts& p : f.passes) {
      counted.insert(p.pass);
      double alu = 0;
      for (int k = 0; k < opcount::kTexLookup; ++k) alu += p.ops[size_t(k)];
      EXPECT_GT(alu, 0.0) << p.pass;  // a counted run that counted nothing is not a counting run
      EXPECT_GT(p.invocations, 0u) << p.pass;
      EXPECT_GT(p.dispatches, 0u) << p.pass;
      // Local arrays at run-time indices (arrayGet / arraySet) are the glints kernels' alone.
      const bool glintsKernel = p.pass == "glint-lighting" || (p.pass == "shade" && scene.technique == "glints");
      EXPECT_EQ(p.ops[opcount::kPrivWrite] > 0.0, glintsKernel) << p.pass;
      EXPECT_EQ(p.ops[opcount::kPrivRead] > 0.0, glintsKernel) << p.pass;
      // Compute passes name the size of the module they run (the code-size term); raster passes none.
      EXPECT_EQ(p.moduleWords > 0, p.triangles == 0) << p.pass;
      EXPECT_GE(p.moduleWords, p.pipelines ? p.pipelineWords / p.pipelines : 0) << p.pass;
      // A pass whose counted run iterated a loop runs a module with a loop at that depth (the loop-state term's values).
      for (int d = 0; d < model::kLoopDepths; ++d)
        if (p.ops[size_t(opcount::kLoop1 + d)] > 0.0) {
          EXPECT_GT(p.loopCarried[size_t(d)], 0u) << p.pass << " depth " << d + 1;
        }
    }
    EXPECT_EQ(ran, counted) << GetParam().scene << " " << scene.technique << " on " << dev->name;
    EXPECT_TRUE(f.differing.empty()) << f.differing.front();
    EXPECT_GT(f.compared, 0u);
    EXPECT_EQ(f.identical, f.compared);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, PassCountsCoverage,
                         ::testing::Values(Case{"bunny.json", ""}, Case{"bunny.json", "mirror"}, Case{"textured.json", ""},
                                           Case{"ward_spheres.json", ""}, Case{"ward_spheres.json", "env"},
                                           Case{"glints_torus.json", ""}, Case{"contact.json", "stochastic"}),
                         [](const auto& i) {
                           std::string n = std::string(i.param.scene) + "_" + (*i.param.technique ? i.param.technique : "own");
                           for (char& c : n)
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

// The raster passes' shape: every quad is 4 lanes (covered pixels + helpers), the G-buffer's fragment lanes run the
// fragment shader (one lane per tick), and the shading pass's 8-lane vectors include the tail lanes.
TEST(PassCounts, RasterAndComputeShapes) {
  Scene scene = small({"bunny.json", ""});
  scene.width = 37, scene.height = 19;  // 703 pixels: the last 8-lane vector has 7 tail lanes
  std::ostringstream quiet;
  const EnvironmentMap env = loadEnvironment(scene.environment, quiet);
  const model::FrameCounts f = model::countFrame(scene, *env.texture, emu::lavapipeProfile());
  GbufferStats gs;
  gbufferEmu(scene, emu::lavapipeProfile(), &gs);
  for (const model::PassCounts& p : f.passes) {
    if (p.pass == "gbuffer") {
      EXPECT_EQ(p.fragments, gs.raster.fragments);
      EXPECT_EQ(p.fragments + p.helperLanes, 4 * gs.raster.quads);
      EXPECT_EQ(p.dispatches, scene.objects.size());
      EXPECT_GT(p.helperLanes, 0u);
    }
    if (p.pass == "shade") {
      EXPECT_EQ(p.invocations, 704u);
    }
    if (p.pass == "shadow") {
      EXPECT_EQ(p.dispatches, scene.objects.size() * uint64_t(scene.visMaps));
    }
    if (p.pass == "visibility-fit") {  // per map: its matrix and weights (5 rows) and its SH row (4), as uniform fetches
      EXPECT_GT(p.ops[opcount::kTexUniform], 0.0);
      EXPECT_LE(p.ops[opcount::kTexUniform], 9.0 * scene.visMaps * double(p.invocations));
      EXPECT_EQ(p.ops[opcount::kTexFetch], scene.visMaps * double(p.invocations));  // the maps themselves (texelFetch)
      EXPECT_EQ(p.ops[opcount::kTexNearest], 0.0);  // no sampler lookups
    }
    // The technique inputs' pipelines are made when the inputs are built: their first dispatch is in the pass.
    if (p.pass == "paraboloid" || p.pass == "sh-project" || p.pass == "sh-reduce") {
      EXPECT_EQ(p.pipelines, 1u) << p.pass;
    }
    // The loop-state term's inputs: the dialect's FOR iterations by depth and the module's carried values. sh_project.comp
    // loops over the row's texels (every invocation, the tail's too, one row), carrying 16 RGB coefficients and the
    // column; the fit loops over the K maps; the filter's dx loop runs inside its dy loop.
    if (p.pass == "sh-project") {
      EXPECT_EQ(p.ops[opcount::kLoop1], double(p.invocations) * env.texture->width());
      EXPECT_EQ(p.ops[opcount::kLoop2], 0.0);
      EXPECT_EQ(p.loopCarried, (std::array<uint32_t, 3>{49, 0, 0}));
    }
    if (p.pass == "visibility-fit") {
      EXPECT_EQ(p.ops[opcount::kLoop1], double(p.invocations) * scene.visMaps);
      EXPECT_GT(p.loopCarried[0], 0u);
    }
    if (p.pass == "visibility-filter") {
      const double side = 2.0 * scene.visFilterRadius + 1.0;
      EXPECT_EQ(p.ops[opcount::kLoop1], double(p.invocations) * side);
      EXPECT_EQ(p.ops[opcount::kLoop2], double(p.invocations) * side * side);
      EXPECT_GT(p.loopCarried[1], 0u);
    }
    if (p.pass == "gbuffer" || p.pass == "shadow" || p.pass == "paraboloid") {
      EXPECT_EQ(p.ops[opcount::kLoop1] + p.ops[opcount::kLoop2] + p.ops[opcount::kLoop3], 0.0) << p.pass;
      EXPECT_EQ(p.loopCarried, (std::array<uint32_t, 3>{})) << p.pass;
    }
    if (p.pass == "sh-reduce") {  // sh_reduce.comp: one workgroup of 16; the tree's reads and in-place writes
      const uint64_t rows = env.texture->height();
      EXPECT_EQ(p.workgroups, 1u);
      EXPECT_EQ(p.bytesRead, rows * 256);
      EXPECT_EQ(p.bytesRead + p.bytesReread, (2 * (rows - 1) + 1) * 256);
      EXPECT_EQ(p.bytesWritten, rows * 256);
    }
    if (p.pass == "mips") {
      EXPECT_EQ(p.pipelines, 1u);  // bunny: the atlas's chain only (no material maps)
      // 9 vec4 loads per texel of each level (mip_downsample.glsl's 3x3 footprint), of which bytesRead holds the
      // distinct ones (4 a texel, 2x2 of the level above, but at the 1-texel levels of a 2:1 chain).
      EXPECT_EQ(p.bytesRead + p.bytesReread, p.bytesWritten * 9);
      EXPECT_GT(p.bytesReread, p.bytesRead);
    }
    if (p.pass == "gbuffer" || p.pass == "shade" || p.pass == "visibility-fit") {
      EXPECT_EQ(p.pipelines, 0u) << p.pass;
    }
    // A new pipeline's first dispatch compiles its module: each counts the module's size, a real SPIR-V module's
    // (more than a header and an entry point; below the 102K words of the calibrate module, the largest).
    if (p.pipelines) {
      EXPECT_GT(p.pipelineWords, 400u * p.pipelines) << p.pass;
      EXPECT_LT(p.pipelineWords, 50000u * p.pipelines) << p.pass;
    } else {
      EXPECT_EQ(p.pipelineWords, 0u) << p.pass;
    }
  }
}


// The shading pass counts the storage-buffer reads of its entry point (src/shaders/shade_*.comp) beside the G-buffer:
// per invocation the material record's 26 components, fis's SH lighting and (with visibility) the pixel's
// coefficients and light transport, the MIS techniques' settings block, and env's lights for every lane of an 8-lane
// vector in which any lane holds geometry (the vector runs the light loop, each lane's load tested against its mask);
// the tables' distinct bytes once, every row read again a re-read.
TEST(PassCounts, ShadePassesCountTheirEntryPointsBufferReads) {
  Scene base = small({"bunny.json", ""});
  base.width = 37, base.height = 19;  // 703 pixels, 704 invocations
  std::ostringstream quiet;
  const EnvironmentMap env = loadEnvironment(base.environment, quiet);
  const uint64_t pixels = 703, inv = 704;
  for (const char* t : {"fis", "env", "mirror", "kdtree-mis"}) {
    Scene scene = base;
    scene.technique = t;
    const model::FrameCounts f = model::countFrame(scene, *env.texture, emu::lavapipeProfile());
    const GBuffer g = gbufferEmu(scene, emu::lavapipeProfile());
    const ShadeInputs in = shadeInputsEmu(scene, *env.texture, emu::lavapipeProfile());
    const bool vis = in.visibility != nullptr;
    uint64_t geometry = 0, looping = 0;  // lanes with geometry; lanes of 8-lane vectors with any (env's light loop)
    for (uint64_t v = 0; v < inv; v += 8) {
      uint64_t here = 0;
      for (uint64_t i = v; i < v + 8; ++i) here += g.texels[std::min(i, pixels - 1) * kGbufFloats + 3] != 0.0f;
      geometry += here, looping += here ? 8 : 0;
    }
    ASSERT_GT(geometry, 0u);
    ASSERT_LT(looping, inv);
    ASSERT_GT(looping, geometry);  // vectors on the silhouette: the two counts differ
    uint64_t expected = pixels * kGbufFloats * 4 + (vis ? pixels * 64 : 0);  // G-buffer texels, the pixels' coefficients
    if (std::string(t) == "fis") expected += inv * (104 + 108 + (vis ? 256 : 0));
    if (std::string(t) == "env") expected += inv * 104 + looping * in.lights.count * 24;
    if (std::string(t) == "mirror") expected += inv * 24;
    if (std::string(t) == "kdtree-mis") expected += inv * (104 + 64 + (vis ? 64 : 0));
    const auto shade = std::find_if(f.passes.begin(), f.passes.end(), [](const model::PassCounts& p) { return p.pass == "shade"; });
    ASSERT_NE(shade, f.passes.end()) << t;
    EXPECT_EQ(shade->bytesRead + shade->bytesReread, expected) << t;
    if (std::string(t) != "mirror") {  // rows read again and again
      EXPECT_GT(shade->bytesReread, shade->bytesRead) << t;
    }
    EXPECT_EQ(shade->bytesWritten, pixels * 16) << t;
  }
}

// kSceneBrdfKinds compiles the absent BRDF kinds out on a device whose compiler specializes (lavapipe); SwiftShader
// runs them under the constant as under a mask (folds_specialization_constants false, measured), so on a device that
// runs every block their straight-line code counts; on a GPU that skips untaken blocks it never does. Bits unchanged.
TEST(PassCounts, AbsentBrdfKindsCountOnlyWhereTheCompilerKeepsThem) {
  const Scene scene = small({"bunny.json", "fis"});
  std::ostringstream quiet;
  const EnvironmentMap env = loadEnvironment(scene.environment, quiet);
  auto shadeOps = [&](bool everyBlock, bool folds) {
    model::CoreModel core;
    core.executeEveryBlock = everyBlock, core.foldsSpecConstants = folds;
    const model::FrameCounts f = model::countFrame(scene, *env.texture, emu::swiftshaderProfile(), core);
    EXPECT_EQ(f.identical, f.compared);
    double ops = 0;
    for (const model::PassCounts& p : f.passes)
      if (p.pass == "shade")
        for (int k = 0; k < opcount::kTexLookup; ++k) ops += p.ops[size_t(k)];
    return ops;
  };
  const double folded = shadeOps(true, true), kept = shadeOps(true, false);
  EXPECT_GT(kept, 1.2 * folded);  // four absent kinds' sampling code per sample
  EXPECT_EQ(shadeOps(false, true), shadeOps(false, false));
}

// Value numbering (a device whose compiler computes an expression once across the blocks it flattened: lavapipe):
// the materials scene under the MIS technique evaluates brdfPdf and brdfEval of one direction in sibling blocks of
// every kind, so fewer operations count; the counted pass still gives the emulator's bits, and the other passes,
// whose drivers do not mark invocations, count as before.
TEST(PassCounts, ValueNumberingCountsARepeatedExpressionOnceAndChangesNoBit) {
  for (const char* technique : {"kdtree-mis", "fis"}) {
    const Scene scene = small({"materials.json", technique});
    std::ostringstream quiet;
    const EnvironmentMap env = loadEnvironment(scene.environment, quiet);
    auto ops = [&](bool numbering) {
      model::CoreModel core;
      core.executeEveryBlock = true, core.valueNumbering = numbering;
      const model::FrameCounts f = model::countFrame(scene, *env.texture, emu::lavapipeProfile(), core);
      EXPECT_EQ(f.identical, f.compared) << technique;
      EXPECT_GT(f.compared, 0u);
      std::map<std::string, double> byPass;
      for (const model::PassCounts& p : f.passes)
        for (int k = 0; k < opcount::kTexLookup; ++k) byPass[p.pass] += p.ops[size_t(k)];
      return byPass;
    };
    const auto all = ops(false), numbered = ops(true);
    ASSERT_EQ(all.size(), numbered.size());
    for (const auto& [pass, n] : all) {
      if (pass == "shade") {
        EXPECT_LT(numbered.at(pass), 0.97 * n) << technique;  // repeated expressions count once
        EXPECT_GT(numbered.at(pass), 0.3 * n) << technique;   // and only those
      } else {
        EXPECT_EQ(numbered.at(pass), n) << pass;
      }
    }
  }
}

}  // namespace
