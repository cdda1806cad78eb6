// Scene files and meshes: the shipped scenes load; bad input names the file, the key and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scene/mesh.h"
#include "scene/scene.h"

namespace {

std::string src(const std::string& p) { return std::string(SHADETWIN_SOURCE_DIR) + "/" + p; }

std::string writeTemp(const std::string& name, const std::string& text) {
  auto dir = std::filesystem::path(SHADETWIN_SOURCE_DIR) / "build-test-scenes";
  std::filesystem::create_directories(dir);
  auto p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

std::string errorOf(const std::string& path) {
  try {
    shadetwin::loadScene(path);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, ShippedScenesLoad) {
  for (const char* name : {"bunny", "spheres", "teapot"}) {
    shadetwin::Scene s = shadetwin::loadScene(src(std::string("scenes/") + name + ".json"));
    EXPECT_GT(s.triangles(), 100u) << name;
    EXPECT_TRUE(std::filesystem::exists(s.environment)) << name;
    for (auto& m : s.meshes) {
      EXPECT_EQ(m.normals.size(), m.positions.size());
      EXPECT_EQ(m.tangents.size(), m.positions.size());
      EXPECT_EQ(m.uvs.size(), m.positions.size());
    }
  }
  shadetwin::Scene b = shadetwin::loadScene(src("scenes/bunny.json"));
  auto bounds = b.bounds();
  EXPECT_NEAR(bounds[0][1], 0.0f, 1e-5f);  // "fit": base at y = 0
}

TEST(Scene, NpmMeshesAreTheRealOnes) {
  shadetwin::Mesh bunny = shadetwin::loadNpmMesh(src("assets/npm/bunny/index.js"));
  EXPECT_EQ(bunny.positions.size(), 1839u);  // the npm `bunny` package (Stanford bunny, reduced)
  EXPECT_EQ(bunny.triangles(), 3674u);
  shadetwin::Mesh teapot = shadetwin::loadNpmMesh(src("assets/npm/teapot/teapot.js"));
  EXPECT_EQ(teapot.triangles(), 992u);  // the npm `teapot` package (Utah teapot, 32 patches)
  for (auto& n : bunny.normals) EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5);
}

TEST(Scene, ErrorsNameFileKeyAndExpectation) {
  const std::string ok = R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/forest.exr"})";
  std::string p = writeTemp("a.json", "{" + ok + R"(, "objects": [{"mesh": "cube"}]})");
  std::string e = errorOf(p);
  EXPECT_NE(e.find(p), std::string::npos) << e;
  EXPECT_NE(e.find("objects[0].mesh"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown mesh 'cube'"), std::string::npos) << e;

  p = writeTemp("b.json", "{" + ok + R"(, "objects": [{"mesh": "sphere"}], "camera_fov": 3})");
  EXPECT_NE(errorOf(p).find("camera_fov: unknown key"), std::string::npos) << errorOf(p);

  p = writeTemp("c.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": "wide"}, "environment": {"file": "../assets/hdri/forest.exr"}, "objects": [{"mesh": "sphere"}]})");
  EXPECT_NE(errorOf(p).find("camera.fov: expected a number"), std::string::npos) << errorOf(p);

  p = writeTemp("d.json", R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/nothere.exr"}, "objects": [{"mesh": "sphere"}]})");
  e = errorOf(p);
  EXPECT_NE(e.find("environment.file: file not found"), std::string::npos) << e;
  EXPECT_NE(e.find("scripts/setup.sh"), std::string::npos) << e;

  p = writeTemp("e.json", "{ \"camera\": ");
  EXPECT_NE(errorOf(p).find("not valid JSON"), std::string::npos) << errorOf(p);

  p = writeTemp("f.json", "{" + ok + R"(, "objects": [{"mesh": "sphere", "material": "gold"}], "materials": [{"name": "steel"}]})");
  EXPECT_NE(errorOf(p).find("objects[0].material: no material named 'gold'"), std::string::npos) << errorOf(p);

  EXPECT_NE(errorOf(src("scenes/missing.json")).find("cannot open scene file"), std::string::npos);
}

TEST(Scene, MisBlock) {
  const shadetwin::Scene w = shadetwin::loadScene(src("scenes/ward_spheres.json"));
  EXPECT_EQ(w.technique, "kdtree-mis");
  EXPECT_EQ(w.misSamples, 16u);
  EXPECT_EQ(w.misHeuristic, 1u);  // power
  EXPECT_EQ(w.envBlocks, 6144u);
  EXPECT_EQ(w.misSeed, 1u);
  const std::string ok = R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/forest.exr"}, "objects": [{"mesh": "sphere"}])";
  std::string p = writeTemp("mis1.json", "{" + ok + R"(, "technique": "alias-mis", "mis": {"heuristic": "balance", "blocks": 64, "samples": 3}})");
  const shadetwin::Scene s = shadetwin::loadScene(p);
  EXPECT_EQ(s.misHeuristic, 0u);
  EXPECT_EQ(s.envBlocks, 64u);
  EXPECT_EQ(s.misSamples, 3u);
  p = writeTemp("mis2.json", "{" + ok + R"(, "mis": {"heuristic": "max"}})");
  EXPECT_NE(errorOf(p).find("mis.heuristic: unknown heuristic 'max'"), std::string::npos) << errorOf(p);
  p = writeTemp("mis3.json", "{" + ok + R"(, "mis": {"blocks": 0}})");
  EXPECT_NE(errorOf(p).find("mis.blocks"), std::string::npos) << errorOf(p);
  p = writeTemp("mis4.json", "{" + ok + R"(, "mis": {"sample": 4}})");
  EXPECT_NE(errorOf(p).find("mis.sample: unknown key"), std::string::npos) << errorOf(p);
  p = writeTemp("mis5.json", "{" + ok + R"(, "technique": "kd-tree"})");
  EXPECT_NE(errorOf(p).find("kdtree-mis"), std::string::npos) << errorOf(p);  // the message lists the techniques
}

TEST(Scene, RotateAboutOwnAxis) {
  // model: scale 2, translate (3, 1, -2). A 90-degree turn maps the object's +x to world -z (right-handed
  // about +y), keeps its origin and up axis; 360 degrees is the identity up to rounding.
  shadetwin::Mat4 m{};
  m[0] = 2, m[5] = 2, m[10] = 2, m[12] = 3, m[13] = 1, m[14] = -2, m[15] = 1;
  const shadetwin::Mat4 r = shadetwin::rotateAboutOwnAxis(m, 90);
  EXPECT_NEAR(r[0], 0, 1e-6);
  EXPECT_NEAR(r[2], -2, 1e-6);  // column 0 (object x) = world -z, length 2
  EXPECT_NEAR(r[8], 2, 1e-6);   // column 2 (object z) = world +x
  EXPECT_EQ(r[5], 2.0f);
  EXPECT_EQ(r[12], 3.0f);
  EXPECT_EQ(r[13], 1.0f);
  EXPECT_EQ(r[14], -2.0f);
  const shadetwin::Mat4 full = shadetwin::rotateAboutOwnAxis(m, 360);
  for (size_t i = 0; i < 16; ++i) EXPECT_NEAR(full[i], m[i], 1e-5) << i;
}

TEST(Scene, VisibilityBlock) {
  const shadetwin::Scene b = shadetwin::loadScene(src("scenes/bunny.json"));  // the default scene uses it
  EXPECT_EQ(b.visMaps, 16u);
  EXPECT_EQ(b.visSize, 1024u);
  EXPECT_TRUE(b.visFitCosine);
  EXPECT_TRUE(b.visFilterEdge);
  EXPECT_EQ(b.visFilterRadius, 2u);
  const std::string ok = R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/forest.exr"}, "objects": [{"mesh": "sphere"}])";
  std::string p = writeTemp("vis1.json", "{" + ok + R"(, "visibility": {"maps": 4, "size": 256, "fit": "v", "filter": "none", "bias": 2}})");
  const shadetwin::Scene s = shadetwin::loadScene(p);
  EXPECT_EQ(s.visMaps, 4u);
  EXPECT_FALSE(s.visFitCosine);
  EXPECT_EQ(s.visFilterRadius, 0u);
  EXPECT_EQ(s.visBias, 2.0f);
  EXPECT_EQ(shadetwin::loadScene(writeTemp("vis0.json", "{" + ok + "}")).visMaps, 0u);  // no block: no shadow pass
  p = writeTemp("vis2.json", "{" + ok + R"(, "visibility": {"fit": "cos"}})");
  EXPECT_NE(errorOf(p).find("visibility.fit: unknown fit 'cos'"), std::string::npos) << errorOf(p);
  p = writeTemp("vis3.json", "{" + ok + R"(, "visibility": {"map": 4}})");
  EXPECT_NE(errorOf(p).find("visibility.map: unknown key"), std::string::npos) << errorOf(p);
  p = writeTemp("vis4.json", "{" + ok + R"(, "visibility": {"maps": 0}})");
  EXPECT_NE(errorOf(p).find("visibility.maps"), std::string::npos) << errorOf(p);
  p = writeTemp("vis5.json", "{" + ok + R"(, "technique": "env", "visibility": {}})");
  EXPECT_NE(errorOf(p).find("technique env does not read visibility"), std::string::npos) << errorOf(p);
  p = writeTemp("vis6.json", "{" + ok + R"(, "visibility": {"filter": "gauss"}})");
  EXPECT_NE(errorOf(p).find("visibility.filter: unknown filter 'gauss'"), std::string::npos) << errorOf(p);
}

TEST(Scene, LafortuneLobesAndMaterialMaps) {
  const std::string head = R"({"camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/forest.exr"}, "objects": [{"mesh": "sphere", "material": "m"}], "materials": [)";
  auto scene = [&](const std::string& name, const std::string& material) { return writeTemp(name, head + material + "]}"); };
  std::string e = errorOf(scene("l1.json", R"({"name": "m", "brdf": "lafortune"})"));
  EXPECT_NE(e.find("materials[0].lobes: missing"), std::string::npos) << e;
  e = errorOf(scene("l2.json", R"({"name": "m", "brdf": "ggx", "lobes": [{"c": [-1, -1, 1], "n": 10, "rho": 1}]})"));
  EXPECT_NE(e.find("only a lafortune material has lobes"), std::string::npos) << e;
  e = errorOf(scene("l3.json", R"({"name": "m", "brdf": "lafortune", "lobes": [{}, {}, {}]})"));
  EXPECT_NE(e.find("1 or 2 lobes"), std::string::npos) << e;
  e = errorOf(scene("l4.json", R"({"name": "m", "brdf": "lafortune", "lobes": [{"c": [-1, -1, 1], "n": -3}]})"));
  EXPECT_NE(e.find("materials[0].lobes[0].n: expected a number in [0"), std::string::npos) << e;
  e = errorOf(scene("l5.json", R"({"name": "m", "brdf": "lafortune", "lobes": [{"c": [-1, -1, 1], "exponent": 3}]})"));
  EXPECT_NE(e.find("lobes[0].exponent: unknown key"), std::string::npos) << e;
  const std::string ok = scene("l6.json", R"({"name": "m", "brdf": "lafortune", "lobes": [{"c": [-1, -1, 1], "n": 30, "rho": 5}, {"c": [0.5, 0.5, 0.8], "n": 2}]})");
  const shadetwin::Scene s = shadetwin::loadScene(ok);
  ASSERT_EQ(s.materials[0].lobes.size(), 2u);
  EXPECT_EQ(s.materials[0].lobes[0].n, 30.0f);
  EXPECT_EQ(s.materials[0].lobes[1].c[2], 0.8f);
  EXPECT_EQ(s.materials[0].lobes[1].rho, 1.0f);  // default

  e = errorOf(scene("m1.json", R"({"name": "m", "diffuse_map": "../assets/textures/nothere.exr"})"));
  EXPECT_NE(e.find("materials[0].diffuse_map: file not found"), std::string::npos) << e;
  EXPECT_NE(e.find("scripts/setup.sh"), std::string::npos) << e;
  e = errorOf(scene("m2.json", R"({"name": "m", "brdf": "phong", "roughness_map": "../assets/textures/roughness_ramp.exr"})"));
  EXPECT_NE(e.find("a roughness map needs brdf ward or ggx"), std::string::npos) << e;
  const shadetwin::Scene t = shadetwin::loadScene(src("scenes/textured.json"));
  EXPECT_TRUE(std::filesystem::exists(t.materials[0].diffuseMap)) << t.materials[0].diffuseMap;
  EXPECT_TRUE(t.materials[2].hasMaps());
}

TEST(Mesh, BadNpmModuleAndIndices) {
  std::string p = writeTemp("bad.js", "exports.positions=[[0,0,0],[1,0,0],[0,1,0]];exports.cells=[[0,1,7]]");
  try {
    shadetwin::loadNpmMesh(p);
    FAIL() << "no error";
  } catch (const shadetwin::MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("index 7 out of range"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos);
  }
  p = writeTemp("bad2.js", "exports.positions=[[0,0,0]");
  EXPECT_THROW(shadetwin::loadNpmMesh(p), shadetwin::MeshError);
  EXPECT_THROW(shadetwin::loadGltf(writeTemp("bad.gltf", "{}")), shadetwin::MeshError);
}

TEST(Mesh, GltfRoundTripMinimal) {
  // A one-triangle glTF with an embedded base64 buffer: positions only; normals/UVs/tangents generated.
  // buffer: 3 x vec3 float = 36 bytes.
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string raw(reinterpret_cast<const char*>(pos), 36);
  static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string enc;
  for (size_t i = 0; i < raw.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(raw[i])) << 16 | uint32_t(uint8_t(raw[i + 1])) << 8 | uint8_t(raw[i + 2]);
    for (int k = 3; k >= 0; --k) enc += b64[(v >> (6 * k)) & 63];
  }
  std::string gltf = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "translation": [0, 2, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + enc + R"("}]})";
  shadetwin::Mesh m = shadetwin::loadGltf(writeTemp("tri.gltf", gltf));
  ASSERT_EQ(m.triangles(), 1u);
  EXPECT_EQ(m.positions[1][0], 1.0f);
  EXPECT_EQ(m.positions[2][1], 3.0f);  // node translation applied
  EXPECT_NEAR(m.normals[0][2], 1.0f, 1e-6f);
}

}  // namespace

