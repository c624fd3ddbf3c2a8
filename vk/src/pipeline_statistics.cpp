#include "s3d/vk/pipeline_statistics.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "s3d/vk/check.h"

namespace s3d::vk {

bool pipelineStatisticsRequested() {
  const char* value = std::getenv("S3D_PIPELINE_STATISTICS");
  return value && *value && std::strcmp(value, "0") != 0;
}

namespace {

void printStatistic(const VkPipelineExecutableStatisticKHR& statistic) {
  switch (statistic.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
      std::fprintf(stderr, "  %s: %s\n", statistic.name, statistic.value.b32 ? "true" : "false");
      break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
      std::fprintf(stderr, "  %s: %lld\n", statistic.name, static_cast<long long>(statistic.value.i64));
      break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
      std::fprintf(stderr, "  %s: %llu\n", statistic.name, static_cast<unsigned long long>(statistic.value.u64));
      break;
    default:
      std::fprintf(stderr, "  %s: %g\n", statistic.name, statistic.value.f64);
  }
}

}  // namespace

void printPipelineStatistics(VkDevice device, VkPipeline pipeline, const std::source_location& madeAt,
                             std::size_t spirvWords) {
  auto executables = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetDeviceProcAddr(device, "vkGetPipelineExecutablePropertiesKHR"));
  auto statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetDeviceProcAddr(device, "vkGetPipelineExecutableStatisticsKHR"));
  if (!executables || !statistics) return;
  VkPipelineInfoKHR pipelineInfo{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  pipelineInfo.pipeline = pipeline;
  std::uint32_t count = 0;
  S3D_VK_CHECK(executables(device, &pipelineInfo, &count, nullptr));
  std::vector<VkPipelineExecutablePropertiesKHR> properties(count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
  S3D_VK_CHECK(executables(device, &pipelineInfo, &count, properties.data()));
  for (std::uint32_t i = 0; i < count; ++i) {
    std::fprintf(stderr, "s3d pipeline statistics, %s:%u, %zu SPIR-V words, %s (subgroup %u):\n", madeAt.file_name(),
                 static_cast<unsigned>(madeAt.line()), spirvWords, properties[i].name, properties[i].subgroupSize);
    VkPipelineExecutableInfoKHR executable{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    executable.pipeline = pipeline;
    executable.executableIndex = i;
    std::uint32_t statisticCount = 0;
    S3D_VK_CHECK(statistics(device, &executable, &statisticCount, nullptr));
    std::vector<VkPipelineExecutableStatisticKHR> values(statisticCount, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
    S3D_VK_CHECK(statistics(device, &executable, &statisticCount, values.data()));
    for (const VkPipelineExecutableStatisticKHR& value : values) printStatistic(value);
  }
}

}  // namespace s3d::vk
