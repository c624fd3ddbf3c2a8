#include "s3d/stereo/hybrid_base_depth_pass.h"

#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_hybrid_base_depth_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

vk::PipelineLayout createLayout(const vk::Context& context) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  return vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::HybridConstants), VK_SHADER_STAGE_COMPUTE_BIT);
}

}  // namespace

HybridBaseDepthPass::HybridBaseDepthPass(const vk::Context& context)
    : context_(&context),
      nearest_(vk::createNearestClampSampler(context)),
      layout_(createLayout(context)),
      pipeline_(context, layout_.layout, spirv_stereo_hybrid_base_depth_comp, {}) {}

vk::Image HybridBaseDepthPass::createEyeDepth(const vk::Context& context, std::uint32_t width, std::uint32_t height) {
  return vk::createImage(context, VK_FORMAT_R32_SFLOAT, width, height,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
}

void HybridBaseDepthPass::record(VkCommandBuffer cmd, const vk::Image& linearDepth, const vk::Image& deviceDepth,
                                 const vk::Image& leftDepth, const vk::Image& rightDepth,
                                 const gpu::HybridConstants& c) const {
  if (c.baseTapCount <= 0) throw std::invalid_argument("hybrid base depth: the base is no gather (seed or search)");
  for (const vk::Image* image : {&linearDepth, &deviceDepth, &leftDepth, &rightDepth})
    if (int(image->width) != c.width || int(image->height) != c.height)
      throw std::invalid_argument("hybrid base depth: an image's size does not match the constants");
  VkDescriptorImageInfo infos[] = {{VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {nearest_.get(), deviceDepth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                   {VK_NULL_HANDLE, leftDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {VK_NULL_HANDLE, rightDepth.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[] = {vk::storageImageWrite(0, &infos[0]), vk::sampledImageWrite(1, &infos[1]),
                                   vk::storageImageWrite(2, &infos[2]), vk::storageImageWrite(3, &infos[3])};
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.forTaps(c.baseTapCount));
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 4, writes);
  vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  const auto groups = [](int size) { return std::uint32_t((size + S3D_HYBRID_GROUP_SIZE - 1) / S3D_HYBRID_GROUP_SIZE); };
  vkCmdDispatch(cmd, groups(c.width), groups(c.height), 1);
}

}  // namespace s3d::stereo
