// Loading the real CC0 HDRIs (fetched by scripts/setup.sh) and clear errors for bad files.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "util/image_io.h"

namespace {
std::string asset(const char* name) { return std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/" + name + ".exr"; }
}  // namespace

TEST(ImageIO, RealHdrisAreHardCases) {
  for (const char* n : {"forest", "courtyard", "studio", "city"}) {
    auto img = shadetwin::loadImageRGBA(asset(n));
    EXPECT_EQ(img.width, 1024u) << n;
    EXPECT_EQ(img.height, 512u) << n;
    size_t negative = 0;
    for (size_t i = 0; i < img.texels.size(); ++i) negative += (i % 4 != 3) && img.texels[i] < 0.0f;
    EXPECT_GT(negative, 0u) << n << " has negative texels (measured: forest 784, courtyard 1818, studio 3, city 506)";
  }
  auto city = shadetwin::loadImageRGBA(asset("city"));
  EXPECT_GT(*std::max_element(city.texels.begin(), city.texels.end()), 30000.0f);  // the sun: 33952
}

TEST(ImageIO, MissingAndBadFilesAreNamed) {
  try {
    shadetwin::loadImageRGBA(std::string(SHADETWIN_SOURCE_DIR) + "/assets/hdri/missing.exr");
    FAIL();
  } catch (const shadetwin::FileError& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("missing.exr: file not found"), std::string::npos) << m;
    EXPECT_NE(m.find("scripts/setup.sh"), std::string::npos) << m;
  }
  const std::string bad = testing::TempDir() + "/not_an_image.exr";
  std::ofstream(bad) << "this is not an EXR file";
  try {
    shadetwin::loadImageRGBA(bad);
    FAIL();
  } catch (const shadetwin::FileError& e) {
    EXPECT_NE(std::string(e.what()).find("not_an_image.exr: cannot read image"), std::string::npos) << e.what();
  }
}
