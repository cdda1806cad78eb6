#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <limits>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>

namespace shadetwin {

Mat4 rotateAboutOwnAxis(const Mat4& m, double degrees) {
  const double a = degrees * 3.14159265358979323846 / 180.0, c = std::cos(a), sn = std::sin(a);
  const double ox = m[12], oz = m[14];  // the object's origin in world space (column 3)
  // R = [c 0 s; 0 1 0; -s 0 c] about (ox, *, oz): rows of the 3x3 part and the translation.
  Mat4 r{};
  for (int col = 0; col < 4; ++col) {
    const double x = m[size_t(4 * col)], y = m[size_t(4 * col + 1)], z = m[size_t(4 * col + 2)], w = m[size_t(4 * col + 3)];
    const double px = x - ox * w, pz = z - oz * w;  // T(-o), per column (w = 0 for directions, 1 for the origin)
    r[size_t(4 * col)] = float(c * px + sn * pz + ox * w);
    r[size_t(4 * col + 1)] = float(y);
    r[size_t(4 * col + 2)] = float(-sn * px + c * pz + oz * w);
    r[size_t(4 * col + 3)] = float(w);
  }
  return r;
}

namespace fs = std::filesystem;
using nlohmann::json;

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(a[k * 4 + rr]) * b[c * 4 + k];
      r[c * 4 + rr] = float(s);
    }
  return r;
}

Mat4 normalMatrix(const Mat4& m) {
  double a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = m[c * 4 + r];
  double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  Mat4 n = identity();
  if (det == 0) return n;
  // inverse-transpose = cofactor matrix / det
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      n[c * 4 + r] = float((a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det);
    }
  return n;
}

namespace {

using v3::cross;
using v3::sub;
Vec3 norm3(Vec3 a) { return v3::normalized(a, a); }
float dot3(Vec3 a, Vec3 b) { return float(v3::dot(a, b)); }

// Strict reader: every key is known, every value has the expected type, and errors name the file,
// the key path and what was expected.
struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw SceneError(file + ": " + (key.empty() ? std::string("top level") : key) + ": " + what);
  }
  void keys(const json& j, const std::string& where, std::set<std::string> allowed) const {
    if (!j.is_object()) fail(where, "expected an object");
    for (auto& [k, v] : j.items())
      if (!allowed.count(k)) {
        std::string list;
        for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(where.empty() ? k : where + "." + k, "unknown key (expected one of: " + list + ")");
      }
  }
  float number(const json& j, const std::string& key, float def, float lo, float hi) const {
    if (!j.contains(key.substr(key.rfind('.') + 1))) return def;
    const json& v = j.at(key.substr(key.rfind('.') + 1));
    if (!v.is_number()) fail(key, "expected a number, got " + v.dump());
    double d = v.get<double>();
    if (!(d >= lo && d <= hi)) fail(key, "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + v.dump());
    return float(d);
  }
  Vec3 vec3(const json& j, const std::string& key, Vec3 def) const {
    auto k = key.substr(key.rfind('.') + 1);
    if (!j.contains(k)) return def;
    const json& v = j.at(k);
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      fail(key, "expected an array of 3 numbers, got " + v.dump());
    Vec3 r{};
    for (int c = 0; c < 3; ++c) {
      const double d = v[size_t(c)].get<double>();  // checked before the conversion (a float cannot hold 1e39)
      if (!(std::fabs(d) <= double(std::numeric_limits<float>::max()))) fail(key, "expected finite numbers, got " + v.dump());
      r[size_t(c)] = float(d);
    }
    return r;
  }
  std::string string(const json& j, const std::string& key, const std::string& def, bool required = false) const {
    auto k = key.substr(key.rfind('.') + 1);
    if (!j.contains(k)) {
      if (required) fail(key, "missing (expected a string)");
      return def;
    }
    if (!j.at(k).is_string()) fail(key, "expected a string, got " + j.at(k).dump());
    return j.at(k).get<std::string>();
  }
  /// `file` resolved against the scene's directory `dir` (unless absolute), normalized; it must exist
  /// (for a path under assets/ the message says how to fetch it).
  std::string existingPath(const fs::path& dir, const std::string& file, const std::string& key) const {
    const fs::path p = (fs::path(file).is_absolute() ? fs::path(file) : dir / file).lexically_normal();
    if (!fs::exists(p))
      fail(key, "file not found: " + p.string() +
                    (file.find("assets/") != std::string::npos ? " (fetch the assets with: bash scripts/setup.sh)" : ""));
    return p.string();
  }
};

