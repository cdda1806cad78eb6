// Campaign files: reading, expanding into jobs, checking each job against its scene (cli/campaign.h).
#include "cli/campaign.h"

#include <fnmatch.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "scene/scene.h"

namespace shadetwin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<std::string> kKinds = {"verify", "render", "sweep", "model"};
const std::vector<std::string> kSuites = {"math",       "texture", "mips", "raster",     "shadow", "shade",
                                          "frame",      "paraboloid", "sh", "visibility", "ndf",    "glint-lighting"};
const std::vector<std::string> kAxes = {"scenes", "techniques", "samples", "sizes", "devices", "seeds"};

// The axes a job of `kind` (and `suite`) expands over. Sweeps take techniques and samples as their own lists (one
// sweep compares them); renders run on the emulator (no device).
std::set<std::string> kindAxes(const std::string& kind, const std::string& suite) {
  if (kind == "render") return {"scenes", "techniques", "samples", "sizes"};
  if (kind == "sweep") return {"scenes", "techniques", "samples", "sizes", "devices"};
  if (kind == "model") return {"scenes", "techniques", "samples", "sizes", "devices"};
  if (suite == "math" || suite == "texture" || suite == "mips" || suite == "ndf") return {"devices", "seeds"};
  if (suite == "raster" || suite == "visibility") return {"scenes", "sizes", "devices"};
  if (suite == "shade" || suite == "frame") return {"scenes", "techniques", "samples", "sizes", "devices"};
  return {"scenes", "devices"};  // shadow, paraboloid, sh, glint-lighting: the scene's environment and geometry
}

std::string joined(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw CampaignError(file + ": " + (key.empty() ? std::string("top level") : key) + ": " + what);
  }
  void keys(const json& j, const std::string& where, const std::vector<std::string>& allowed) const {
    if (!j.is_object()) fail(where, "expected an object");
    for (auto& [k, v] : j.items())
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
        fail(where.empty() ? k : where + "." + k, "unknown key (expected one of: " + joined(allowed) + ")");
  }
  std::string str(const json& j, const std::string& key, const std::string& where) const {
    if (!j.is_string()) fail(where, "expected a string, got " + j.dump());
    (void)key;
    return j.get<std::string>();
  }
  std::vector<std::string> strings(const json& j, const std::string& where) const {
    if (!j.is_array() || j.empty()) fail(where, "expected a non-empty array of strings, got " + j.dump());
    std::vector<std::string> r;
    for (size_t i = 0; i < j.size(); ++i) {
      if (!j[i].is_string() || j[i].get<std::string>().empty())
        fail(where + "[" + std::to_string(i) + "]", "expected a non-empty string, got " + j[i].dump());
      r.push_back(j[i].get<std::string>());
    }
    return r;
  }
  std::vector<int64_t> integers(const json& j, const std::string& where, int64_t lo, int64_t hi) const {
    if (!j.is_array() || j.empty()) fail(where, "expected a non-empty array of integers, got " + j.dump());
    std::vector<int64_t> r;
    for (size_t i = 0; i < j.size(); ++i) {
      if (!j[i].is_number_integer() || j[i].get<int64_t>() < lo || j[i].get<int64_t>() > hi)
        fail(where + "[" + std::to_string(i) + "]",
             "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + j[i].dump());
      r.push_back(j[i].get<int64_t>());
    }
    return r;
  }
};

bool isName(const std::string& s) {
  return !s.empty() && s.size() <= 64 &&
         std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
}

// One job's axes after the campaign's defaults and the job's own keys.
struct Axes {
  std::vector<std::string> scenes;      // absolute, normalized
  std::vector<std::string> techniques;  // {""}: the scene's
  std::vector<uint32_t> samples;        // {0}: the scene's
  std::vector<std::pair<uint32_t, uint32_t>> sizes;  // {0, 0}: the scene's
  std::vector<std::string> devices;     // default {"lavapipe"}
  std::vector<int64_t> seeds;           // default {1}
  std::set<std::string> given;          // the axes the file names (campaign or job)
};

