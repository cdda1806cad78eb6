// The bad-input table (issue 20, item 3; docs/RESULTS.md "Bad input"): one test per row. Every row is either a clear
// error naming the file, the place and the problem, or a documented, counted sanitisation whose result is checked.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "emu/device_profile.h"
#include "inputs/environment.h"
#include "inputs/shade_inputs.h"
#include "passes/gbuffer.h"
#include "passes/shade.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "util/image_io.h"

namespace {
namespace fs = std::filesystem;
using shadetwin::FileError;

// <tmp>/bad_input/scenes/ for the inputs and <tmp>/bad_input/assets -> the checkout's assets/ (a scene's
// "../assets/..." resolves as for the shipped scenes).
const fs::path& dir() {
  static const fs::path d = [] {
    // One folder per process (ctest runs this file's tests as parallel processes), removed when the process ends.
    const fs::path root = fs::path(testing::TempDir()) / ("shadetwin_bad_input_" + std::to_string(::getpid()));
    fs::create_directories(root / "scenes");
    static struct Cleanup {
      fs::path p;
      ~Cleanup() {
        std::error_code ec;
        fs::remove_all(p, ec);
      }
    } cleanup{root};
    std::error_code ec;
    fs::create_directory_symlink(fs::path(SHADETWIN_SOURCE_DIR) / "assets", root / "assets", ec);
    return root / "scenes";
  }();
  return d;
}

std::string write(const std::string& name, const std::string& bytes) {
  const fs::path p = dir() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}

std::string slurp(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// The message of what `f` throws ("" if it does not throw).
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_MENTIONS(msg, part) EXPECT_NE(std::string(msg).find(part), std::string::npos) << "message: " << (msg)

// A small image written by OpenImageIO with the given channel names (float pixels 0.25 * (channel + 1)).
std::string image(const std::string& name, int w, int h, std::vector<std::string> channels) {
  const std::string p = (dir() / name).string();
  OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  std::vector<float> px(size_t(w) * h * channels.size());
  for (size_t i = 0; i < px.size(); ++i) px[i] = 0.25f * float(i % channels.size() + 1);
  auto out = OIIO::ImageOutput::create(p);
  EXPECT_TRUE(out && out->open(p, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close()) << p;
  return p;
}

const std::string kOkScene = R"("camera": {"eye": [0, 0, 3], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/studio.exr"})";

std::vector<float> shadeWith(shadetwin::Scene s, const shadetwin::EnvironmentMap& env, const std::string& technique) {
  shadetwin::setTechnique(s, technique);
  const emu::DeviceProfile& dev = emu::lavapipeProfile();
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev);
  return shadetwin::shadeEmu(s, g, shadetwin::shadeInputsEmu(s, *env.texture, dev), dev);
}

size_t nonFinite(const std::vector<float>& v) {
  size_t n = 0;
  for (float x : v) n += !std::isfinite(x);
  return n;
}
}  // namespace

// ---- images ----

TEST(BadInput, TruncatedImagesAreErrorsNamingTheFile) {
  for (const char* ext : {"exr", "hdr", "png"}) {
    const std::string whole = image(std::string("whole.") + ext, 64, 32, {"R", "G", "B"});
    const std::string bytes = slurp(whole);
    for (double keep : {0.5, 0.1}) {
      const std::string cut = write(std::string("truncated.") + ext, bytes.substr(0, size_t(double(bytes.size()) * keep)));
      const std::string e = errorOf([&] { shadetwin::loadImageRGBA(cut); });
      EXPECT_MENTIONS(e, cut);
    }
  }
}

