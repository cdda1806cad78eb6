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

// The zero counts above can fail: the same messenger counts a real misuse (a buffer created with no usage bits,
// VUID-VkBufferCreateInfo-usage-requiredbitmask) and names it.
TEST(VkContext, ValidationCountsAMisuse) {
  shadetwin::vk::Context ctx({"", true});
  ASSERT_TRUE(ctx.validationEnabled()) << "VK_LAYER_KHRONOS_validation missing (scripts/setup.sh installs it)";
  EXPECT_EQ(ctx.validationErrors(), 0u);
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = 256;
  bi.usage = 0;  // invalid: at least one usage bit is required
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buf = VK_NULL_HANDLE;
  if (vkCreateBuffer(ctx.device(), &bi, nullptr, &buf) == VK_SUCCESS) vkDestroyBuffer(ctx.device(), buf, nullptr);
  EXPECT_GE(ctx.validationErrors(), 1u);
  EXPECT_NE(ctx.lastValidationMessage.find("usage"), std::string::npos) << ctx.lastValidationMessage;
}
