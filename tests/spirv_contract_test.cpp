// The exactness contract in the SPIR-V the Vulkan build runs: every float operation carries
// NoContraction, shared math uses no FDiv and no GLSL.std.450 transcendental, and modules validate:
// every module the build embeds (the passes' are optimised by spirv-opt after marking, CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {
std::string run(const std::string& cmd) {
  std::array<char, 4096> buf;
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  if (!p) return out;
  while (fgets(buf.data(), buf.size(), p.get())) out += buf.data();
  return out;
}
// The embedded modules: <name>.spv (not the build's intermediate .raw/.marked/.opt.spv).
std::vector<std::string> modules() {
  std::vector<std::string> m;
  for (const auto& e : std::filesystem::directory_iterator(SHADER_DIR)) {
    const std::string f = e.path().filename().string();
    if (f.size() > 4 && f.ends_with(".spv") && f.find('.') == f.size() - 4) m.push_back(f.substr(0, f.size() - 4));
  }
  std::sort(m.begin(), m.end());
  return m;
}
}  // namespace

TEST(SpirvContract, EveryPassModuleIsChecked) {
  const std::vector<std::string> m = modules();
  for (const char* want : {"verify_math_comp", "verify_texture_frag", "gbuffer_frag", "shade_fis_comp", "shade_env_mis_comp",
                           "shade_glints_comp", "glint_lighting_comp", "visibility_fit_comp", "mip_downsample", "calibrate_k0", "calibrate_k13", "calibrate_exmath_k1_dep"})
    EXPECT_TRUE(std::count(m.begin(), m.end(), want)) << want;
  EXPECT_GE(m.size(), 40u);
}

TEST(SpirvContract, EveryFloatOpIsNoContraction) {
  for (const std::string& m : modules()) {
    std::string dis = run(std::string(SPIRV_DIS) + " --raw-id " + SHADER_DIR + "/" + m + ".spv");
    ASSERT_FALSE(dis.empty()) << m;
    std::set<std::string> decorated, ops;
    std::regex dec(R"(OpDecorate (%\d+) NoContraction)"), op(R"((%\d+) = Op(FAdd|FSub|FMul|FDiv|VectorTimesScalar|Dot|FNegate) )");
    for (std::sregex_iterator it(dis.begin(), dis.end(), dec), end; it != end; ++it) decorated.insert((*it)[1]);
    for (std::sregex_iterator it(dis.begin(), dis.end(), op), end; it != end; ++it) ops.insert((*it)[1]);
    if (m.find("math") != std::string::npos || m.starts_with("shade_")) EXPECT_GT(ops.size(), 100u) << m;
    for (auto& id : ops) EXPECT_TRUE(decorated.count(id)) << m << ": " << id << " lacks NoContraction";
  }
}

// Every module but bench_native_* (the native functions the exact ones are timed against): no FDiv, no
// GLSL.std.450 function whose bits Vulkan leaves open, nor min/max/clamp/mix/fract, which the optimiser
// could have made out of selects (their NaN and -0 results are the implementation's).
TEST(SpirvContract, SharedMathUsesNoImplementationDefinedOps) {
  for (const std::string& m : modules()) {
    if (m.starts_with("bench_native_")) continue;
    std::string dis = run(std::string(SPIRV_DIS) + " " + SHADER_DIR + "/" + m + ".spv");
    ASSERT_FALSE(dis.empty()) << m;
    EXPECT_EQ(dis.find("OpFDiv"), std::string::npos) << m;
    for (const char* bad : {"Fma", "Sqrt", "InverseSqrt", "Normalize", "Exp ", "Exp2", "Log ", "Log2", "Pow", "Sin ", "Cos ",
                            "Atan2", "Acos", "Length", "FMin", "FMax", "NMin", "NMax", "FClamp", "NClamp", "FMix", "Fract"})
      EXPECT_EQ(dis.find(std::string("GLSL.std.450 ") + bad), std::string::npos) << m << ": " << bad;
  }
}

TEST(SpirvContract, ModulesValidate) {
  for (const std::string& m : modules())
    EXPECT_EQ(0, std::system((std::string(SPIRV_VAL) + " --target-env vulkan1.1 " + SHADER_DIR + "/" + m + ".spv").c_str())) << m;
}

// calibrate's microkernels: one module per kernel and chain layout, no other kernel's code in it (CMakeLists.txt). A
// driver that does not fold specialization constants (SwiftShader) ran every other kernel under a false mask in the
// one module there was: a fixed part of 130-220 ms in each rate run (docs/RESULTS.md, session 41). Each module may keep
// no specialization constant but the spec-branch kernel's DEPENDENT (kind 13) and, in the exact-math modules, the
// prelude's scene-BRDF constant; and each holds far fewer instructions than every kernel together.
TEST(SpirvContract, CalibrateModulesHoldOneKernelEach) {
  const std::regex calib(R"(calibrate_(exmath_)?k\d+(_dep)?)");
  std::vector<std::string> found;
  for (const std::string& m : modules())
    if (std::regex_match(m, calib)) found.push_back(m);
  EXPECT_EQ(found.size(), 25u + 9u + 4u);  // every kernel, the dependent layouts, 2 exact-math routines x 2 layouts
  const auto lines = [](const std::string& dis, const std::string& what) {
    size_t n = 0;
    for (size_t at = dis.find(what); at != std::string::npos; at = dis.find(what, at + 1)) ++n;
    return n;
  };
  size_t largest = 0;
  for (const std::string& m : found) {
    const std::string dis = run(std::string(SPIRV_DIS) + " --raw-id " + SHADER_DIR + "/" + m + ".spv");
    ASSERT_FALSE(dis.empty()) << m;
    const size_t spec = lines(dis, "OpSpecConstant"), insts = lines(dis, "\n");
    if (m == "calibrate_k13") EXPECT_GT(spec, 0u) << m << ": the spec-branch kernel measures a specialization constant";
    else if (m.starts_with("calibrate_exmath")) EXPECT_LE(spec, 1u) << m;
    else EXPECT_EQ(spec, 0u) << m;
    largest = std::max(largest, insts);
  }
  // The kernels differ in size (a chain of 128 steps against one lookup a step), but none holds the others: the raw
  // module of every kernel has ~24,000 lines, the largest kernel's module under 3,000.
  const std::string all = run(std::string(SPIRV_DIS) + " --raw-id " + SHADER_DIR + "/calibrate_k0.raw.spv");
  EXPECT_LT(5 * largest, lines(all, "\n")) << "a calibrate module holds more than its kernel";
  EXPECT_GT(largest, 0u);
}
