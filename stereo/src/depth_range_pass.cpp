#include "s3d/stereo/depth_range_pass.h"

#include <cstring>

#include "s3d/vk/timestamps.h"

// clang-format off
#include <s3d_spirv/depth_range_comp.h>
// clang-format on

namespace s3d::stereo {

DepthRangePass::DepthRangePass(const vk::Context& context) : context_(&context) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  layout_ = vk::createPushDescriptorLayout(context, bindings, 0, VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context, layout_.layout, spirv_depth_range_comp);
  // The atomics land in device memory (host-visible memory may sit across the bus on a discrete GPU); one small
  // copy brings the result back. On an H200 at 1920x1080 both layouts measured 0.025-0.027 ms (docs/RESULTS.md).
  counters_ = vk::createBuffer(context, sizeof(gpu::DepthRangeBuffer),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               vk::MemoryLocation::Device);
  buffer_ = vk::createBuffer(context, sizeof(gpu::DepthRangeBuffer), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             vk::MemoryLocation::HostVisible);
}

void DepthRangePass::record(VkCommandBuffer cmd, const vk::Image& linearDepth) const {
  // Nearest starts at +inf's bits, every other counter at 0.
  vkCmdFillBuffer(cmd, counters_.buffer, 0, sizeof(std::uint32_t), 0x7f800000u);
  vkCmdFillBuffer(cmd, counters_.buffer, sizeof(std::uint32_t), VK_WHOLE_SIZE, 0u);
  VkMemoryBarrier2 cleared{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                           VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &cleared;
  vkCmdPipelineBarrier2(cmd, &dependency);

  VkDescriptorImageInfo image{VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorBufferInfo buffer{counters_.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[2] = {vk::storageImageWrite(0, &image), vk::uniformBufferWrite(1, &buffer)};
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 2, writes);
  auto groups = [](std::uint32_t size, std::uint32_t perGroup) { return (size + perGroup - 1) / perGroup; };
  vkCmdDispatch(cmd, groups(linearDepth.width, S3D_DEPTH_GROUP_SIZE * S3D_DEPTH_RUN),
                groups(linearDepth.height, S3D_DEPTH_GROUP_SIZE), 1);

  VkMemoryBarrier2 reduced{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                           VK_ACCESS_2_TRANSFER_READ_BIT};
  dependency.pMemoryBarriers = &reduced;
  vkCmdPipelineBarrier2(cmd, &dependency);
  const VkBufferCopy whole{0, 0, sizeof(gpu::DepthRangeBuffer)};
  vkCmdCopyBuffer(cmd, counters_.buffer, buffer_.buffer, 1, &whole);
  VkMemoryBarrier2 done{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, VK_PIPELINE_STAGE_2_COPY_BIT,
                        VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
  dependency.pMemoryBarriers = &done;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

DepthRange DepthRangePass::result() const {
  gpu::DepthRangeBuffer copy;
  std::memcpy(&copy, buffer_.mapped, sizeof(copy));
  return depthRangeFromBuffer(copy);
}

TimedDepthRange reduceDepthRangeTimed(vk::Context& context, const DepthRangePass& pass, const vk::Image& linearDepth) {
  vk::TimestampQueries timestamps(context, 2);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, linearDepth, vk::kComputeWrite, vk::kComputeRead);
    if (timestamps.supported()) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
    pass.record(cmd, linearDepth);
    if (timestamps.supported()) timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    vk::transition(cmd, linearDepth, vk::kComputeRead, vk::kComputeWrite);
  });
  return {pass.result(), timestamps.elapsedMs(0, 1)};
}

DepthRange reduceDepthRangeOnGpu(vk::Context& context, const DepthImage& linearDepth) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, linearDepth.width, linearDepth.height, usage);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeRead);
  const DepthRangePass pass(context);
  context.submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, depth); });
  return pass.result();
}

}  // namespace s3d::stereo
