// Campaign files (cli/campaign.h): expansion into jobs, stable ids, the scene's refusals, strict keys with errors naming
// the file and the key. Running them (locally and through Slurm) is tests/campaign_end_to_end_test.sh.
#include "cli/campaign.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

namespace {

namespace fs = std::filesystem;
const std::string kSrc = SHADETWIN_SOURCE_DIR;

std::string writeCampaign(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "shadetwin_campaign_test";
  fs::create_directories(dir);
  const fs::path p = dir / (name + ".json");
  std::ofstream(p) << text;
  return p.string();
}

std::string errorOf(const std::string& text) {
  const std::string p = writeCampaign("bad", text);
  try {
    shadetwin::loadCampaign(p);
  } catch (const shadetwin::CampaignError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(p + ": ", 0), 0u) << "the message names the file: " << m;
    return m;
  }
  ADD_FAILURE() << "no error for " << text;
  return "";
}

const shadetwin::CampaignJob* find(const shadetwin::Campaign& c, const std::string& id) {
  for (const auto& j : c.jobs)
    if (j.id == id) return &j;
  return nullptr;
}

TEST(Campaign, ExpandsEachKindOverItsAxes) {
  const std::string scenes = "[\"" + kSrc + "/scenes/bunny.json\", \"" + kSrc + "/scenes/textured.json\"]";
  const auto c = shadetwin::loadCampaign(writeCampaign("expand", R"({"name": "t", "axes": {"scenes": )" + scenes +
      R"(, "techniques": ["fis", "mirror", "glints"], "samples": [4, 8], "sizes": ["24x16", "8x8"],
      "devices": ["lavapipe", "swiftshader"], "seeds": [1, 2, 3]},
      "jobs": [{"kind": "verify", "suite": "frame"}, {"kind": "verify", "suite": "math"},
               {"kind": "verify", "suite": "shadow"}, {"kind": "verify", "suite": "raster"},
               {"kind": "render"}, {"kind": "sweep"}, {"kind": "model", "devices": ["h100"]}]})"));
  std::map<std::string, size_t> perKind;
  for (const auto& j : c.jobs) ++perKind[j.kind + "-" + j.suite];
  EXPECT_EQ(perKind["verify-frame"], 2u * 3 * 2 * 2 * 2);  // scenes x techniques x samples x sizes x devices; no seeds
  EXPECT_EQ(perKind["verify-math"], 2u * 3);                // devices x seeds; no scene
  EXPECT_EQ(perKind["verify-shadow"], 2u * 2);              // scenes x devices
  EXPECT_EQ(perKind["verify-raster"], 2u * 2 * 2);          // scenes x sizes x devices
  EXPECT_EQ(perKind["render-"], 2u * 3 * 2 * 2);            // no devices: the emulator
  EXPECT_EQ(perKind["sweep-"], 2u * 2 * 2);                 // its techniques and samples are one sweep's lists
  EXPECT_EQ(perKind["model-"], 2u * 3 * 2 * 2 * 1);
  std::set<std::string> ids;
  for (const auto& j : c.jobs) EXPECT_TRUE(ids.insert(j.id).second) << "duplicate id " << j.id;

  const auto* f = find(c, "verify-frame.bunny.fis.s4.24x16.swiftshader");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->groupId, "verify-frame.bunny.fis.s4.24x16");
  const auto cmd = f->command("/out/x");
  const std::vector<std::string> want = {"verify", "frame", "--scene", kSrc + "/scenes/bunny.json", "--technique", "fis", "--samples", "4",
                                         "--width", "24", "--height", "16", "--device", "swiftshader", "--json", "/out/x/report.json",
                                         "--junit", "/out/x/junit.xml", "--heatmap", "/out/x/heatmap.png"};
  EXPECT_EQ(cmd, want);
  ASSERT_NE(find(c, "verify-math.lavapipe.seed3"), nullptr);
  const auto* sw = find(c, "sweep.textured.8x8.lavapipe");
  ASSERT_NE(sw, nullptr);
  const auto swc = sw->command("/o");
  EXPECT_NE(std::find(swc.begin(), swc.end(), "fis,mirror,glints"), swc.end());
  EXPECT_NE(std::find(swc.begin(), swc.end(), "4,8"), swc.end());
  const auto* m = find(c, "model.bunny.fis.s8.8x8.h100");
  ASSERT_NE(m, nullptr);
  // The device descriptions' folder defaults to ../devices beside the campaign file.
  EXPECT_EQ(m->devicesDir, (fs::temp_directory_path() / "shadetwin_campaign_test" / ".." / "devices").lexically_normal().string());
  const auto mc = m->command("/o");
  EXPECT_NE(std::find(mc.begin(), mc.end(), m->devicesDir), mc.end());
}