// Reads the axis keys of `j` (the campaign's "axes" or a job) into `a`.
void readAxes(const Reader& R, const json& j, const std::string& where, const fs::path& dir, Axes& a) {
  for (const std::string& k : kAxes) {
    if (!j.contains(k)) continue;
    const std::string key = where.empty() ? k : where + "." + k;
    a.given.insert(k);
    const json& v = j.at(k);
    if (k == "scenes") {
      a.scenes.clear();
      const auto list = R.strings(v, key);
      for (size_t i = 0; i < list.size(); ++i) {
        const fs::path p = (fs::path(list[i]).is_absolute() ? fs::path(list[i]) : dir / list[i]).lexically_normal();
        const std::string stem = p.filename().string();
        std::vector<std::string> found;
        if (stem.find_first_of("*?[") != std::string::npos) {  // a pattern in the file name: every match, sorted
          std::error_code ec;
          for (const auto& e : fs::directory_iterator(p.parent_path(), ec))
            if (e.is_regular_file() && fnmatch(stem.c_str(), e.path().filename().c_str(), 0) == 0)
              found.push_back(fs::absolute(e.path()).lexically_normal().string());
          if (ec) R.fail(key + "[" + std::to_string(i) + "]", "cannot read folder " + p.parent_path().string() + ": " + ec.message());
          if (found.empty()) R.fail(key + "[" + std::to_string(i) + "]", "no file matches " + p.string());
          std::sort(found.begin(), found.end());
        } else {
          if (!fs::is_regular_file(p)) R.fail(key + "[" + std::to_string(i) + "]", "scene file not found: " + p.string());
          found.push_back(fs::absolute(p).lexically_normal().string());
        }
        for (const auto& f : found)
          if (std::find(a.scenes.begin(), a.scenes.end(), f) == a.scenes.end()) a.scenes.push_back(f);
      }
    } else if (k == "techniques") {
      a.techniques = R.strings(v, key);
      for (size_t i = 0; i < a.techniques.size(); ++i)
        if (!isTechnique(a.techniques[i])) {
          std::vector<std::string> known(std::begin(kTechniques), std::end(kTechniques));
          R.fail(key + "[" + std::to_string(i) + "]", "unknown technique '" + a.techniques[i] + "' (expected one of: " + joined(known) + ")");
        }
    } else if (k == "samples") {
      a.samples.clear();
      for (int64_t n : R.integers(v, key, 1, 1 << 20)) a.samples.push_back(uint32_t(n));
    } else if (k == "sizes") {
      a.sizes.clear();
      const auto list = R.strings(v, key);
      for (size_t i = 0; i < list.size(); ++i) {
        unsigned w = 0, h = 0;
        char x = 0, extra = 0;
        if (std::sscanf(list[i].c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 || h < 1 || w > 16384 || h > 16384)
          R.fail(key + "[" + std::to_string(i) + "]", "expected WIDTHxHEIGHT (1 to 16384 each), got \"" + list[i] + "\"");
        a.sizes.emplace_back(w, h);
      }
    } else if (k == "devices") {
      a.devices = R.strings(v, key);
      for (size_t i = 0; i < a.devices.size(); ++i)
        if (!isName(a.devices[i])) R.fail(key + "[" + std::to_string(i) + "]", "expected a device name of letters, digits, '_' and '-', got \"" + a.devices[i] + "\"");
    } else {
      a.seeds = R.integers(v, key, 0, int64_t(1) << 53);
    }
  }
}

template <class T>
void dedupe(std::vector<T>& v) {
  std::vector<T> r;
  for (const T& x : v)
    if (std::find(r.begin(), r.end(), x) == r.end()) r.push_back(x);
  v = r;
}

}  // namespace

std::vector<std::string> CampaignJob::command(const std::string& dir) const {
  std::vector<std::string> c;
  const fs::path d(dir);
  auto scene_ = [&] {
    if (!scene.empty()) c.insert(c.end(), {"--scene", scene});
  };
  auto size_ = [&] {
    if (width) c.insert(c.end(), {"--width", std::to_string(width), "--height", std::to_string(height)});
  };
  auto technique_ = [&] {
    if (!technique.empty()) c.insert(c.end(), {"--technique", technique});
    if (samples) c.insert(c.end(), {"--samples", std::to_string(samples)});
  };
  if (kind == "verify") {
    c = {"verify", suite};
    scene_();
    technique_();
    size_();
    if (!device.empty()) c.insert(c.end(), {"--device", device});
    if (seed >= 0) c.insert(c.end(), {"--seed", std::to_string(seed)});
    c.insert(c.end(), args.begin(), args.end());
    c.insert(c.end(), {"--json", (d / "report.json").string(), "--junit", (d / "junit.xml").string(), "--heatmap",
                       (d / "heatmap.png").string()});
  } else if (kind == "render") {
    c = {"render"};
    scene_();
    technique_();
    size_();
    c.insert(c.end(), args.begin(), args.end());
    c.insert(c.end(), {"--out", (d / "render.exr").string()});
  } else if (kind == "sweep") {
    c = {"sweep"};
    scene_();
    size_();
    if (!techniques.empty()) c.insert(c.end(), {"--technique", joined(techniques, ",")});
    if (!sampleList.empty()) {
      std::vector<std::string> s;
      for (uint32_t n : sampleList) s.push_back(std::to_string(n));
      c.insert(c.end(), {"--samples", joined(s, ",")});
    }
    if (!device.empty()) c.insert(c.end(), {"--device", device});
    c.insert(c.end(), args.begin(), args.end());
    c.insert(c.end(), {"--out", (d / "sweep").string()});
  } else {  // model
    c = {"model"};
    scene_();
    technique_();
    size_();
    if (!device.empty()) c.insert(c.end(), {"--device", device});
    c.insert(c.end(), {"--devices", devicesDir});
    c.insert(c.end(), args.begin(), args.end());
  }
  return c;
}

