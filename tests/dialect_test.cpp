// The shading dialect's source rules that the compilers cannot check (shade/prelude.h): a local array is read and
// written through arrayGet / arraySet unless its index is a literal, so the counting build sees every access a device
// makes at a run-time index (private_read / private_write, model/op_count.h). Every shared header is scanned.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

// The text without comments (line comments and block comments), lines kept.
std::string stripComments(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s.compare(i, 2, "//") == 0) {
      while (i < s.size() && s[i] != '\n') ++i;
      if (i < s.size()) out += '\n';
    } else if (s.compare(i, 2, "/*") == 0) {
      const size_t e = s.find("*/", i + 2);
      for (size_t j = i; j < std::min(e, s.size()); ++j)
        if (s[j] == '\n') out += '\n';
      i = e == std::string::npos ? s.size() : e + 1;
    } else {
      out += s[i];
    }
  }
  return out;
}

// Subscripts of a source that are neither an array's declaration (`Float c[N];`, a literal or constant size) nor at an
// integer literal: "line: text" for each.
std::vector<std::string> rawSubscripts(const std::string& source) {
  static const std::regex decl(R"(^\s*(?:Float[234]?|Int|Uint|Mask|float|int|uint)\s+\w+\s*\[[^\]]*\]\s*;\s*$)");
  static const std::regex subscript(R"(\w\s*\[([^\]]*)\])");
  static const std::regex literal(R"(^\s*\d+u?\s*$)");
  std::vector<std::string> found;
  std::istringstream in(stripComments(source));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (std::regex_match(line, decl)) continue;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), subscript); it != std::sregex_iterator(); ++it)
      if (!std::regex_match((*it)[1].str(), literal)) {
        found.push_back(std::to_string(n) + ": " + line);
        break;
      }
  }
  return found;
}

TEST(Dialect, TheCheckFindsARawSubscriptAndAcceptsTheAccessors) {
  EXPECT_EQ(rawSubscripts("  Float c[6 * (kMax + 1)];\n  Float d[4];\n").size(), 0u);
  EXPECT_EQ(rawSubscripts("  arraySet(col.c, i + 0, arrayGet(col.c, i + 0) + w);\n  x = a[3];\n").size(), 0u);
  EXPECT_EQ(rawSubscripts("  // col.c[i] in a comment\n  /* D[l] */ y = 1;\n").size(), 0u);
  EXPECT_EQ(rawSubscripts("  y = 1;\n  col.c[i + 0] = col.c[i + 0] + w;\n").size(), 1u);
  EXPECT_EQ(rawSubscripts("  x = kl[l];\n").front(), "1:   x = kl[l];");
  EXPECT_EQ(rawSubscripts("  s = f(s, g.a[l - m]);\n").size(), 1u);
}

TEST(Dialect, SharedHeadersIndexLocalArraysOnlyThroughTheAccessors) {
  const std::filesystem::path dir = std::filesystem::path(SHADETWIN_SOURCE_DIR) / "src" / "shade";
  int scanned = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "prelude.h") continue;  // defines the accessors (its C++ side indexes the arrays they are given)
    std::ifstream f(e.path());
    ASSERT_TRUE(f) << e.path();
    std::stringstream ss;
    ss << f.rdbuf();
    for (const std::string& hit : rawSubscripts(ss.str())) ADD_FAILURE() << name << ":" << hit;
    ++scanned;
  }
  EXPECT_GE(scanned, 20);
}

}  // namespace
