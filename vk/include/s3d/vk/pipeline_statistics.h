#pragma once
// The driver's own statistics of each compute pipeline s3d makes (registers, shared memory, binary size, as the
// driver names them), printed to stderr: a developer's view of what limits a kernel's occupancy, with no profiler.
// Asked for with the environment variable S3D_PIPELINE_STATISTICS=1 on a device that s3d creates itself and that
// has VK_KHR_pipeline_executable_properties; otherwise nothing is captured and nothing printed.
#include <cstddef>

#include <vulkan/vulkan.h>

namespace s3d::vk {

// Whether the environment asks for the statistics (S3D_PIPELINE_STATISTICS set and not "0").
bool pipelineStatisticsRequested();

// Prints each executable's statistics of `pipeline`, made with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR, to
// stderr, headed by its SPIR-V's size in words (which names the shader: each embedded module's size is in the
// build's s3d_spirv headers) and its specialization constants' 32-bit values.
void printPipelineStatistics(VkDevice device, VkPipeline pipeline, std::size_t spirvWords,
                             const VkSpecializationInfo* specialization);

}  // namespace s3d::vk
