// The exactness contract in the SPIR-V the Vulkan build runs: every float operation carries
// NoContraction, shared math uses no FDiv and no GLSL.std.450 transcendental, and modules validate.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <regex>
#include <set>
#include <string>

namespace {
std::string run(const std::string& cmd) {
  std::array<char, 4096> buf;
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  if (!p) return out;
  while (fgets(buf.data(), buf.size(), p.get())) out += buf.data();
  return out;
}
const char* kModules[] = {"verify_math_comp", "verify_math_frag", "verify_texture_comp", "verify_texture_frag"};
}  // namespace

TEST(SpirvContract, EveryFloatOpIsNoContraction) {
  for (const char* m : kModules) {
    std::string dis = run(std::string(SPIRV_DIS) + " --raw-id " + SHADER_DIR + "/" + m + ".spv");
    ASSERT_FALSE(dis.empty()) << m;
    std::set<std::string> decorated, ops;
    std::regex dec(R"(OpDecorate (%\d+) NoContraction)"), op(R"((%\d+) = Op(FAdd|FSub|FMul|FDiv|VectorTimesScalar|Dot|FNegate) )");
    for (std::sregex_iterator it(dis.begin(), dis.end(), dec), end; it != end; ++it) decorated.insert((*it)[1]);
    for (std::sregex_iterator it(dis.begin(), dis.end(), op), end; it != end; ++it) ops.insert((*it)[1]);
    if (std::string(m).find("math") != std::string::npos) EXPECT_GT(ops.size(), 100u) << m;
    for (auto& id : ops) EXPECT_TRUE(decorated.count(id)) << m << ": " << id << " lacks NoContraction";
  }
}

TEST(SpirvContract, SharedMathUsesNoImplementationDefinedOps) {
  std::string dis = run(std::string(SPIRV_DIS) + " " + SHADER_DIR + "/verify_math_comp.spv");
  EXPECT_EQ(dis.find("OpFDiv"), std::string::npos);
  for (const char* bad : {"Fma", "Sqrt", "InverseSqrt", "Normalize", "Exp ", "Exp2", "Log ", "Log2", "Pow", "Sin ", "Cos ",
                          "Atan2", "Acos", "Length"})
    EXPECT_EQ(dis.find(std::string("GLSL.std.450 ") + bad), std::string::npos) << bad;
}

TEST(SpirvContract, ModulesValidate) {
  for (const char* m : kModules)
    EXPECT_EQ(0, std::system((std::string(SPIRV_VAL) + " --target-env vulkan1.1 " + SHADER_DIR + "/" + m + ".spv").c_str())) << m;
}
