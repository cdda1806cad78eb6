#include "model/device_desc.h"

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "util/output_file.h"

namespace shadetwin::model {

namespace {
using nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what);
}

void checkKeys(const json& j, const std::set<std::string>& allowed, const std::string& path, const std::string& where) {
  if (!j.is_object()) fail(path, where + " must be an object");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!allowed.count(it.key())) fail(path, "unknown key '" + where + it.key() + "'");
  for (const auto& k : allowed)
    if (!j.contains(k)) fail(path, "missing key '" + where + k + "'");
}

double positive(const json& j, const std::string& key, const std::string& path, const std::string& where) {
  const json& v = j.at(key);
  if (!v.is_number()) fail(path, "'" + where + key + "' must be a number");
  const double d = v.get<double>();
  if (!(d > 0.0)) fail(path, "'" + where + key + "' must be positive, got " + v.dump());
  return d;
}

double nonNegative(const json& j, const std::string& key, const std::string& path, const std::string& where = "") {
  const json& v = j.at(key);
  if (!v.is_number() || !(v.get<double>() >= 0.0)) fail(path, "'" + where + key + "' must be a number >= 0");
  return v.get<double>();
}
}  // namespace

DeviceDesc parseDeviceDesc(const std::string& text, const std::string& path) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    fail(path, std::string("not valid JSON: ") + e.what());
  }
  checkKeys(j, {"device", "name", "verified", "provenance", "lanes", "cores", "clock_ghz", "ops_per_second",
                "lookups_per_second", "cache_line_bytes", "cache_bytes", "bandwidth_bytes_per_second", "reread_bytes_per_second",
                "dispatch_seconds", "first_dispatch_seconds", "compile_seconds_per_word", "workgroup_seconds", "raster", "texture_miss_seconds",
                "texture_stream_seconds", "units_overlap", "latency_seconds", "window_ops", "executes_every_block",
                "folds_specialization_constants", "value_numbering", "vertex_cache", "code_size", "loop_state"},
            path, "");
  DeviceDesc d;
  for (const char* k : {"device", "name", "provenance"})
    if (!j.at(k).is_string()) fail(path, std::string("'") + k + "' must be a string");
  if (!j.at("verified").is_boolean()) fail(path, "'verified' must be true or false");
  if (!j.at("units_overlap").is_boolean()) fail(path, "'units_overlap' must be true or false");
  d.unitsOverlap = j.at("units_overlap").get<bool>();
  if (!j.at("executes_every_block").is_boolean()) fail(path, "'executes_every_block' must be true or false");
  d.executesEveryBlock = j.at("executes_every_block").get<bool>();
  if (!j.at("folds_specialization_constants").is_boolean())
    fail(path, "'folds_specialization_constants' must be true or false");
  d.foldsSpecConstants = j.at("folds_specialization_constants").get<bool>();
  if (!j.at("value_numbering").is_boolean()) fail(path, "'value_numbering' must be true or false");
  d.valueNumbering = j.at("value_numbering").get<bool>();
  d.device = j.at("device").get<std::string>();
  d.name = j.at("name").get<std::string>();
  d.provenance = j.at("provenance").get<std::string>();
  d.verified = j.at("verified").get<bool>();
  d.lanes = int(positive(j, "lanes", path, ""));
  d.cores = int(positive(j, "cores", path, ""));
  d.clockGHz = nonNegative(j, "clock_ghz", path);
  std::set<std::string> ops(std::begin(kOpClassNames), std::end(kOpClassNames));
  checkKeys(j.at("ops_per_second"), ops, path, "ops_per_second.");
  for (int c = 0; c < kOpClasses; ++c) d.opsPerSecond[size_t(c)] = positive(j.at("ops_per_second"), kOpClassNames[c], path, "ops_per_second.");
  checkKeys(j.at("latency_seconds"), ops, path, "latency_seconds.");
  for (int c = 0; c < kOpClasses; ++c)
    d.latencySeconds[size_t(c)] = positive(j.at("latency_seconds"), kOpClassNames[c], path, "latency_seconds.");
  std::set<std::string> filters(std::begin(kTexFilterNames), std::end(kTexFilterNames));
  checkKeys(j.at("lookups_per_second"), filters, path, "lookups_per_second.");
  for (int f = 0; f < kTexFilters; ++f)
    d.lookupsPerSecond[size_t(f)] = positive(j.at("lookups_per_second"), kTexFilterNames[f], path, "lookups_per_second.");
  d.cacheLineBytes = int(positive(j, "cache_line_bytes", path, ""));
  d.cacheBytes = positive(j, "cache_bytes", path, "");
  d.bandwidthBytesPerSecond = positive(j, "bandwidth_bytes_per_second", path, "");
  d.rereadBytesPerSecond = positive(j, "reread_bytes_per_second", path, "");
  d.dispatchSeconds = positive(j, "dispatch_seconds", path, "");
  d.firstDispatchSeconds = nonNegative(j, "first_dispatch_seconds", path);
  d.compileSecondsPerWord = nonNegative(j, "compile_seconds_per_word", path);
  d.workgroupSeconds = nonNegative(j, "workgroup_seconds", path);
  d.textureMissSeconds = nonNegative(j, "texture_miss_seconds", path);
  d.textureStreamSeconds = nonNegative(j, "texture_stream_seconds", path);
  checkKeys(j.at("raster"), {std::begin(kRasterPipelineNames), std::end(kRasterPipelineNames)}, path, "raster.");
  for (int r = 0; r < kRasterPipelines; ++r) {
    const std::string where = std::string("raster.") + kRasterPipelineNames[r] + ".";
    const json& x = j.at("raster").at(kRasterPipelineNames[r]);
    checkKeys(x, {"triangles_per_second", "fragments_per_second", "target_bytes_per_second", "vertex_run_seconds",
                  "outside_triangle_seconds", "draw_seconds", "spanning_triangle_seconds", "partial_block_seconds"}, path, where);
    d.raster[size_t(r)] = {positive(x, "triangles_per_second", path, where), positive(x, "fragments_per_second", path, where),
                           positive(x, "target_bytes_per_second", path, where),
                           nonNegative(x, "vertex_run_seconds", path, where),
                           nonNegative(x, "outside_triangle_seconds", path, where), nonNegative(x, "draw_seconds", path, where),
                           nonNegative(x, "spanning_triangle_seconds", path, where),
                           nonNegative(x, "partial_block_seconds", path, where)};
  }
  {
    const json& v = j.at("vertex_cache");
    checkKeys(v, {"entries", "batch_triangles", "run_lanes"}, path, "vertex_cache.");
    auto count = [&](const char* k) {
      const json& x = v.at(k);
      if (!x.is_number_unsigned() || x.get<uint64_t>() > (1u << 20))
        fail(path, std::string("'vertex_cache.") + k + "' must be an integer in [0, 2^20]");
      return uint32_t(x.get<uint64_t>());
    };
    d.vertexCache = {count("entries"), count("batch_triangles"), count("run_lanes")};
    if (d.vertexCache.entries && (d.vertexCache.entries & (d.vertexCache.entries - 1)))
      fail(path, "'vertex_cache.entries' must be 0 or a power of two (a direct-mapped cache indexed by index mod entries)");
    if (d.vertexCache.entries && (!d.vertexCache.batchTriangles || !d.vertexCache.runLanes))
      fail(path, "'vertex_cache.batch_triangles' and 'vertex_cache.run_lanes' must be positive when entries is");
  }
  d.windowOps = positive(j, "window_ops", path, "");
  {
    const json& cs = j.at("code_size");
    checkKeys(cs, {"words", "slowdown"}, path, "code_size.");
    for (const char* k : {"words", "slowdown"})
      if (!cs.at(k).is_array()) fail(path, std::string("'code_size.") + k + "' must be an array of numbers");
    if (cs.at("words").size() != cs.at("slowdown").size())
      fail(path, "'code_size.words' and 'code_size.slowdown' must have the same length");
    for (size_t i = 0; i < cs.at("words").size(); ++i) {
      const json &w = cs.at("words")[i], &s = cs.at("slowdown")[i];
      if (!w.is_number() || !(w.get<double>() > (i ? d.codeWords.back() : 0.0)))
        fail(path, "'code_size.words' must be positive and increasing, got " + w.dump() + " at " + std::to_string(i));
      if (!s.is_number() || !(s.get<double>() >= 1.0))
        fail(path, "'code_size.slowdown' must be numbers >= 1, got " + s.dump() + " at " + std::to_string(i));
      d.codeWords.push_back(w.get<double>());
      d.codeSlowdown.push_back(s.get<double>());
    }
  }
  {
    const json& ls = j.at("loop_state");
    checkKeys(ls, {"values", "seconds_per_value"}, path, "loop_state.");
    d.loopStateValues = nonNegative(ls, "values", path, "loop_state.");
    d.loopStateSeconds = nonNegative(ls, "seconds_per_value", path, "loop_state.");
  }
  return d;
}

