// Loading the real CC0 HDRIs (fetched by scripts/setup.sh) and clear errors for bad files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <iterator>
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

// An EXR header attribute that claims more bytes than the file holds is refused before OpenEXR allocates it (found by
// fuzz_image: a 1 KiB file claiming a 1.2 GiB string). Every attribute of a file writeExr wrote is tried in turn: its
// size field set past the end and negative is an error naming the file and the attribute; the file as written loads.
TEST(ImageIO, ExrAttributeSizesPastTheEndAreRefusedByName) {
  const std::string good = testing::TempDir() + "/attr_good.exr";
  shadetwin::writeExr(good, 3, 2, std::vector<float>(3 * 2 * 4, 0.5f));
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(shadetwin::loadImageRGBA(good).width, 3u);
  // Walk the header the way the loader does (magic, version, then name NUL type NUL int32 size value, ended by NUL).
  struct Attribute {
    std::string name;
    size_t sizeAt;
  };
  std::vector<Attribute> attributes;
  size_t at = 8;
  while (bytes.at(at) != 0) {
    const std::string name = bytes.c_str() + at;
    at += name.size() + 1;
    at += std::string(bytes.c_str() + at).size() + 1;
    int32_t size;
    std::memcpy(&size, bytes.data() + at, 4);
    attributes.push_back({name, at});
    at += 4 + size_t(size);
  }
  ASSERT_GE(attributes.size(), 6u) << "an EXR has at least channels, compression, dataWindow, displayWindow, lineOrder, "
                                      "pixelAspectRatio, screenWindowCenter, screenWindowWidth";
  for (const auto& a : attributes)
    for (const int32_t claim : {int32_t(bytes.size()), int32_t(1296911694), int32_t(-1)}) {
      std::string bad = bytes;
      std::memcpy(bad.data() + a.sizeAt, &claim, 4);
      const std::string path = testing::TempDir() + "/attr_bad.exr";
      std::ofstream(path, std::ios::binary | std::ios::trunc) << bad;
      try {
        shadetwin::loadImageRGBA(path);
        ADD_FAILURE() << a.name << " claiming " << claim << " bytes loaded";
      } catch (const shadetwin::FileError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("attr_bad.exr: EXR attribute " + a.name + " "), std::string::npos) << m;
        EXPECT_NE(m.find("claims " + std::to_string(claim) + " bytes"), std::string::npos) << m;
      }
    }
  // A name that runs to the end of the file is an error too, not a read past it.
  const std::string cut = testing::TempDir() + "/attr_cut.exr";
  std::ofstream(cut, std::ios::binary | std::ios::trunc) << bytes.substr(0, 8 + attributes[0].name.size() / 2);
  EXPECT_THROW(shadetwin::loadImageRGBA(cut), shadetwin::FileError);
}