Mat4 translate(Vec3 t) {
  Mat4 m = identity();
  m[12] = t[0], m[13] = t[1], m[14] = t[2];
  return m;
}
Mat4 scale(float s) {
  Mat4 m = identity();
  m[0] = m[5] = m[10] = s;
  return m;
}
Mat4 rotateY(float deg) {
  double a = deg * std::numbers::pi / 180.0;
  Mat4 m = identity();
  m[0] = float(std::cos(a)), m[8] = float(std::sin(a)), m[2] = float(-std::sin(a)), m[10] = float(std::cos(a));
  return m;
}

}  // namespace

CameraBasis Scene::basis() const {
  Vec3 f = norm3(sub(camera.target, camera.eye));
  Vec3 s = norm3(cross(f, camera.up));
  return {s, cross(s, f), f};
}

Mat4 Scene::view() const {
  const auto [s, u, f] = basis();
  // Camera space: x right, y down, z forward (Vulkan conventions, so the projection needs no flip).
  Mat4 m = identity();
  m[0] = s[0], m[4] = s[1], m[8] = s[2];
  m[1] = -u[0], m[5] = -u[1], m[9] = -u[2];
  m[2] = f[0], m[6] = f[1], m[10] = f[2];
  m[12] = -dot3(s, camera.eye), m[13] = dot3(u, camera.eye), m[14] = -dot3(f, camera.eye);
  return m;
}

Mat4 Scene::projection() const {
  const double t = std::tan(camera.fovY * std::numbers::pi / 360.0), aspect = double(width) / height;
  const double n = camera.near, f = camera.far;
  Mat4 p{};
  p[0] = float(1.0 / (t * aspect));
  p[5] = float(1.0 / t);
  p[10] = float(f / (f - n));  // z_ndc = f (z - n) / ((f - n) z): 0 at near, 1 at far
  p[11] = 1.0f;
  p[14] = float(-f * n / (f - n));
  return p;
}

Mat4 Scene::viewProjection() const { return mul(projection(), view()); }

std::array<Vec3, 2> Scene::bounds() const {
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (auto& o : objects)
    for (auto& p : meshes[o.mesh].positions)
      for (int k = 0; k < 3; ++k) {
        float w = o.model[k] * p[0] + o.model[4 + k] * p[1] + o.model[8 + k] * p[2] + o.model[12 + k];
        lo[k] = std::min(lo[k], w), hi[k] = std::max(hi[k], w);
      }
  return {lo, hi};
}

size_t Scene::triangles() const {
  size_t n = 0;
  for (auto& o : objects) n += meshes[o.mesh].triangles();
  return n;
}

std::string defaultScenePath() { return "scenes/bunny.json"; }

std::string techniqueRefusal(const Scene& scene, const std::string& technique) {
  for (const Material& m : scene.materials) {
    if (isGlintsTechnique(technique) && !m.glints)
      return scene.path + ": material '" + m.name + "' has no glints block (every material of a glints scene is a glinty conductor)";
    if (technique == "mirror" && m.hasMaps())  // the mirror pass reads no material maps (inputs/material.cpp)
      return scene.path + ": material '" + m.name + "' has material maps, which technique mirror does not read (fis, "
             "unfiltered, stochastic and env do)";
  }
  return "";
}

