#include "s3d/vk/pipeline_statistics.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
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

// The specialization constants as 32-bit values in map order ("" without any).
std::string specializationText(const VkSpecializationInfo* specialization) {
  std::string text;
  if (!specialization) return text;
  for (std::uint32_t i = 0; i < specialization->mapEntryCount; ++i) {
    const VkSpecializationMapEntry& entry = specialization->pMapEntries[i];
    std::int32_t value = 0;
    if (entry.size == sizeof value && entry.offset + sizeof value <= specialization->dataSize)
      std::memcpy(&value, static_cast<const std::byte*>(specialization->pData) + entry.offset, sizeof value);
    text += (text.empty() ? "" : ", ") + std::to_string(entry.constantID) + ": " + std::to_string(value);
  }
  return text;
}

}  // namespace

void printPipelineStatistics(VkDevice device, VkPipeline pipeline, std::size_t spirvWords,
                             const VkSpecializationInfo* specialization) {
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
    std::fprintf(stderr, "s3d pipeline statistics: SPIR-V of %zu words, specialization {%s}, %s (subgroup %u):\n",
                 spirvWords, specializationText(specialization).c_str(), properties[i].name, properties[i].subgroupSize);
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
