// The Vulkan core's error reporting (failures name the call, the VkResult and the devices) and its submissions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

#include "s3d/vk/check.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"
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

// Each recording of a concurrent submission runs to its end before the call returns: every buffer holds the value
// its own command buffer filled it with (on one queue or two).
TEST_F(VulkanContextTest, ASubmissionOfSeveralRecordingsRunsEachOfThem) {
  std::vector<Buffer> buffers;
  std::vector<std::function<void(VkCommandBuffer)>> records;
  for (std::uint32_t i = 0; i < 3; ++i) {
    buffers.push_back(createBuffer(context(), 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryLocation::HostVisible));
    std::memset(buffers.back().mapped, 0, 256);
  }
  for (std::uint32_t i = 0; i < 3; ++i)
    records.push_back([&, i](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, buffers[i].buffer, 0, VK_WHOLE_SIZE, 0x01010101u * (i + 1));
      memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                    VK_ACCESS_2_HOST_READ_BIT);
    });
  context().submitConcurrentlyAndWait(records);
  for (std::uint32_t i = 0; i < 3; ++i) {
    const auto* bytes = static_cast<const std::uint8_t*>(buffers[i].mapped);
    EXPECT_TRUE(std::all_of(bytes, bytes + 256, [&](std::uint8_t b) { return b == i + 1; })) << "recording " << i;
  }
}

}  // namespace
}  // namespace s3d::vk