void setTechnique(Scene& scene, const std::string& technique) {
  if (!isTechnique(technique)) {
    std::string known;
    for (const char* k : kTechniques) known += (known.empty() ? "" : ", ") + std::string(k);
    throw std::invalid_argument("--technique: unknown technique '" + technique + "' (expected one of " + known + ")");
  }
  const std::string refusal = techniqueRefusal(scene, technique);
  if (!refusal.empty()) throw std::invalid_argument("--technique " + technique + ": " + refusal);
  scene.technique = technique;
}

void applyOverrides(Scene& scene, const SceneOverrides& o) {
  if (!o.technique.empty()) setTechnique(scene, o.technique);
  if (o.width) scene.width = o.width;
  if (o.height) scene.height = o.height;
  if (o.samples) scene.fisSamples = scene.misSamples = scene.glintGxdSamples = o.samples;
  if (o.blocks) scene.envBlocks = o.blocks;
  if (o.visMaps) {
    if (!scene.visMaps) throw std::invalid_argument("--vis-maps: " + scene.path + " has no \"visibility\" block");
    scene.visMaps = o.visMaps;
  }
  if (!o.glintViews.empty()) {
    const auto grid = parseGlintGrid(o.glintViews, "--glint-views");
    if (std::none_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.glints; }))
      throw std::invalid_argument("--glint-views: " + scene.path + " has no glints materials");
    std::tie(scene.glintViewRings, scene.glintViewSectors) = grid;
  }
}

std::pair<uint32_t, uint32_t> parseGlintGrid(const std::string& g, const char* flag) {
  unsigned rings = 0, sectors = 0;
  char tail = 0;
  if (std::sscanf(g.c_str(), "%ux%u%c", &rings, &sectors, &tail) != 2 || rings < 2 || rings > 513 || sectors < 1 || sectors > 1024)
    throw std::invalid_argument(std::string(flag) + ": '" + g + "' is not RINGSxSECTORS (rings 2-513, sectors 1-1024)");
  return {rings, sectors};
}

Scene loadScene(const std::string& path, const SceneOverrides& o) {
  Scene s = loadScene(path);
  applyOverrides(s, o);
  return s;
}