TEST(BadInput, CorruptImagesAreErrorsNamingTheFile) {
  // EXR (zip-compressed blocks) and PNG (CRC per chunk) detect a damaged block; HDR's header is checked (its RLE pixels
  // carry no checksum: a damaged run decodes to other finite values, which no reader can tell: a documented limit).
  for (const char* ext : {"exr", "png"}) {
    std::string bytes = slurp(image(std::string("good.") + ext, 64, 32, {"R", "G", "B"}));
    // In the pixel data (both formats keep it at the end; PNG's last 12 bytes are the IEND chunk).
    for (size_t i = bytes.size() * 3 / 4; i + 16 < bytes.size(); ++i) bytes[i] = char(bytes[i] ^ 0x5a);
    const std::string bad = write(std::string("corrupt.") + ext, bytes);
    EXPECT_MENTIONS(errorOf([&] { shadetwin::loadImageRGBA(bad); }), bad);
  }
  const std::string hdr = slurp(image("good.hdr", 64, 32, {"R", "G", "B"}));
  const size_t res = hdr.find("-Y 32 +X 64");
  ASSERT_NE(res, std::string::npos);
  // (OpenImageIO's reader does not insist on the "#?" magic: a file whose magic alone is damaged still decodes.)
  for (const auto& [at, with] : {std::pair{res, std::string("-Q 32 +X 64")}, std::pair{res, std::string("-Y 32 +X 6x")}}) {
    std::string damaged = hdr;
    damaged.replace(at, with.size(), with);
    const std::string bad = write("corrupt.hdr", damaged);
    EXPECT_MENTIONS(errorOf([&] { shadetwin::loadImageRGBA(bad); }), bad) << "damaged at byte " << at;
  }
}

TEST(BadInput, ChannelSetsAreTakenByNameOrRefused) {
  auto first = [](const std::string& p) {
    const shadetwin::ImageRGBA im = shadetwin::loadImageRGBA(p);
    return std::array<float, 4>{im.texels[0], im.texels[1], im.texels[2], im.texels[3]};
  };
  using A = std::array<float, 4>;
  EXPECT_EQ(first(image("gray.exr", 4, 2, {"Y"})), (A{0.25f, 0.25f, 0.25f, 1.0f}));       // one channel: gray
  EXPECT_EQ(first(image("ya.exr", 4, 2, {"Y", "A"})), (A{0.25f, 0.25f, 0.25f, 0.5f}));   // luminance + alpha
  EXPECT_EQ(first(image("rgb.exr", 4, 2, {"R", "G", "B"})), (A{0.25f, 0.5f, 0.75f, 1.0f}));
  EXPECT_EQ(first(image("rgba.exr", 4, 2, {"R", "G", "B", "A"})), (A{0.25f, 0.5f, 0.75f, 1.0f}));
  EXPECT_EQ(first(image("rgbaz.exr", 4, 2, {"R", "G", "B", "A", "Z"})), (A{0.25f, 0.5f, 0.75f, 1.0f}));  // Z ignored
  const std::string rg = image("rg.exr", 4, 2, {"R", "G"});
  const std::string e = errorOf([&] { shadetwin::loadImageRGBA(rg); });
  EXPECT_MENTIONS(e, rg);
  EXPECT_MENTIONS(e, "2 channels (R, G): expected R, G, B");
}