TEST(Campaign, TheScenesRefusalsAreSkippedJobsWithTheirReason) {
  const auto c = shadetwin::loadCampaign(writeCampaign("refuse", R"({"name": "r", "axes": {"scenes": [")" + kSrc +
      R"(/scenes/*.json"], "techniques": ["fis", "mirror", "glints", "glints-gxd"]}, "jobs": [{"kind": "verify", "suite": "frame"}]})"));
  size_t scenes = 0, skipped = 0;
  for (const auto& e : fs::directory_iterator(kSrc + "/scenes")) scenes += e.path().extension() == ".json";
  EXPECT_EQ(c.jobs.size(), scenes * 4);  // the pattern found every shipped scene
  for (const auto& j : c.jobs) {
    const bool glintScene = j.sceneName == "glints" || j.sceneName == "glints_torus";
    const bool refused = ((j.technique == "glints" || j.technique == "glints-gxd") && !glintScene) ||
                         (j.technique == "mirror" && j.sceneName == "textured");
    EXPECT_EQ(!j.skipReason.empty(), refused) << j.id << ": " << j.skipReason;
    skipped += refused;
    if (refused) EXPECT_NE(j.skipReason.find(j.scene), std::string::npos) << "the reason names the scene: " << j.skipReason;
  }
  EXPECT_GT(skipped, 0u);
  EXPECT_TRUE(std::is_sorted(c.jobs.begin(), c.jobs.end(), [](const auto& a, const auto& b) { return a.scene < b.scene; }));
}