Scene loadScene(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw SceneError(path + ": cannot open scene file");
  // A scene file is a few KiB (meshes and images are files of their own): refuse a huge one before parsing it.
  std::error_code sizeError;
  const auto bytes = fs::file_size(path, sizeError);
  if (!sizeError && bytes > kMaxSceneFileBytes)
    throw SceneError(path + ": scene file of " + std::to_string(bytes >> 20) + " MiB (at most " +
                     std::to_string(kMaxSceneFileBytes >> 20) + " MiB: meshes and images belong in files of their own)");
  json j;
  try {
    j = json::parse(f, nullptr, true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    throw SceneError(path + ": not valid JSON: " + e.what());
  }
  Reader R{path};
  R.keys(j, "", {"image", "camera", "environment", "technique", "fis", "mis", "visibility", "glints", "materials", "objects",
                 "description"});
  const fs::path dir = fs::path(path).parent_path();
  const fs::path root = fs::weakly_canonical(dir / "..");
  Scene s;
  s.path = path;
  if (j.contains("image")) {
    const json& im = j["image"];
    R.keys(im, "image", {"width", "height"});
    s.width = uint32_t(R.number(im, "image.width", 512, 1, 16384));
    s.height = uint32_t(R.number(im, "image.height", 512, 1, 16384));
  }
  if (!j.contains("camera")) R.fail("camera", "missing (expected an object with eye, target, fov)");
  {
    const json& c = j["camera"];
    R.keys(c, "camera", {"eye", "target", "up", "fov", "near", "far"});
    s.camera.eye = R.vec3(c, "camera.eye", s.camera.eye);
    s.camera.target = R.vec3(c, "camera.target", s.camera.target);
    s.camera.up = R.vec3(c, "camera.up", s.camera.up);
    s.camera.fovY = R.number(c, "camera.fov", 40, 1, 170);
    s.camera.near = R.number(c, "camera.near", 0.1f, 1e-6f, 1e6f);
    s.camera.far = R.number(c, "camera.far", 100, 1e-6f, 1e9f);
    if (!(s.camera.far > s.camera.near)) R.fail("camera.far", "expected far > near");
    Vec3 d = sub(s.camera.target, s.camera.eye);
    if (dot3(d, d) == 0) R.fail("camera.target", "expected a point different from camera.eye");
    Vec3 c3 = cross(norm3(d), s.camera.up);
    if (dot3(c3, c3) < 1e-12f) R.fail("camera.up", "expected a vector not parallel to the view direction");
  }
  if (!j.contains("environment")) R.fail("environment", "missing (expected {\"file\": \"../assets/hdri/forest.exr\"})");
  {
    const json& e = j["environment"];
    R.keys(e, "environment", {"file", "intensity", "negative"});
    s.environment = R.existingPath(dir, R.string(e, "environment.file", "", true), "environment.file");
    s.environmentIntensity = R.number(e, "environment.intensity", 1, 0, 1e9f);
    const std::string negative = R.string(e, "environment.negative", "keep");
    if (negative != "keep" && negative != "clamp")
      R.fail("environment.negative", "unknown policy '" + negative + "' (expected keep or clamp)");
    s.envClampNegative = negative == "clamp";
  }
  s.technique = R.string(j, "technique", "fis");
  if (!isTechnique(s.technique))
    R.fail("technique", "unknown technique '" + s.technique +
                           "' (expected: fis, unfiltered, stochastic, env, mirror, kdtree-mis, alias-mis, inversion-mis or glints)");
  if (j.contains("fis")) {
    const json& f = j["fis"];
    if (!f.is_object()) R.fail("fis", "expected an object with samples, k, face_size");
    R.keys(f, "fis", {"samples", "k", "face_size", "level_bias", "background"});
    s.fisSamples = uint32_t(R.number(f, "fis.samples", 40, 1, 4096));
    s.fisK = R.number(f, "fis.k", 4, 1e-3f, 1e6f);
    s.fisFaceSize = uint32_t(R.number(f, "fis.face_size", 256, 4, 8192));
    s.fisLevelBias = R.number(f, "fis.level_bias", 0, 0, 16);
    const std::string bg = R.string(f, "fis.background", "environment");
    if (bg != "environment" && bg != "atlas")
      R.fail("fis.background", "unknown background '" + bg + "' (expected: environment or atlas)");
    s.fisBackgroundAtlas = bg == "atlas";
  }
  if (j.contains("glints")) {
    const json& f = j["glints"];
    if (!f.is_object())
      R.fail("glints", "expected an object with order, rings, sectors, theta_max, view_rings, view_sectors, lobe_rings, lobe_sectors, gxd_samples");
    R.keys(f, "glints", {"order", "rings", "sectors", "theta_max", "view_rings", "view_sectors", "lobe_rings", "lobe_sectors", "gxd_samples"});
    s.glintOrder = uint32_t(R.number(f, "glints.order", 16, 0, 64));  // shade_glints.h kGlintShadeMaxOrder
    s.glintRings = uint32_t(R.number(f, "glints.rings", 9, 1, 16));
    s.glintSectors = uint32_t(R.number(f, "glints.sectors", 32, 8, 64));
    if (s.glintSectors % 8) R.fail("glints.sectors", "expected a multiple of 8 (the table packs 8 sectors per texel)");
    s.glintThetaMax = R.number(f, "glints.theta_max", 90, 1, 180) * 3.14159265f / 180.0f;
    s.glintViewRings = uint32_t(R.number(f, "glints.view_rings", 65, 2, 513));
    s.glintViewSectors = uint32_t(R.number(f, "glints.view_sectors", 128, 1, 1024));
    s.glintGxdSamples = uint32_t(R.number(f, "glints.gxd_samples", 64, 1, 1 << 20));
    s.glintLobeRings = uint32_t(R.number(f, "glints.lobe_rings", 0, 0, 513));
    s.glintLobeSectors = uint32_t(R.number(f, "glints.lobe_sectors", 0, 0, 1024));
    if ((s.glintLobeRings == 0) != (s.glintLobeSectors == 0) || s.glintLobeRings == 1)
      R.fail("glints.lobe_rings", "the rotated-lobe table needs lobe_rings >= 2 and lobe_sectors >= 1 (both 0: recurrences per bin)");
  }
  if (j.contains("visibility")) {
    const json& f = j["visibility"];
    if (!f.is_object()) R.fail("visibility", "expected an object with maps, size, fit, bias, slope_bias, filter, radius");
    R.keys(f, "visibility", {"maps", "size", "fit", "bias", "slope_bias", "filter", "radius"});
    s.visFilterRadius = uint32_t(R.number(f, "visibility.radius", 2, 0, 16));
    const std::string filter = R.string(f, "visibility.filter", "edge");
    if (filter != "edge" && filter != "box" && filter != "none")
      R.fail("visibility.filter", "unknown filter '" + filter + "' (expected edge, box or none)");
    s.visFilterEdge = filter == "edge";
    if (filter == "none") s.visFilterRadius = 0;
    s.visMaps = uint32_t(R.number(f, "visibility.maps", 16, 1, 1024));
    s.visSize = uint32_t(R.number(f, "visibility.size", 1024, 16, 8192));
    s.visBias = R.number(f, "visibility.bias", 1.0f, 0, 1000);
    s.visSlopeBias = R.number(f, "visibility.slope_bias", 1.5f, 0, 1000);
    const std::string fit = R.string(f, "visibility.fit", "vcos");
    if (fit != "vcos" && fit != "v") R.fail("visibility.fit", "unknown fit '" + fit + "' (expected vcos or v)");
    s.visFitCosine = fit == "vcos";
    if (!usesFisPass(s.technique) && !usesMisPass(s.technique))
      R.fail("visibility", "technique " + s.technique +
                               " does not read visibility yet (fis, unfiltered, stochastic and the *-mis techniques do)");
  }
  if (j.contains("mis")) {
    const json& f = j["mis"];
    if (!f.is_object()) R.fail("mis", "expected an object with samples, heuristic, blocks, seed");
    R.keys(f, "mis", {"samples", "heuristic", "blocks", "seed"});
    s.misSamples = uint32_t(R.number(f, "mis.samples", 16, 1, 4096));
    s.envBlocks = uint32_t(R.number(f, "mis.blocks", 6144, 1, 1 << 20));
    s.misSeed = uint32_t(R.number(f, "mis.seed", 0, 0, 16777216));
    const std::string h = R.string(f, "mis.heuristic", "power");
    bool found = false;
    for (uint32_t i = 0; i < std::size(kMisHeuristics); ++i)
      if (h == kMisHeuristics[i]) s.misHeuristic = i, found = true;
    if (!found) R.fail("mis.heuristic", "unknown heuristic '" + h + "' (expected balance, power, env-only or brdf-only)");
  }

  std::map<std::string, uint32_t> matIndex;
  if (j.contains("materials")) {
    if (!j["materials"].is_array()) R.fail("materials", "expected an array of objects");
    for (size_t i = 0; i < j["materials"].size(); ++i) {
      const json& m = j["materials"][i];
      const std::string key = "materials[" + std::to_string(i) + "]";
      R.keys(m, key, {"name", "diffuse", "specular", "brdf", "exponent", "roughness", "roughness_y", "lobes", "diffuse_map",
                      "specular_map", "roughness_map", "glints"});
      Material mat;
      mat.name = R.string(m, key + ".name", "", true);
      if (matIndex.count(mat.name)) R.fail(key + ".name", "duplicate material name '" + mat.name + "'");
      mat.diffuse = R.vec3(m, key + ".diffuse", mat.diffuse);
      mat.specular = R.vec3(m, key + ".specular", mat.specular);
      mat.brdf = R.string(m, key + ".brdf", mat.brdf);
      static const std::set<std::string> brdfs{"phong", "blinn", "ward", "lafortune", "ggx", "mirror"};
      if (!brdfs.count(mat.brdf)) R.fail(key + ".brdf", "unknown BRDF '" + mat.brdf + "' (expected phong, blinn, ward, lafortune, ggx or mirror)");
      mat.exponent = R.number(m, key + ".exponent", mat.exponent, 0, 1e7f);
      mat.roughness = R.number(m, key + ".roughness", mat.roughness, 0, 1);
      mat.roughnessY = R.number(m, key + ".roughness_y", mat.roughness, 0, 1);
      if (m.contains("lobes")) {
        if (mat.brdf != "lafortune") R.fail(key + ".lobes", "only a lafortune material has lobes (brdf is '" + mat.brdf + "')");
        const json& lobes = m["lobes"];
        if (!lobes.is_array() || lobes.empty() || lobes.size() > 2) R.fail(key + ".lobes", "expected an array of 1 or 2 lobes {c, n, rho}");
        for (size_t l = 0; l < lobes.size(); ++l) {
          const std::string lk = key + ".lobes[" + std::to_string(l) + "]";
          R.keys(lobes[l], lk, {"c", "n", "rho"});
          LafortuneLobe lobe;
          lobe.c = R.vec3(lobes[l], lk + ".c", lobe.c);
          for (float c : lobe.c)
            if (std::fabs(c) > 100) R.fail(lk + ".c", "expected coefficients in [-100, 100]");
          lobe.n = R.number(lobes[l], lk + ".n", lobe.n, 0, 1e6f);
          lobe.rho = R.number(lobes[l], lk + ".rho", lobe.rho, 0, 1e6f);
          mat.lobes.push_back(lobe);
        }
      } else if (mat.brdf == "lafortune") {
        R.fail(key + ".lobes", "missing: a lafortune material needs 1 or 2 lobes, e.g. [{\"c\": [-1, -1, 1], \"n\": 60, \"rho\": 9.7}]");
      }
      auto map = [&](const char* name) {
        const std::string k = key + "." + name, file = R.string(m, k, "");
        return file.empty() ? file : R.existingPath(dir, file, k);
      };
      mat.diffuseMap = map("diffuse_map");
      mat.specularMap = map("specular_map");
      mat.roughnessMap = map("roughness_map");
      if (!mat.roughnessMap.empty() && mat.brdf != "ward" && mat.brdf != "ggx")
        R.fail(key + ".roughness_map", "a roughness map needs brdf ward or ggx (brdf is '" + mat.brdf + "')");
      if (m.contains("glints")) {
        const json& g = m["glints"];
        const std::string gk = key + ".glints";
        if (!g.is_object()) R.fail(gk, "expected an object with map, size, seed, spread, scale, sigma, eta, k");
        R.keys(g, gk, {"map", "size", "seed", "spread", "scale", "sigma", "eta", "k"});
        mat.glints = true;
        mat.glintMap = R.string(g, gk + ".map", "flakes");
        static const std::set<std::string> kinds{"flat", "flakes", "scratches", "brushed", "bumps"};
        if (!kinds.count(mat.glintMap)) mat.glintMap = R.existingPath(dir, mat.glintMap, gk + ".map");
        mat.glintMapSize = uint32_t(R.number(g, gk + ".size", 512, 1, 4096));
        mat.glintMapSeed = uint32_t(R.number(g, gk + ".seed", 1, 0, 4e9f));
        mat.glintSpread = R.number(g, gk + ".spread", 0.15f, 0, 1.5f);
        mat.glintScale = R.number(g, gk + ".scale", 4, 1e-3f, 1e4f);
        mat.glintSigma = R.number(g, gk + ".sigma", 0.05f, 0.005f, 1.0f);
        mat.glintEta = R.vec3(g, gk + ".eta", mat.glintEta);
        mat.glintK = R.vec3(g, gk + ".k", mat.glintK);
      }
      matIndex[mat.name] = uint32_t(s.materials.size());
      s.materials.push_back(mat);
    }
  }
  if (s.materials.empty()) s.materials.push_back(Material{"default"});
  if (isGlintsTechnique(s.technique))
    for (size_t i = 0; i < s.materials.size(); ++i)
      if (!s.materials[i].glints)
        R.fail("materials[" + std::to_string(i) + "].glints",
               "technique " + s.technique + " shades every material as a glinty conductor: material '" + s.materials[i].name +
                   "' has no glints block (\"glints\": {\"map\": \"flat\"} is a smooth one)");

  if (!j.contains("objects") || !j["objects"].is_array() || j["objects"].empty())
    R.fail("objects", "expected a non-empty array of objects");
  std::map<std::string, uint32_t> meshIndex;
  for (size_t i = 0; i < j["objects"].size(); ++i) {
    const json& o = j["objects"][i];
    const std::string key = "objects[" + std::to_string(i) + "]";
    R.keys(o, key, {"name", "mesh", "material", "fit", "translate", "rotate_y", "scale"});
    Object obj;
    const std::string spec = R.string(o, key + ".mesh", "", true);
    obj.name = R.string(o, key + ".name", spec);
    if (!meshIndex.count(spec)) {
      Mesh mesh;
      try {
        if (spec == "sphere") mesh = makeSphere();
        else if (spec == "plane") mesh = makePlane();
        else if (spec == "torus") mesh = makeTorus();
        else if (spec == "npm:bunny") mesh = loadNpmMesh((root / "assets/npm/bunny/index.js").string());
        else if (spec == "npm:teapot") mesh = loadNpmMesh((root / "assets/npm/teapot/teapot.js").string());
        else if (spec.ends_with(".gltf") || spec.ends_with(".glb")) {
          mesh = loadGltf(R.existingPath(dir, spec, key + ".mesh"));
        } else {
          R.fail(key + ".mesh", "unknown mesh '" + spec + "' (expected sphere, plane, torus, npm:bunny, npm:teapot or a .gltf/.glb path)");
        }
      } catch (const MeshError& e) {
        R.fail(key + ".mesh", e.what());
      }
      meshIndex[spec] = uint32_t(s.meshes.size());
      s.meshes.push_back(std::move(mesh));
    }
    obj.mesh = meshIndex[spec];
    const std::string mname = R.string(o, key + ".material", s.materials[0].name);
    if (!matIndex.empty() || j.contains("materials")) {
      if (!matIndex.count(mname)) R.fail(key + ".material", "no material named '" + mname + "'");
      obj.material = matIndex[mname];
    }
    // model = translate * rotateY * scale * fit; fit: largest extent -> `fit`, centred in x/z, base at y = 0
    Mat4 fitM = identity();
    if (o.contains("fit")) {
      float size = R.number(o, key + ".fit", 1, 1e-6f, 1e6f);
      auto b = meshBounds(s.meshes[obj.mesh]);
      float ext = std::max({b[1][0] - b[0][0], b[1][1] - b[0][1], b[1][2] - b[0][2]});
      float k = size / ext;
      fitM = mul(scale(k), translate({-(b[0][0] + b[1][0]) / 2, -b[0][1], -(b[0][2] + b[1][2]) / 2}));
    }
    obj.model = mul(translate(R.vec3(o, key + ".translate", {0, 0, 0})),
                    mul(rotateY(R.number(o, key + ".rotate_y", 0, -1e4f, 1e4f)),
                        mul(scale(R.number(o, key + ".scale", 1, 1e-6f, 1e6f)), fitM)));
    s.objects.push_back(obj);
  }
  if (const std::string refusal = techniqueRefusal(s, s.technique); !refusal.empty()) R.fail("technique", refusal);
  return s;
}

}  // namespace shadetwin