TEST(BadInput, ZeroSizedAndHugeImagesAreRefusedBeforeDecoding) {
  const std::string zero = write("zero.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadImageRGBA(zero); }), zero);
  // A header that claims 200000 x 100000 (a few bytes of file): refused with the memory it would need, not allocated.
  const std::string huge = write("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n" + std::string(64, '\0'));
  const std::string e = errorOf([&] { shadetwin::loadImageRGBA(huge); });
  EXPECT_MENTIONS(e, huge);
  EXPECT_MENTIONS(e, "would need");
  EXPECT_THROW(shadetwin::environmentFromLevel0({}, 0, 0), std::invalid_argument);
}

TEST(BadInput, TinyAndThinEnvironmentsRenderEveryTechnique) {
  // 1x1, 1x4096, 4096x1 and 3x2 maps: their MIP chains, paraboloid atlas, SH, lights and kd-tree are built and every
  // technique shades finite pixels (glints are their own scene kind: tests/shade_glints_test.cpp).
  shadetwin::Scene s = shadetwin::loadScene(std::string(SHADETWIN_SOURCE_DIR) + "/scenes/spheres.json");
  s.width = 24, s.height = 16, s.fisFaceSize = 8, s.envBlocks = 64, s.visMaps = 0;
  for (auto [w, h] : {std::pair{1u, 1u}, {1u, 4096u}, {4096u, 1u}, {3u, 2u}}) {
    std::vector<float> texels(size_t(w) * h * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = i % 4 == 3 ? 1.0f : 0.5f + 0.25f * float(i % 7);
    const shadetwin::EnvironmentMap env = shadetwin::environmentFromLevel0(texels, w, h);
    for (const char* t : {"fis", "unfiltered", "stochastic", "env", "mirror", "kdtree-mis", "alias-mis", "inversion-mis"}) {
      const std::vector<float> img = shadeWith(s, env, t);
      ASSERT_EQ(img.size(), size_t(s.width) * s.height * 4);
      EXPECT_EQ(nonFinite(img), 0u) << w << "x" << h << " " << t;
      double sum = 0;
      for (float v : img) sum += v;
      EXPECT_GT(sum, 0.0) << w << "x" << h << " " << t;
    }
  }
}

TEST(BadInput, NonFiniteTexelsBecomeZeroAndNegativeOnesAreCountedOrClamped) {
  std::vector<float> t(4 * 4 * 4, 1.0f);
  t[0] = NAN, t[5] = INFINITY, t[6] = -INFINITY, t[9] = -5.0f, t[13] = -0.5f;
  const shadetwin::EnvironmentMap keep = shadetwin::environmentFromLevel0(t, 4, 4);
  EXPECT_EQ(keep.nonFinite, 3u);
  EXPECT_EQ(keep.negative, 2u);
  EXPECT_EQ(keep.levels[0][0], 0.0f);
  EXPECT_EQ(keep.levels[0][9], -5.0f);  // kept: the default (real data in the CC0 maps)
  const shadetwin::EnvironmentMap clamp = shadetwin::environmentFromLevel0(t, 4, 4, true);
  EXPECT_EQ(clamp.negative, 2u);
  EXPECT_EQ(clamp.levels[0][9], 0.0f);
  EXPECT_EQ(clamp.levels[0][13], 0.0f);
  for (const auto& level : clamp.levels)
    for (float v : level) EXPECT_GE(v, 0.0f);
  // Through a scene: "negative": "clamp" turns a -5 texel's contribution off; "keep" lets it through (documented).
  shadetwin::Scene s = shadetwin::loadScene(write("neg.json", "{" + kOkScene.substr(0, kOkScene.size() - 1) +
                                                                  R"(, "negative": "clamp"}, "objects": [{"mesh": "sphere"}]})"));
  EXPECT_TRUE(s.envClampNegative);
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(write("neg2.json", "{" + kOkScene.substr(0, kOkScene.size() - 1) +
                                                                             R"(, "negative": "abs"}})")); }),
                  "environment.negative: unknown policy 'abs' (expected keep or clamp)");
  std::vector<float> neg(8 * 4 * 4, 1.0f);
  for (size_t i = 0; i < neg.size(); i += 4) neg[i] = -5.0f;  // red -5 everywhere: the background's red is -5 x intensity
  s.width = 16, s.height = 8;
  const std::vector<float> kept = shadeWith(s, shadetwin::environmentFromLevel0(neg, 8, 4), "mirror");
  const std::vector<float> clamped = shadeWith(s, shadetwin::environmentFromLevel0(neg, 8, 4, true), "mirror");
  EXPECT_LT(kept[0], 0.0f);
  EXPECT_EQ(clamped[0], 0.0f);
  EXPECT_EQ(clamped[1], kept[1]);
}

// ---- scene files ----

TEST(BadInput, MalformedTruncatedAndHugeSceneFiles) {
  const std::string good = "{" + kOkScene + R"(, "objects": [{"mesh": "sphere"}]})";
  const std::string malformed = write("malformed.json", "{" + kOkScene + R"(, "objects": [{"mesh": "sphere"},]})");
  std::string e = errorOf([&] { shadetwin::loadScene(malformed); });
  EXPECT_MENTIONS(e, malformed);
  EXPECT_MENTIONS(e, "not valid JSON");
  EXPECT_MENTIONS(e, "line 1");  // the place
  const std::string truncated = write("truncated.json", good.substr(0, good.size() / 2));
  e = errorOf([&] { shadetwin::loadScene(truncated); });
  EXPECT_MENTIONS(e, truncated);
  EXPECT_MENTIONS(e, "not valid JSON");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(write("empty.json", "")); }), "not valid JSON");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(write("array.json", "[1, 2]")); }), "top level: expected an object");
  // Huge: 17 MiB of whitespace before a valid scene is refused unread; 100,000 nested arrays parse (nlohmann's parser and
  // destructor are iterative) and fail on the key.
  const std::string huge = write("huge.json", std::string(17 << 20, ' ') + good);
  e = errorOf([&] { shadetwin::loadScene(huge); });
  EXPECT_MENTIONS(e, huge);
  EXPECT_MENTIONS(e, "scene file of 17 MiB (at most 16 MiB");
  const std::string deep = write("deep.json", "{" + kOkScene + ", \"description\": " + std::string(100000, '[') +
                                                  std::string(100000, ']') + "}");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(deep); }), deep);
}