TEST(Campaign, BadFilesNameTheKeyAndTheProblem) {
  const std::string bunny = "\"" + kSrc + "/scenes/bunny.json\"";
  struct Case {
    std::string text, want;
  } cases[] = {
      {"{", "not valid JSON"},
      {R"({"jobs": [{"kind": "render"}]})", "name: missing"},
      {R"({"name": "a b", "jobs": [{"kind": "render"}]})", "name: expected at most 64 letters"},
      {R"({"name": "x", "axis": {}, "jobs": []})", "axis: unknown key (expected one of: name, description, axes, jobs, devices_folder)"},
      {R"({"name": "x"})", "jobs: expected a non-empty array"},
      {R"({"name": "x", "jobs": [{"kind": "bake"}]})", "jobs[0].kind: unknown kind 'bake'"},
      {R"({"name": "x", "jobs": [{"kind": "verify"}]})", "jobs[0].suite: missing"},
      {R"({"name": "x", "jobs": [{"kind": "verify", "suite": "colour"}]})", "jobs[0].suite: unknown suite 'colour'"},
      {R"({"name": "x", "jobs": [{"kind": "render", "suite": "frame"}]})", "jobs[0].suite: only verify jobs have a suite"},
      {R"({"name": "x", "jobs": [{"kind": "render"}]})", "jobs[0]: render needs scenes"},
      {R"({"name": "x", "axes": {"scenes": ["nope.json"]}, "jobs": [{"kind": "render"}]})", "axes.scenes[0]: scene file not found"},
      {R"({"name": "x", "axes": {"scenes": ["nope*.json"]}, "jobs": [{"kind": "render"}]})", "axes.scenes[0]: no file matches"},
      {R"({"name": "x", "axes": {"techniques": ["phong"]}, "jobs": [{"kind": "verify", "suite": "math"}]})",
       "axes.techniques[0]: unknown technique 'phong'"},
      {R"({"name": "x", "axes": {"sizes": ["64"]}, "jobs": [{"kind": "verify", "suite": "math"}]})",
       "axes.sizes[0]: expected WIDTHxHEIGHT"},
      {R"({"name": "x", "axes": {"sizes": ["0x4"]}, "jobs": [{"kind": "verify", "suite": "math"}]})", "axes.sizes[0]: expected WIDTHxHEIGHT"},
      {R"({"name": "x", "axes": {"samples": [0]}, "jobs": [{"kind": "verify", "suite": "math"}]})", "axes.samples[0]: expected an integer in [1,"},
      {R"({"name": "x", "axes": {"seeds": "1"}, "jobs": [{"kind": "verify", "suite": "math"}]})", "axes.seeds: expected a non-empty array of integers"},
      {R"({"name": "x", "axes": {"devices": ["a/b"]}, "jobs": [{"kind": "verify", "suite": "math"}]})", "axes.devices[0]: expected a device name"},
      {R"({"name": "x", "jobs": [{"kind": "verify", "suite": "math", "techniques": ["fis"]}]})",
       "jobs[0].techniques: does not apply to verify math (it takes: devices, seeds)"},
      {R"({"name": "x", "jobs": [{"kind": "render", "devices": ["lavapipe"], "scenes": [)" + bunny + "]}]}",
       "jobs[0].devices: does not apply to render"},
      {R"({"name": "x", "jobs": [{"kind": "verify", "suite": "math", "args": ["--seed", "3"]}]})",
       "jobs[0].args[0]: '--seed' is set by the campaign's axes"},
      {R"({"name": "x", "jobs": [{"kind": "verify", "suite": "math", "args": ["--json=x"]}]})", "jobs[0].args[0]: '--json' is set"},
      {R"({"name": "x", "jobs": [{"kind": "verify", "suite": "math", "args": [3]}]})", "jobs[0].args[0]: expected a string"},
      {R"({"name": "x", "jobs": [{"kind": "verify", "suite": "math"}, {"kind": "verify", "suite": "math", "args": ["--count", "9"]}]})",
       "jobs[1]: job id verify-math.lavapipe.seed1 is also made by jobs[0]"},
      {R"({"name": "x", "jobs": [{"kind": "render", "scenes": [)" + bunny + R"(], "colour": 1}]})", "jobs[0].colour: unknown key"},
  };
  for (const auto& k : cases) {
    const std::string m = errorOf(k.text);
    EXPECT_NE(m.find(k.want), std::string::npos) << "for " << k.text << "\n got: " << m;
  }
  // A scene that does not load: the scene's own message, under the campaign's key.
  const std::string badScene = writeCampaign("badscene_scene", R"({"image": {"width": -1}})");
  const std::string m = errorOf(R"({"name": "x", "axes": {"scenes": [")" + badScene + R"("]}, "jobs": [{"kind": "render"}]})");
  EXPECT_NE(m.find("jobs[0].scenes: " + badScene), std::string::npos) << m;
}

TEST(Campaign, CsvFieldsAreQuotedOnlyWhenNeeded) {
  EXPECT_EQ(shadetwin::csvField("plain"), "plain");
  EXPECT_EQ(shadetwin::csvField("a,b"), "\"a,b\"");
  EXPECT_EQ(shadetwin::csvField("say \"x\""), "\"say \"\"x\"\"\"");
  EXPECT_EQ(shadetwin::csvField("two\nlines"), "\"two\nlines\"");
}

}  // namespace
