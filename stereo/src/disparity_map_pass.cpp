#include "s3d/stereo/disparity_map_pass.h"

#include <cstring>

#include "s3d/vk/timestamps.h"

// clang-format off
#include <s3d_spirv/disparity_map_comp.h>
// clang-format on

namespace s3d::stereo {

DisparityMapPass::DisparityMapPass(const vk::Context& context) : context_(&context) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  layout_ = vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::DisparityMapConstants),
                                           VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context, layout_.layout, spirv_disparity_map_comp);
}

void DisparityMapPass::record(VkCommandBuffer cmd, const vk::Image& linearDepth,
                              const gpu::DisparityMapConstants& map) const {
  if (map.knotCount < 2) return;
  VkDescriptorImageInfo image{VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkWriteDescriptorSet write = vk::storageImageWrite(0, &image);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 1, &write);
  vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(map), &map);
  auto groups = [](std::uint32_t size) { return (size + S3D_DISPARITY_MAP_GROUP_SIZE - 1) / S3D_DISPARITY_MAP_GROUP_SIZE; };
  vkCmdDispatch(cmd, groups(linearDepth.width), groups(linearDepth.height), 1);
}

std::optional<double> mapDepthTimed(vk::Context& context, const DisparityMapPass& pass, const vk::Image& linearDepth,
                                    const gpu::DisparityMapConstants& map) {
  if (map.knotCount < 2) return std::nullopt;
  vk::TimestampQueries timestamps(context, 2);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, linearDepth, vk::kComputeWrite, vk::kComputeWrite);
    if (timestamps.supported()) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
    pass.record(cmd, linearDepth, map);
    if (timestamps.supported()) timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    vk::transition(cmd, linearDepth, vk::kComputeWrite, vk::kComputeWrite);
  });
  return timestamps.elapsedMs(0, 1);
}

DepthImage mapDepthOnGpu(vk::Context& context, const DepthImage& linearDepth, const gpu::DisparityMapConstants& map) {
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, linearDepth.width, linearDepth.height, usage);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeWrite);
  const DisparityMapPass pass(context);
  (void)mapDepthTimed(context, pass, depth, map);
  const std::vector<std::byte> bytes = vk::readbackImage(context, depth, vk::kComputeWrite);
  DepthImage result(linearDepth.width, linearDepth.height);
  std::memcpy(result.pixels.data(), bytes.data(), result.pixels.size() * sizeof(float));
  return result;
}

}  // namespace s3d::stereo
