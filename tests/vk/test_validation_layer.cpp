// The GPU tests' promise "any validation message fails the test" rests on two links: the Khronos layer is
// really loaded (Context throws if it is missing) and what it reports reaches the fixture's list, which
// VulkanTest::TearDown turns into a failure. This checks the second link with a deliberately invalid call.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "vulkan_test.h"

namespace s3d::test {
namespace {

class ValidationLayerTest : public VulkanTest {};

TEST_F(ValidationLayerTest, AnInvalidCallIsRecordedForTheFixtureToFail) {
  // usage = 0 breaks VUID-VkBufferCreateInfo-usage-requiredbitmask; lavapipe itself ignores usage.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 16;
  info.usage = 0;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(context().device(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS) vkDestroyBuffer(context().device(), buffer, nullptr);

  const std::vector<std::string> messages = context().validationMessages();
  const bool named = std::any_of(messages.begin(), messages.end(), [](const std::string& message) {
    return message.find("VkBufferCreateInfo") != std::string::npos;
  });
  EXPECT_TRUE(named) << messages.size() << " message(s) recorded";
  context().clearValidationMessages();  // expected here: do not let TearDown fail this test for it
}

}  // namespace
}  // namespace s3d::test
