#pragma once
// The driver's own statistics of each compute pipeline s3d makes (registers, shared memory, binary size, as the
// driver names them), printed to stderr: a developer's view of what limits a kernel's occupancy, with no profiler.
// Asked for with the environment variable S3D_PIPELINE_STATISTICS=1 on a device that s3d creates itself and that
// has VK_KHR_pipeline_executable_properties; otherwise nothing is captured and nothing printed.
#include <cstddef>
#include <source_location>

#include <vulkan/vulkan.h>

namespace s3d::vk {

// Whether the environment asks for the statistics (S3D_PIPELINE_STATISTICS set and not "0").
bool pipelineStatisticsRequested();

// Prints each executable's statistics of `pipeline`, made with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR, to
// stderr, headed by the source line that made it and its SPIR-V's size in words (which tells apart the shaders one
// helper makes).
void printPipelineStatistics(VkDevice device, VkPipeline pipeline, const std::source_location& madeAt,
                             std::size_t spirvWords);

}  // namespace s3d::vk