TEST(Scene, GlintsBlocks) {
  const shadetwin::Scene g = shadetwin::loadScene(src("scenes/glints.json"));
  EXPECT_EQ(g.technique, "glints");
  EXPECT_EQ(g.glintOrder, 16u);
  EXPECT_NEAR(g.glintThetaMax, 40.0f * 3.14159265f / 180.0f, 1e-6f);
  ASSERT_EQ(g.materials.size(), 3u);
  EXPECT_TRUE(g.materials[0].glints);
  EXPECT_EQ(g.materials[0].glintMap, "flakes");
  EXPECT_EQ(g.materials[1].glintMap, "scratches");
  EXPECT_FLOAT_EQ(g.materials[1].glintSigma, 0.05f);
  EXPECT_FLOAT_EQ(g.materials[2].glintEta[0], 2.87f);
  EXPECT_EQ(g.glintViewRings, 65u);  // the default view grid of the lighting table
  EXPECT_EQ(g.glintViewSectors, 128u);
  shadetwin::SceneOverrides views;  // --glint-views replaces it and nothing else
  views.glintViews = "9x16";
  const shadetwin::Scene v = shadetwin::loadScene(src("scenes/glints.json"), views);
  EXPECT_EQ(v.glintViewRings, 9u);
  EXPECT_EQ(v.glintViewSectors, 16u);
  EXPECT_EQ(v.glintOrder, g.glintOrder);
  EXPECT_EQ(v.glintRings, g.glintRings);
  EXPECT_EQ(v.glintSectors, g.glintSectors);
  EXPECT_EQ(v.width, g.width);
  const std::string base = R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/forest.exr"}, "objects": [{"mesh": "sphere", "material": "m"}])";
  auto scene = [&](const std::string& name, const std::string& extra, const std::string& mat) {
    return writeTemp(name, "{" + base + extra + R"(, "materials": [{"name": "m")" + mat + "}]}");
  };
  std::string p = scene("gl1.json", R"(, "technique": "glints")", "");
  EXPECT_NE(errorOf(p).find("materials[0].glints"), std::string::npos) << errorOf(p);
  EXPECT_NE(errorOf(p).find("material 'm' has no glints block"), std::string::npos) << errorOf(p);
  p = scene("gl2.json", R"(, "technique": "glints", "glints": {"sectors": 12})", R"(, "glints": {"map": "flat"})");
  EXPECT_NE(errorOf(p).find("glints.sectors: expected a multiple of 8"), std::string::npos) << errorOf(p);
  p = scene("gl3.json", R"(, "technique": "glints")", R"(, "glints": {"map": "no_such_map.png"})");
  EXPECT_NE(errorOf(p).find("materials[0].glints.map"), std::string::npos) << errorOf(p);
  p = scene("gl4.json", R"(, "technique": "glints")", R"(, "glints": {"sigma": 0})");
  EXPECT_NE(errorOf(p).find("materials[0].glints.sigma"), std::string::npos) << errorOf(p);
  p = scene("gl5.json", R"(, "technique": "glints")", R"(, "glints": {"colour": 1})");
  EXPECT_NE(errorOf(p).find("materials[0].glints.colour: unknown key"), std::string::npos) << errorOf(p);
  const shadetwin::Scene ok = shadetwin::loadScene(scene("gl6.json", R"(, "technique": "glints", "glints": {"order": 8, "view_rings": 9})",
                                                        R"(, "glints": {"map": "bumps", "size": 64, "scale": 2})"));
  EXPECT_EQ(ok.glintOrder, 8u);
  EXPECT_EQ(ok.glintViewRings, 9u);
  EXPECT_EQ(ok.materials[0].glintMapSize, 64u);
  EXPECT_EQ(ok.glintGxdSamples, 64u);
  // The ground-truth technique: the same glints blocks required, its sample pairs a key.
  p = scene("gl7.json", R"(, "technique": "glints-gxd")", "");
  EXPECT_NE(errorOf(p).find("technique glints-gxd shades every material"), std::string::npos) << errorOf(p);
  const shadetwin::Scene gx = shadetwin::loadScene(scene("gl8.json", R"(, "technique": "glints-gxd", "glints": {"gxd_samples": 300})",
                                                        R"(, "glints": {"map": "flakes"})"));
  EXPECT_EQ(gx.technique, "glints-gxd");
  EXPECT_EQ(gx.glintGxdSamples, 300u);
  EXPECT_EQ(gx.glintLobeRings, 0u);  // default: the recurrences
  p = scene("gl11.json", R"(, "glints": {"lobe_rings": 65})", "");
  EXPECT_NE(errorOf(p).find("glints.lobe_rings: the rotated-lobe table needs"), std::string::npos) << errorOf(p);
  EXPECT_EQ(shadetwin::loadScene(scene("gl12.json", R"(, "glints": {"lobe_rings": 65, "lobe_sectors": 128})", "")).glintLobeSectors, 128u);
  p = scene("gl9.json", R"(, "glints": {"gxd_samples": 0})", "");
  EXPECT_NE(errorOf(p).find("glints.gxd_samples"), std::string::npos) << errorOf(p);
  // --technique on a command line: unknown names listed, a glints technique on a scene without glints blocks named.
  shadetwin::Scene plain = shadetwin::loadScene(scene("gl10.json", "", ""));
  try {
    shadetwin::setTechnique(plain, "glintz");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown technique 'glintz'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("glints-gxd"), std::string::npos) << e.what();
  }
  try {
    shadetwin::setTechnique(plain, "glints-gxd");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gl10.json: material 'm' has no glints block"), std::string::npos) << e.what();
  }
  EXPECT_EQ(plain.technique, "fis");  // unchanged
  shadetwin::setTechnique(plain, "mirror");
  EXPECT_EQ(plain.technique, "mirror");
}