TEST(BadInput, UnknownKeysAndWrongTypesNameTheKey) {
  auto err = [&](const std::string& name, const std::string& body) {
    return errorOf([&] { shadetwin::loadScene(write(name, body)); });
  };
  EXPECT_MENTIONS(err("k.json", "{" + kOkScene + R"(, "objects": [{"mesh": "sphere", "colour": 1}]})"),
                  "objects[0].colour: unknown key");
  EXPECT_MENTIONS(err("t1.json", "{" + kOkScene + R"(, "image": {"width": "wide"}})"), "image.width: expected a number, got \"wide\"");
  EXPECT_MENTIONS(err("t2.json", "{" + kOkScene + R"(, "objects": {"mesh": "sphere"}})"), "objects");
  EXPECT_MENTIONS(err("t3.json", R"({"camera": {"eye": [0, 0], "target": [0, 0, 0]}, "environment": {"file": "../assets/hdri/studio.exr"}})"),
                  "camera.eye");
  EXPECT_MENTIONS(err("t4.json", "{" + kOkScene + R"(, "fis": 40})"), "fis: expected an object");
  EXPECT_MENTIONS(err("t5.json", "{" + kOkScene + R"(, "fis": {"background": "sky"}})"),
                  "fis.background: unknown background 'sky' (expected: environment or atlas)");
  EXPECT_MENTIONS(err("t6.json", "{" + kOkScene + R"(, "fis": {"background": 1}})"), "fis.background: expected a string");
  const std::string sphere = R"(, "objects": [{"mesh": "sphere"}])";
  EXPECT_TRUE(shadetwin::loadScene(write("t7.json", "{" + kOkScene + sphere + R"(, "fis": {"background": "atlas"}})")).fisBackgroundAtlas);
  EXPECT_FALSE(shadetwin::loadScene(write("t8.json", "{" + kOkScene + sphere + "}")).fisBackgroundAtlas);
}

TEST(BadInput, SceneOverridesNameTheOptionAndTheScene) {
  // The command line's scene options (applyOverrides: one definition for every command that renders).
  const std::string path = write("ov.json", "{" + kOkScene + R"(, "objects": [{"mesh": "sphere"}]})");
  shadetwin::SceneOverrides o;
  o.visMaps = 4;
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(path, o); }), "--vis-maps: ");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(path, o); }), "ov.json has no \"visibility\" block");
  o = {};
  o.glintViews = "9x16";
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(path, o); }), "--glint-views: ");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(path, o); }), "ov.json has no glints materials");
  for (const char* bad : {"1x16", "9x0", "514x16", "9x1025", "9x16q", "9", "x16", "-3x16", ""}) {
    EXPECT_MENTIONS(errorOf([&] { shadetwin::parseGlintGrid(bad, "--glint-views"); }), "--glint-views: '" + std::string(bad) + "' is not RINGSxSECTORS") << bad;
  }
  EXPECT_EQ(shadetwin::parseGlintGrid("2x1", "f"), std::make_pair(2u, 1u));
  EXPECT_EQ(shadetwin::parseGlintGrid("513x1024", "f"), std::make_pair(513u, 1024u));
  o = {};
  o.technique = "phong";
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(path, o); }), "unknown technique 'phong'");
  o = {};
  o.technique = "kdtree-mis", o.width = 7, o.height = 5, o.samples = 3, o.blocks = 99;
  const shadetwin::Scene s = shadetwin::loadScene(path, o);
  EXPECT_EQ(s.technique, "kdtree-mis");
  EXPECT_EQ(s.width, 7u);
  EXPECT_EQ(s.height, 5u);
  EXPECT_EQ(s.misSamples, 3u);
  EXPECT_EQ(s.fisSamples, 3u);
  EXPECT_EQ(s.glintGxdSamples, 3u);
  EXPECT_EQ(s.envBlocks, 99u);
  const shadetwin::Scene plain = shadetwin::loadScene(path, shadetwin::SceneOverrides{});
  EXPECT_EQ(plain.technique, "fis");
  EXPECT_EQ(plain.fisSamples, 40u);
}

