// The Vulkan core's error reporting: failures name the call, the VkResult and the devices.
#include <gtest/gtest.h>

#include <algorithm>

#include "s3d/vk/check.h"
#include "s3d/vk/context.h"
#include "vulkan_test.h"

namespace s3d::vk {
namespace {

TEST(VulkanCheck, ErrorNamesTheCallAndTheResult) {
  try {
    S3D_VK_CHECK(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    FAIL() << "no exception";
  } catch (const VulkanError& error) {
    EXPECT_EQ(error.result(), VK_ERROR_OUT_OF_DEVICE_MEMORY);
    EXPECT_NE(std::string(error.what()).find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("failed"), std::string::npos) << error.what();
  }
}

TEST(VulkanDeviceChoice, UnknownChoiceIsRejectedWithTheChoices) {
  ContextOptions options;
  options.device = "fastest";
  try {
    Context context(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("auto, cpu, gpu"), std::string::npos) << error.what();
  }
}

TEST(VulkanDeviceChoice, MissingDeviceIndexListsTheDevices) {
  ContextOptions options;
  options.device = "99";
  try {
    Context context(options);
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("no usable Vulkan device"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("[0]"), std::string::npos) << error.what();
  }
}

TEST(VulkanDeviceChoice, AskingForAGpuWhereOnlyTheCpuDeviceIsUsableAdvisesAGpuDriverOrTheCpu) {
  const std::vector<PhysicalDeviceInfo> devices = listPhysicalDevices();
  const bool usableGpu = std::any_of(devices.begin(), devices.end(), [](const PhysicalDeviceInfo& d) {
    return d.usable && d.type != VK_PHYSICAL_DEVICE_TYPE_CPU;
  });
  if (usableGpu) GTEST_SKIP() << "a usable GPU is present: --device gpu succeeds here";
  ContextOptions options;
  options.device = "gpu";
  try {
    Context context(options);
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    // lavapipe is installed: advising the package that provides it again would not help.
    EXPECT_EQ(std::string(error.what()).find("install mesa-vulkan-drivers"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("no usable GPU: install its Vulkan driver, or use --device cpu"),
              std::string::npos)
        << error.what();
  }
}

TEST(VulkanDeviceChoice, EveryListedDeviceSaysWhetherItIsUsable) {
  std::vector<PhysicalDeviceInfo> devices = listPhysicalDevices();
  ASSERT_FALSE(devices.empty()) << "no Vulkan device at all (mesa-vulkan-drivers provides lavapipe)";
  for (const PhysicalDeviceInfo& device : devices) EXPECT_TRUE(device.usable || !device.unusableReason.empty());
}

class VulkanContextTest : public test::VulkanTest {};

TEST_F(VulkanContextTest, SharedTestContextHasTimestamps) {
  // The report's GPU times come from timestamps: the CI device (lavapipe) must have them.
  EXPECT_GT(context().timestampPeriodNs(), 0.0);
}

}  // namespace
}  // namespace s3d::vk