Campaign loadCampaign(const std::string& path) {
  Reader R{path};
  std::ifstream f(path);
  if (!f) throw CampaignError(path + ": cannot open campaign file");
  std::error_code sizeError;
  if (fs::file_size(path, sizeError) > (uint64_t(4) << 20) && !sizeError)
    throw CampaignError(path + ": campaign file larger than 4 MiB");
  json j;
  try {
    j = json::parse(f);
  } catch (const json::parse_error& e) {
    throw CampaignError(path + ": not valid JSON: " + e.what());
  }
  R.keys(j, "", {"name", "description", "axes", "jobs", "devices_folder"});
  Campaign c;
  c.file = path;
  if (!j.contains("name")) R.fail("name", "missing (expected a name of letters, digits, '_' and '-')");
  c.name = R.str(j["name"], "name", "name");
  if (!isName(c.name)) R.fail("name", "expected at most 64 letters, digits, '_' and '-', got \"" + c.name + "\"");
  if (j.contains("description")) c.description = R.str(j["description"], "description", "description");
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  const std::string devicesDir =
      (dir / (j.contains("devices_folder") ? R.str(j["devices_folder"], "", "devices_folder") : std::string("../devices"))).lexically_normal().string();
  Axes base;
  base.techniques = {""}, base.samples = {0}, base.sizes = {{0, 0}}, base.devices = {"lavapipe"}, base.seeds = {1};
  if (j.contains("axes")) {
    R.keys(j["axes"], "axes", kAxes);
    readAxes(R, j["axes"], "axes", dir, base);
  }
  if (!j.contains("jobs") || !j["jobs"].is_array() || j["jobs"].empty()) R.fail("jobs", "expected a non-empty array of jobs");
  std::vector<std::string> jobKeys = {"kind", "suite", "args"};
  jobKeys.insert(jobKeys.end(), kAxes.begin(), kAxes.end());
  std::map<std::string, std::string> seen;  // id -> where it came from
  std::map<std::string, Scene> scenes;      // loaded once each
  for (size_t n = 0; n < j["jobs"].size(); ++n) {
    const json& jj = j["jobs"][n];
    const std::string where = "jobs[" + std::to_string(n) + "]";
    R.keys(jj, where, jobKeys);
    if (!jj.contains("kind")) R.fail(where + ".kind", "missing (expected one of: " + joined(kKinds) + ")");
    const std::string kind = R.str(jj["kind"], "kind", where + ".kind");
    if (std::find(kKinds.begin(), kKinds.end(), kind) == kKinds.end())
      R.fail(where + ".kind", "unknown kind '" + kind + "' (expected one of: " + joined(kKinds) + ")");
    std::string suite;
    if (kind == "verify") {
      if (!jj.contains("suite")) R.fail(where + ".suite", "missing (expected one of: " + joined(kSuites) + ")");
      suite = R.str(jj["suite"], "suite", where + ".suite");
      if (std::find(kSuites.begin(), kSuites.end(), suite) == kSuites.end())
        R.fail(where + ".suite", "unknown suite '" + suite + "' (expected one of: " + joined(kSuites) + ")");
    } else if (jj.contains("suite")) {
      R.fail(where + ".suite", "only verify jobs have a suite");
    }
    std::vector<std::string> args;
    if (jj.contains("args")) {
      if (!jj["args"].is_array()) R.fail(where + ".args", "expected an array of strings, got " + jj["args"].dump());
      for (size_t i = 0; i < jj["args"].size(); ++i) {
        if (!jj["args"][i].is_string()) R.fail(where + ".args[" + std::to_string(i) + "]", "expected a string, got " + jj["args"][i].dump());
        args.push_back(jj["args"][i].get<std::string>());
      }
      // The generated arguments are the campaign's: an argument that sets them would make two ids one run.
      static const std::set<std::string> owned = {"--scene", "--technique", "--samples", "--width", "--height", "--device",
                                                  "--seed", "--json", "--junit", "--heatmap", "--out", "--threads",
                                                  "--devices"};
      for (size_t i = 0; i < args.size(); ++i) {
        const std::string flag = args[i].substr(0, args[i].find('='));
        if (owned.count(flag))
          R.fail(where + ".args[" + std::to_string(i) + "]", "'" + flag + "' is set by the campaign's axes (scenes, techniques, samples, "
                                                              "sizes, devices, seeds) or its outputs; use the axis");
      }
    }
    Axes a = base;
    a.given.clear();
    const std::set<std::string> applies = kindAxes(kind, suite);
    readAxes(R, jj, where, dir, a);
    for (const std::string& k : a.given)
      if (!applies.count(k))
        R.fail(where + "." + k, "does not apply to " + kind + (suite.empty() ? "" : " " + suite) + " (it takes: " +
                                    joined(std::vector<std::string>(applies.begin(), applies.end())) + ")");
    if (applies.count("scenes") && a.scenes.empty())
      R.fail(where, kind + (suite.empty() ? "" : " " + suite) + " needs scenes (axes.scenes or the job's scenes)");
    // The axes that do not apply take one neutral value.
    if (!applies.count("scenes")) a.scenes = {""};
    if (!applies.count("techniques")) a.techniques = {""};
    if (!applies.count("samples")) a.samples = {0};
    if (!applies.count("sizes")) a.sizes = {{0, 0}};
    if (!applies.count("devices")) a.devices = {""};
    if (!applies.count("seeds")) a.seeds = {-1};
    dedupe(a.techniques), dedupe(a.samples), dedupe(a.sizes), dedupe(a.devices), dedupe(a.seeds);
    // A sweep compares its techniques and sample counts in one run.
    std::vector<std::string> sweepTechniques;
    std::vector<uint32_t> sweepSamples;
    if (kind == "sweep") {
      if (a.techniques != std::vector<std::string>{""}) sweepTechniques = a.techniques;
      if (a.samples != std::vector<uint32_t>{0}) sweepSamples = a.samples;
      a.techniques = {""}, a.samples = {0};
    }
    for (const std::string& scene : a.scenes) {
      std::string sceneName;
      if (!scene.empty()) {
        sceneName = fs::path(scene).stem().string();
        if (!isName(sceneName)) R.fail(where + ".scenes", "scene file name '" + sceneName + "' is not a name of letters, digits, '_' and '-'");
        if (!scenes.count(scene)) {
          try {
            scenes.emplace(scene, loadScene(scene));
          } catch (const std::exception& e) {
            R.fail(where + ".scenes", e.what());
          }
        }
      }
      for (const std::string& technique : a.techniques)
        for (uint32_t samples : a.samples)
          for (const auto& [w, h] : a.sizes)
            for (const std::string& device : a.devices)
              for (int64_t seed : a.seeds) {
                CampaignJob job;
                job.kind = kind, job.suite = suite, job.scene = scene, job.sceneName = sceneName;
                job.technique = technique, job.samples = samples, job.width = w, job.height = h;
                job.device = device, job.seed = seed, job.args = args;
                if (kind == "model") job.devicesDir = devicesDir;
                job.techniques = sweepTechniques, job.sampleList = sweepSamples;
                std::vector<std::string> parts = {kind + (suite.empty() ? "" : "-" + suite)};
                if (!sceneName.empty()) parts.push_back(sceneName);
                if (!technique.empty()) parts.push_back(technique);
                if (samples) parts.push_back("s" + std::to_string(samples));
                if (w) parts.push_back(std::to_string(w) + "x" + std::to_string(h));
                std::vector<std::string> group = parts;
                if (seed >= 0) group.push_back("seed" + std::to_string(seed));
                if (!device.empty()) parts.push_back(device);
                if (seed >= 0) parts.push_back("seed" + std::to_string(seed));
                job.id = joined(parts, ".");
                job.groupId = joined(group, ".");
                if (seen.count(job.id))
                  R.fail(where, "job id " + job.id + " is also made by " + seen[job.id] + " (give the two jobs different axes or merge them)");
                seen[job.id] = where;
                if (!scene.empty()) {  // the scene's own refusals, as the command would report them
                  Scene s = scenes.at(scene);
                  SceneOverrides o;
                  o.technique = technique, o.samples = samples, o.width = w, o.height = h;
                  try {
                    applyOverrides(s, o);
                  } catch (const std::invalid_argument& e) {
                    job.skipReason = e.what();
                  }
                }
                c.jobs.push_back(std::move(job));
              }
    }
  }
  return c;
}

}  // namespace shadetwin