TEST(BadInput, CameraWithZeroFieldOfViewOrDegenerateFrameIsAnError) {
  const std::string env = R"("environment": {"file": "../assets/hdri/studio.exr"})";
  auto err = [&](const std::string& name, const std::string& camera) {
    return errorOf([&] { shadetwin::loadScene(write(name, "{\"camera\": " + camera + ", " + env + "}")); });
  };
  EXPECT_MENTIONS(err("fov0.json", R"({"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 0})"), "camera.fov: expected a number in [1");
  EXPECT_MENTIONS(err("fov180.json", R"({"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 180})"), "camera.fov");
  EXPECT_MENTIONS(err("same.json", R"({"eye": [0, 0, 0], "target": [0, 0, 0]})"), "camera.target: expected a point different");
  EXPECT_MENTIONS(err("up.json", R"({"eye": [0, 3, 0], "target": [0, 0, 0], "up": [0, 1, 0]})"), "camera.up");
  EXPECT_MENTIONS(err("nan.json", R"({"eye": [0, 0, NaN], "target": [0, 0, 0]})"), "not valid JSON");  // JSON has no NaN
}

TEST(BadInput, CameraInsideGeometryRendersTheInside) {
  // Inside the unit sphere: every pixel sees the sphere's back faces (the G-buffer draws both sides) and shades finite.
  shadetwin::Scene s = shadetwin::loadScene(
      write("inside.json", R"({"camera": {"eye": [0, 0, 0.2], "target": [0, 0, -1], "near": 0.01},
        "environment": {"file": "../assets/hdri/studio.exr"}, "image": {"width": 32, "height": 24},
        "objects": [{"mesh": "sphere"}]})"));
  std::ostringstream log;
  const shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  const emu::DeviceProfile& dev = emu::lavapipeProfile();
  const shadetwin::GBuffer g = shadetwin::gbufferEmu(s, dev);
  size_t covered = 0;
  for (size_t p = 0; p < size_t(g.width) * g.height; ++p) covered += g.texels[p * shadetwin::kGbufFloats + 3] != 0.0f;
  for (const char* t : {"fis", "mirror", "env", "kdtree-mis"}) {
    const std::vector<float> img = shadeWith(s, env, t);
    EXPECT_EQ(nonFinite(img), 0u) << t;
  }
  EXPECT_EQ(covered, size_t(g.width) * g.height);
}

TEST(BadInput, SampleCountsOutOfRangeNameTheKey) {
  for (const char* n : {"0", "1000000000"}) {
    EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(write("fis_n.json", "{" + kOkScene + R"(, "fis": {"samples": )" + n + "}}")); }),
                    "fis.samples: expected a number in [1");
    EXPECT_MENTIONS(errorOf([&] { shadetwin::loadScene(write("mis_n.json", "{" + kOkScene + R"(, "mis": {"samples": )" + n + "}}")); }),
                    "mis.samples: expected a number in [1");
  }
}

// ---- meshes ----

namespace {
std::string b64(const std::string& raw) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < raw.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(raw[i])) << 16;
    if (i + 1 < raw.size()) v |= uint32_t(uint8_t(raw[i + 1])) << 8;
    if (i + 2 < raw.size()) v |= uint8_t(raw[i + 2]);
    for (int c = 0; c < 4; ++c) out += i * 4 / 3 + size_t(c) <= (raw.size() * 4 + 2) / 3 ? k[(v >> (18 - 6 * c)) & 63] : '=';
  }
  return out;
}

// A glTF of `positions` (float3 each) and, when given, uint32 `indices`, mode `mode`; `uri` overrides the embedded buffer.
std::string gltf(const std::vector<float>& positions, const std::vector<uint32_t>& indices, int mode = 4,
                 const std::string& uri = "") {
  std::string raw(reinterpret_cast<const char*>(positions.data()), positions.size() * 4);
  const size_t posBytes = raw.size();
  raw += std::string(reinterpret_cast<const char*>(indices.data()), indices.size() * 4);
  const std::string u = uri.empty() ? "data:application/octet-stream;base64," + b64(raw) : uri;
  std::string j = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": )" + std::to_string(mode) +
                  (indices.empty() ? "" : R"(, "indices": 1)") + R"(}]}],
    "buffers": [{"byteLength": )" + std::to_string(raw.size()) + R"(, "uri": ")" + u + R"("}],
    "bufferViews": [{"buffer": 0, "byteLength": )" + std::to_string(posBytes) + "}";
  if (!indices.empty())
    j += R"(, {"buffer": 0, "byteOffset": )" + std::to_string(posBytes) + R"(, "byteLength": )" + std::to_string(indices.size() * 4) + "}";
  j += R"(], "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(positions.size() / 3) +
       R"(, "type": "VEC3"})";
  if (!indices.empty())
    j += R"(, {"bufferView": 1, "componentType": 5125, "count": )" + std::to_string(indices.size()) + R"(, "type": "SCALAR"})";
  return j + "]}";
}
const std::vector<float> kTri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
}  // namespace

