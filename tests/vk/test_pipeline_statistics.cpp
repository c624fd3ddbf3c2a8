// The driver's pipeline statistics are a developer's request: the environment asks, a device without them is made
// as usual and captures nothing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "s3d/vk/context.h"
#include "s3d/vk/pipeline_statistics.h"

namespace s3d::vk {
namespace {

// Sets S3D_PIPELINE_STATISTICS for one scope (unset: nullptr), then restores it unset.
class StatisticsRequest {
 public:
  explicit StatisticsRequest(const char* value) {
    if (value) setenv("S3D_PIPELINE_STATISTICS", value, 1);
    else unsetenv("S3D_PIPELINE_STATISTICS");
  }
  ~StatisticsRequest() { unsetenv("S3D_PIPELINE_STATISTICS"); }
};

TEST(PipelineStatistics, AreAskedForByTheEnvironmentUnlessUnsetEmptyOrZero) {
  {
    const StatisticsRequest request(nullptr);
    EXPECT_FALSE(pipelineStatisticsRequested());
  }
  {
    const StatisticsRequest request("");
    EXPECT_FALSE(pipelineStatisticsRequested());
  }
  {
    const StatisticsRequest request("0");
    EXPECT_FALSE(pipelineStatisticsRequested());
  }
  {
    const StatisticsRequest request("1");
    EXPECT_TRUE(pipelineStatisticsRequested());
  }
}

bool hasPipelineExecutableProperties(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  for (const VkExtensionProperties& extension : extensions)
    if (std::strcmp(extension.extensionName, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME) == 0) return true;
  return false;
}

TEST(PipelineStatistics, AreCapturedExactlyWhereAskedForAndTheDeviceHasThem) {
  const StatisticsRequest request("1");
  const Context asked;
  EXPECT_EQ(asked.capturesPipelineStatistics(), hasPipelineExecutableProperties(asked.physicalDevice()));
  unsetenv("S3D_PIPELINE_STATISTICS");
  const Context notAsked;
  EXPECT_FALSE(notAsked.capturesPipelineStatistics());
}

}  // namespace
}  // namespace s3d::vk
