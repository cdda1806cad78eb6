// Device descriptions of the performance model (issue 19): strict parsing with errors that name the file and
// the key, a lossless round trip, and the shipped files: the two software devices written by `calibrate`,
// the two NVIDIA GPUs from public figures.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "model/device_desc.h"

namespace {
using shadetwin::model::DeviceDesc;
using shadetwin::model::loadDeviceDesc;
using shadetwin::model::parseDeviceDesc;

std::string shipped(const std::string& d) { return std::string(SHADETWIN_SOURCE_DIR) + "/devices/" + d + ".json"; }

std::string errorOf(const std::string& json) {
  try {
    parseDeviceDesc(json, "dev.json");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(DeviceDesc, ShippedFilesLoadAndSayWhereTheyComeFrom) {
  for (const char* d : {"lavapipe", "swiftshader", "h100", "h200"}) {
    const DeviceDesc x = loadDeviceDesc(shipped(d));
    EXPECT_EQ(x.device, d);
    EXPECT_FALSE(x.provenance.empty());
    for (double r : x.opsPerSecond) EXPECT_GT(r, 0.0) << d;
    for (double r : x.lookupsPerSecond) EXPECT_GT(r, 0.0) << d;
  }
  const DeviceDesc h100 = loadDeviceDesc(shipped("h100")), h200 = loadDeviceDesc(shipped("h200"));
  EXPECT_FALSE(h100.verified);  // public figures until a GPU is measured
  EXPECT_TRUE(loadDeviceDesc(shipped("lavapipe")).verified);
  // Measured by calibrate's spec-branch kernel (and by the shading pass: SwiftShader's time does not change when the
  // pipeline's kSceneBrdfKinds is every kind instead of the scene's, lavapipe's quadruples; docs/RESULTS.md).
  EXPECT_TRUE(loadDeviceDesc(shipped("lavapipe")).foldsSpecConstants);
  EXPECT_FALSE(loadDeviceDesc(shipped("swiftshader")).foldsSpecConstants);
  {  // shifts: SwiftShader's Subzero scalarizes vector shifts (calibrate: several times its integer add's cost); lavapipe
     // shifts at about its add rate; the GPUs at their INT32 rate (CUDA guide, compute capability 9.0)
    const DeviceDesc ss = loadDeviceDesc(shipped("swiftshader")), lp = loadDeviceDesc(shipped("lavapipe"));
    EXPECT_LT(ss.opsPerSecond[shadetwin::model::kShift], 0.5 * ss.opsPerSecond[shadetwin::model::kIAlu]);
    EXPECT_GT(lp.opsPerSecond[shadetwin::model::kShift], 0.5 * lp.opsPerSecond[shadetwin::model::kIAlu]);
    EXPECT_EQ(h100.opsPerSecond[shadetwin::model::kShift], h100.opsPerSecond[shadetwin::model::kIAlu]);
  }
  {  // integer selects: SwiftShader runs one (after its compare) at several times its integer add's cost (calibrate
     // kernel 18: ~0.15x the ialu rate), lavapipe at a blend's rate, 0.4-0.5x its add rate on session 39's Zen 3 host
     // (1.4x on session 38's file, the same CPU model); the GPUs at their compare/select rate
    const DeviceDesc ss = loadDeviceDesc(shipped("swiftshader")), lp = loadDeviceDesc(shipped("lavapipe"));
    EXPECT_LT(ss.opsPerSecond[shadetwin::model::kISelect], 0.5 * ss.opsPerSecond[shadetwin::model::kIAlu]);
    EXPECT_GT(lp.opsPerSecond[shadetwin::model::kISelect], 0.3 * lp.opsPerSecond[shadetwin::model::kIAlu]);
    EXPECT_EQ(h100.opsPerSecond[shadetwin::model::kISelect], h100.opsPerSecond[shadetwin::model::kSelect]);
  }
  {  // the post-transform vertex cache: simulated for SwiftShader (its source's direct-mapped 64 entries), not elsewhere
    const DeviceDesc ss = loadDeviceDesc(shipped("swiftshader"));
    EXPECT_EQ(ss.vertexCache.entries, 64u);
    EXPECT_EQ(ss.vertexCache.runLanes, 4u);
    EXPECT_EQ(h100.vertexCache.entries, 0u);
    EXPECT_EQ(loadDeviceDesc(shipped("lavapipe")).vertexCache.entries, 0u);
  }
  EXPECT_EQ(h100.cores, 132);
  EXPECT_NEAR(h100.opsPerSecond[shadetwin::model::kFAdd], 132.0 * 128.0 * 1.98e9, 1e6);
  EXPECT_NEAR(h200.bandwidthBytesPerSecond / h100.bandwidthBytesPerSecond, 4.8 / 3.35, 1e-9);
  // Re-reads are L1 hits: 32 load/store lanes an SM a clock, 4 bytes each.
  EXPECT_NEAR(h100.rereadBytesPerSecond, 132.0 * 32.0 * 4.0 * 1.98e9, 1e3);
  EXPECT_EQ(h200.rereadBytesPerSecond, h100.rereadBytesPerSecond);
  // The texture filters' costs are ordered on every device: nearest >= bilinear >= trilinear lookups per second.
  for (const char* d : {"lavapipe", "swiftshader", "h100", "h200"}) {
    const DeviceDesc x = loadDeviceDesc(shipped(d));
    EXPECT_GE(x.lookupsPerSecond[0], x.lookupsPerSecond[1]) << d;
    EXPECT_GE(x.lookupsPerSecond[1], x.lookupsPerSecond[2]) << d;
  }
}

TEST(DeviceDesc, RoundTripIsLossless) {
  DeviceDesc d = loadDeviceDesc(shipped("swiftshader"));
  const std::string path = std::string(::testing::TempDir()) + "/round_trip.json";
  shadetwin::model::saveDeviceDesc(d, path);
  const DeviceDesc e = loadDeviceDesc(path);
  EXPECT_EQ(e.name, d.name);
  EXPECT_EQ(e.opsPerSecond, d.opsPerSecond);
  EXPECT_EQ(e.lookupsPerSecond, d.lookupsPerSecond);
  EXPECT_EQ(e.dispatchSeconds, d.dispatchSeconds);
  EXPECT_EQ(e.rereadBytesPerSecond, d.rereadBytesPerSecond);
  EXPECT_EQ(e.codeWords, d.codeWords);
  EXPECT_EQ(e.codeSlowdown, d.codeSlowdown);
  EXPECT_EQ(e.loopStateValues, d.loopStateValues);
  EXPECT_EQ(e.loopStateSeconds, d.loopStateSeconds);
  for (int r = 0; r < shadetwin::model::kRasterPipelines; ++r) {
    EXPECT_EQ(e.raster[size_t(r)].trianglesPerSecond, d.raster[size_t(r)].trianglesPerSecond);
    EXPECT_EQ(e.raster[size_t(r)].fragmentsPerSecond, d.raster[size_t(r)].fragmentsPerSecond);
    EXPECT_EQ(e.raster[size_t(r)].targetBytesPerSecond, d.raster[size_t(r)].targetBytesPerSecond);
  }
  std::remove(path.c_str());
}

TEST(DeviceDesc, BadInputNamesTheFileAndTheKey) {
  const std::string good = shadetwin::model::deviceDescJson(loadDeviceDesc(shipped("h100")));
  EXPECT_EQ(errorOf(good), "");
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  // `good` without one of its top-level blocks: the key, its value, the comma and the newline.
  auto without = [&](const std::string& block) {
    std::string s = good;
    const size_t at = s.find("  " + block);
    EXPECT_NE(at, std::string::npos) << block;
    return at == std::string::npos ? s : s.erase(at, block.size() + 4);
  };
  EXPECT_NE(errorOf("{").find("dev.json: not valid JSON"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"lanes\"", "\"lane\"")).find("unknown key 'lane'"), std::string::npos);
  // The first "fadd" is the latency table's (keys are written sorted), the last the rates'.
  EXPECT_NE(errorOf(replaced("\"fadd\"", "\"fadd2\"")).find("unknown key 'latency_seconds.fadd2'"), std::string::npos);
  {
    std::string s = good;
    s.replace(s.rfind("\"fadd\""), 6, "\"fadd2\"");
    EXPECT_NE(errorOf(s).find("unknown key 'ops_per_second.fadd2'"), std::string::npos);
  }
  EXPECT_NE(errorOf(replaced("\"executes_every_block\": false", "\"executes_every_block\": 1")).find("'executes_every_block' must be true or false"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"folds_specialization_constants\": true", "\"folds_specialization_constants\": \"yes\""))
                .find("'folds_specialization_constants' must be true or false"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"value_numbering\": false", "\"value_numbering\": 0")).find("'value_numbering' must be true or false"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"value_numbering\": false,", "")).find("value_numbering"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"reread_bytes_per_second\": 33454080000000.0", "\"reread_bytes_per_second\": 0"))
                .find("'reread_bytes_per_second' must be positive"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"reread_bytes_per_second\": 33454080000000.0,", "")).find("missing key 'reread_bytes_per_second'"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"first_dispatch_seconds\": 0.0", "\"first_dispatch_seconds\": -1")).find("'first_dispatch_seconds' must be a number >= 0"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"compile_seconds_per_word\": 0.0", "\"compile_seconds_per_word\": -1e-9"))
                .find("'compile_seconds_per_word' must be a number >= 0"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"compile_seconds_per_word\": 0.0,", "")).find("compile_seconds_per_word"), std::string::npos);
  // The code-size term (session 43): points of increasing size, slowdowns of at least 1, as many of each; a file
  // written before it is refused by name.
  {
    const std::string empty = "\"code_size\": {\n    \"slowdown\": [],\n    \"words\": []\n  }";
    auto with = [&](const std::string& slowdown, const std::string& words) {
      return errorOf(replaced(empty, "\"code_size\": {\"slowdown\": " + slowdown + ", \"words\": " + words + "}"));
    };
    EXPECT_EQ(with("[1, 1.5, 2]", "[16000, 56000, 219000]"), "");
    EXPECT_NE(with("[1, 1.5]", "[16000, 56000, 219000]").find("must have the same length"), std::string::npos);
    EXPECT_NE(with("[1, 1.5, 2]", "[16000, 16000, 219000]").find("'code_size.words' must be positive and increasing"), std::string::npos);
    EXPECT_NE(with("[1, 0.9, 2]", "[16000, 56000, 219000]").find("'code_size.slowdown' must be numbers >= 1"), std::string::npos);
    EXPECT_NE(with("1.5", "[16000]").find("'code_size.slowdown' must be an array"), std::string::npos);
    const std::string s = without(empty);
    EXPECT_NE(errorOf(s).find("missing key 'code_size'"), std::string::npos) << errorOf(s);
  }
  // The loop-state term (session 44): a baseline and a price, neither negative; a file written before it is refused.
  {
    const std::string zero = "\"loop_state\": {\n    \"seconds_per_value\": 0.0,\n    \"values\": 0.0\n  }";
    auto with = [&](const std::string& seconds, const std::string& values) {
      return errorOf(replaced(zero, "\"loop_state\": {\"seconds_per_value\": " + seconds + ", \"values\": " + values + "}"));
    };
    EXPECT_EQ(with("2.4e-10", "10"), "");
    EXPECT_NE(with("-1e-10", "10").find("'loop_state.seconds_per_value' must be a number >= 0"), std::string::npos);
    EXPECT_NE(with("1e-10", "\"ten\"").find("'loop_state.values' must be a number >= 0"), std::string::npos);
    EXPECT_NE(errorOf(replaced(zero, "\"loop_state\": {\"values\": 10}")).find("missing key 'loop_state.seconds_per_value'"),
              std::string::npos);
    const std::string s = without(zero);
    EXPECT_NE(errorOf(s).find("missing key 'loop_state'"), std::string::npos) << errorOf(s);
  }
  EXPECT_NE(errorOf(replaced("\"workgroup_seconds\": 0.0", "\"workgroup_seconds\": null")).find("'workgroup_seconds' must be a number >= 0"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"uniform\"", "\"uniforms\"")).find("unknown key 'lookups_per_second.uniforms'"), std::string::npos);
  {
    std::string s = good;
    const size_t at = s.find("\"fetch\": ");
    s.erase(at, s.find('\n', at) - at + 1);
    EXPECT_NE(errorOf(s).find("missing key 'lookups_per_second.fetch'"), std::string::npos);
  }
  {
    std::string s = good;
    const size_t at = s.find("\"texture_miss_seconds\": ") + 24;
    s.replace(at, s.find(',', at) - at, "-3");
    EXPECT_NE(errorOf(s).find("'texture_miss_seconds' must be a number >= 0"), std::string::npos);
  }
  // Raster rates per pipeline: each pipeline's three rates, no other pipeline, positive.
  EXPECT_NE(errorOf(replaced("\"gbuffer\": {", "\"deferred\": {")).find("unknown key 'raster.deferred'"), std::string::npos);
  {
    std::string s = good;  // the first "triangles_per_second" is depth_only's (keys are written sorted)
    s.replace(s.find("\"triangles_per_second\""), 22, "\"triangle_per_second\"");
    EXPECT_NE(errorOf(s).find("unknown key 'raster.depth_only.triangle_per_second'"), std::string::npos);
    s = good;
    const size_t at = s.rfind("\"fragments_per_second\": ") + 24;
    s.replace(at, s.find(',', at) - at, "0");
    EXPECT_NE(errorOf(s).find("'raster.gbuffer.fragments_per_second' must be positive"), std::string::npos);
    s = good;  // session 34's key: a file without it (older calibrations) is refused by name, a negative cost too
    const size_t sp = s.find("\"spanning_triangle_seconds\": ");
    ASSERT_NE(sp, std::string::npos);
    s.erase(sp, s.find('\n', sp) + 1 - sp);
    EXPECT_NE(errorOf(s).find("spanning_triangle_seconds"), std::string::npos) << errorOf(s);
    s = good;
    const size_t v = s.rfind("\"spanning_triangle_seconds\": ") + 29;
    s.replace(v, s.find(',', v) - v, "-1e-9");
    EXPECT_NE(errorOf(s).find("'raster.gbuffer.spanning_triangle_seconds' must be a number >= 0"), std::string::npos) << errorOf(s);
  }
  EXPECT_NE(errorOf(replaced("\"verified\": false", "\"verified\": 0")).find("'verified' must be true or false"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"dispatch_seconds\": 1e-05", "\"dispatch_seconds\": -1")).find("'dispatch_seconds' must be positive"),
            std::string::npos);
  EXPECT_NE(errorOf("{\"device\": \"x\"}").find("dev.json: missing key"), std::string::npos);
  EXPECT_NE(errorOf(replaced("\"entries\": 0", "\"entries\": 48")).find("'vertex_cache.entries' must be 0 or a power of two"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"entries\": 0", "\"entries\": -1")).find("'vertex_cache.entries' must be an integer"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced("\"entries\": 0", "\"entries\": 64")).find("'vertex_cache.batch_triangles' and"),
            std::string::npos);
  {
    std::string s = good;  // the first "vertex_run_seconds" is depth_only's
    const size_t at = s.find("\"vertex_run_seconds\": ") + 22;
    s.replace(at, s.find('\n', at) - at, "-1");
    EXPECT_NE(errorOf(s).find("'raster.depth_only.vertex_run_seconds' must be a number >= 0"), std::string::npos) << errorOf(s);
  }
  {  // a description written before shifts were a class of their own: the missing rate is named
    std::string s = good;
    const size_t at = s.rfind(",\n    \"shift\": ");
    ASSERT_NE(at, std::string::npos);
    s.erase(at, s.find('\n', at + 2) - at);
    EXPECT_NE(errorOf(s).find("ops_per_second.shift"), std::string::npos) << errorOf(s);
  }
  try {
    loadDeviceDesc("/nonexistent/devices/x.json");
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/devices/x.json: cannot open"), std::string::npos);
  }
}

}  // namespace