TEST(BadInput, GltfWithMissingBuffersOrBadIndicesIsAnError) {
  const std::string missing = write("missing_buffer.gltf", gltf(kTri, {}, 4, "nothere.bin"));
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadGltf(missing); }), missing);
  const std::string bad = write("bad_index.gltf", gltf(kTri, {0, 1, 9}));
  const std::string e = errorOf([&] { shadetwin::validateMesh(shadetwin::loadGltf(bad), bad); });
  EXPECT_MENTIONS(e, bad);
  EXPECT_MENTIONS(e, "index 9 out of range (3 vertices)");
  const std::string cut = write("cut.gltf", gltf(kTri, {0, 1, 2}).substr(0, 200));
  EXPECT_MENTIONS(errorOf([&] { shadetwin::loadGltf(cut); }), cut);
}

TEST(BadInput, GltfWithNaNPositionsIsAnError) {
  const std::string p = write("nan.gltf", gltf({0, 0, 0, NAN, 0, 0, 0, 1, 0}, {}));
  const std::string e = errorOf([&] { shadetwin::validateMesh(shadetwin::loadGltf(p), p); });
  EXPECT_MENTIONS(e, p);
  EXPECT_MENTIONS(e, "non-finite vertex position");
}

TEST(BadInput, MeshesWithNoTrianglesAreAnError) {
  const std::string points = write("points.gltf", gltf(kTri, {}, 0));  // mode 0: points (skipped)
  EXPECT_MENTIONS(errorOf([&] { shadetwin::validateMesh(shadetwin::loadGltf(points), points); }), "mesh has no triangles");
  const std::string npm = write("empty.js", "exports.positions=[];exports.cells=[]");
  EXPECT_MENTIONS(errorOf([&] { shadetwin::validateMesh(shadetwin::loadNpmMesh(npm), npm); }), "mesh has no triangles");
}

TEST(BadInput, ZeroAreaAndDegenerateTrianglesAndMissingNormalsAndUvsAreCompleted) {
  // A real triangle, a zero-area one (three collinear points) and a degenerate one (a repeated vertex), positions only:
  // normals are generated (the zero-area triangles add nothing; a vertex only they use gets the fallback +y), UVs and
  // tangents too, all finite and unit length; the G-buffer draws it and shading is finite.
  const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0, 5, 5, 5};
  const std::string p = write("degenerate.gltf", gltf(pos, {0, 1, 2, 3, 4, 5, 6, 6, 6}));
  shadetwin::Mesh m = shadetwin::loadGltf(p);
  shadetwin::validateMesh(m, p);
  shadetwin::completeMesh(m);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (const auto& n : m.normals) {
    for (float c : n) EXPECT_TRUE(std::isfinite(c));
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-5f);
  }
  EXPECT_NEAR(m.normals[0][2], 1.0f, 1e-6f);  // the real triangle's normal
  EXPECT_EQ(m.normals[6][1], 1.0f);  // only in the degenerate triangle: the fallback
  shadetwin::Scene s = shadetwin::loadScene(
      write("degenerate.json", R"({"camera": {"eye": [0.3, 0.3, 3], "target": [0.3, 0.3, 0]}, "image": {"width": 24, "height": 16},
        "environment": {"file": "../assets/hdri/studio.exr"}, "objects": [{"mesh": "degenerate.gltf"}]})"));
  std::ostringstream log;
  const shadetwin::EnvironmentMap env = shadetwin::loadEnvironment(s.environment, log);
  EXPECT_EQ(nonFinite(shadeWith(s, env, "fis")), 0u);
}
