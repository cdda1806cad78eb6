// Vulkan host on lavapipe with validation layers: runs kernels with zero validation errors and
// reports bad device names clearly.
#include <gtest/gtest.h>

#include <sstream>

#include "cli/verify/verify.h"
#include "vk/context.h"

TEST(VkContext, UnknownDeviceListsAvailableOnes) {
  try {
    shadetwin::vk::Context ctx({"no-such-gpu", false});
    FAIL();
  } catch (const shadetwin::vk::Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("no-such-gpu"), std::string::npos);
    EXPECT_NE(m.find("llvmpipe"), std::string::npos) << m;
  }
}

TEST(VkContext, VerifyRunsCleanUnderValidation) {
  shadetwin::VerifyOptions o;
  o.count = 3000;
  o.validate = true;
  std::ostringstream math, tex;
  EXPECT_EQ(0, shadetwin::verifyMath(o, math)) << math.str();
  EXPECT_NE(math.str().find("validation errors: 0"), std::string::npos) << math.str();
  o.count = 200;
  o.finiteTexels = true;
  o.filters = "texelFetch,bilinear,trilinear";
  EXPECT_EQ(0, shadetwin::verifyTexture(o, tex)) << tex.str();
  EXPECT_NE(tex.str().find("validation errors: 0"), std::string::npos) << tex.str();
}