DeviceDesc loadDeviceDesc(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open the device description");
  std::stringstream ss;
  ss << f.rdbuf();
  return parseDeviceDesc(ss.str(), path);
}

std::string deviceDescJson(const DeviceDesc& d) {
  json ops = json::object(), lookups = json::object(), latency = json::object();
  for (int c = 0; c < kOpClasses; ++c) ops[kOpClassNames[c]] = d.opsPerSecond[size_t(c)];
  for (int c = 0; c < kOpClasses; ++c) latency[kOpClassNames[c]] = d.latencySeconds[size_t(c)];
  for (int f = 0; f < kTexFilters; ++f) lookups[kTexFilterNames[f]] = d.lookupsPerSecond[size_t(f)];
  json raster = json::object();
  for (int r = 0; r < kRasterPipelines; ++r)
    raster[kRasterPipelineNames[r]] = {{"triangles_per_second", d.raster[size_t(r)].trianglesPerSecond},
                                       {"fragments_per_second", d.raster[size_t(r)].fragmentsPerSecond},
                                       {"target_bytes_per_second", d.raster[size_t(r)].targetBytesPerSecond},
                                       {"vertex_run_seconds", d.raster[size_t(r)].vertexRunSeconds},
                                       {"outside_triangle_seconds", d.raster[size_t(r)].outsideTriangleSeconds},
                                       {"draw_seconds", d.raster[size_t(r)].drawSeconds},
                                       {"spanning_triangle_seconds", d.raster[size_t(r)].spanningTriangleSeconds},
                                       {"partial_block_seconds", d.raster[size_t(r)].partialBlockSeconds}};
  json j = {{"device", d.device},
            {"name", d.name},
            {"verified", d.verified},
            {"provenance", d.provenance},
            {"lanes", d.lanes},
            {"cores", d.cores},
            {"clock_ghz", d.clockGHz},
            {"ops_per_second", ops},
            {"lookups_per_second", lookups},
            {"cache_line_bytes", d.cacheLineBytes},
            {"cache_bytes", d.cacheBytes},
            {"bandwidth_bytes_per_second", d.bandwidthBytesPerSecond},
            {"reread_bytes_per_second", d.rereadBytesPerSecond},
            {"dispatch_seconds", d.dispatchSeconds},
            {"first_dispatch_seconds", d.firstDispatchSeconds},
            {"compile_seconds_per_word", d.compileSecondsPerWord},
            {"workgroup_seconds", d.workgroupSeconds},
            {"raster", raster},
            {"texture_miss_seconds", d.textureMissSeconds},
            {"texture_stream_seconds", d.textureStreamSeconds},
            {"units_overlap", d.unitsOverlap},
            {"latency_seconds", latency},
            {"window_ops", d.windowOps},
            {"executes_every_block", d.executesEveryBlock},
            {"folds_specialization_constants", d.foldsSpecConstants},
            {"value_numbering", d.valueNumbering},
            {"vertex_cache", {{"entries", d.vertexCache.entries}, {"batch_triangles", d.vertexCache.batchTriangles},
                              {"run_lanes", d.vertexCache.runLanes}}},
            {"code_size", {{"words", d.codeWords}, {"slowdown", d.codeSlowdown}}},
            {"loop_state", {{"values", d.loopStateValues}, {"seconds_per_value", d.loopStateSeconds}}}};
  return j.dump(2) + "\n";
}

void saveDeviceDesc(const DeviceDesc& d, const std::string& path) {
  OutputFile file(path);
  file.stream() << deviceDescJson(d);
  file.commit();
}

}  // namespace shadetwin::model