// The mirror pass reads no material maps: --technique mirror on a scene with maps, and a scene file asking for mirror
// with maps, are refused up front (naming the scene and the material), not deep in the shading pass.
TEST(Scene, MirrorOnMaterialMapsIsRefusedNamingSceneAndMaterial) {
  const std::string textured = std::string(SHADETWIN_SOURCE_DIR) + "/scenes/textured.json";
  shadetwin::Scene s = shadetwin::loadScene(textured);
  EXPECT_EQ(shadetwin::techniqueRefusal(s, "fis"), "");
  EXPECT_EQ(shadetwin::techniqueRefusal(s, "env"), "");
  try {
    shadetwin::setTechnique(s, "mirror");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--technique mirror: " + textured + ": material 'checker_plastic' has material maps"),
              std::string::npos) << e.what();
  }
  EXPECT_EQ(s.technique, "fis");
  // The same in the file itself.
  const auto dir = std::filesystem::temp_directory_path() / "shadetwin_scene_mirror";
  std::filesystem::create_directories(dir);
  std::ifstream in(textured);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string fisKey = "\"technique\": \"fis\"";
  text.replace(text.find(fisKey), fisKey.size(), "\"technique\": \"mirror\"");
  const std::string root = std::string(SHADETWIN_SOURCE_DIR);
  for (size_t at; (at = text.find("\"../assets/")) != std::string::npos;) text.replace(at, 11, "\"" + root + "/assets/");
  const std::string p = (dir / "mirror_maps.json").string();
  std::ofstream(p) << text;
  try {
    shadetwin::loadScene(p);
    ADD_FAILURE() << "no error";
  } catch (const shadetwin::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(p + ": technique: " + p + ": material 'checker_plastic' has material maps"), std::string::npos)
        << e.what();
  }
}
