#include "s3d/stereo/hybrid_base_depth_pass.h"

#include <cstdint>
#include <span>
#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_hybrid_base_depth_comp.h>
#include <s3d_spirv/stereo_search_base_depth_comp.h>
#include <s3d_spirv/stereo_seed_base_depth_comp.h>
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

// The gather with the base depth (stereo_gather.glsl's S3D_STEREO_BASE_DEPTH_OUTPUT): centre colour, linear depth,
// both eyes, the device depth sampled, both eyes' depth; the gather's constants pushed.
vk::PipelineLayout createGatherLayout(const vk::Context& context) {
  const auto storage = [](std::uint32_t binding) {
    return VkDescriptorSetLayoutBinding{binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                        nullptr};
  };
  const VkDescriptorSetLayoutBinding bindings[] = {
      storage(0), storage(1), storage(2), storage(3),
      {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}, storage(5), storage(6)};
  return vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::StereoConstants), VK_SHADER_STAGE_COMPUTE_BIT);
}

}  // namespace

HybridBaseDepthPass::HybridBaseDepthPass(const vk::Context& context)
    : context_(&context),
      nearest_(vk::createNearestClampSampler(context)),
      layout_(createLayout(context)),
      pipeline_(context, layout_.layout, spirv_stereo_hybrid_base_depth_comp, {}),
      gatherLayout_(createGatherLayout(context)) {}

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

void HybridBaseDepthPass::recordWithGather(VkCommandBuffer cmd, const vk::Image& centerColor,
                                           const vk::Image& linearDepth, const vk::Image& deviceDepth,
                                           const vk::Image& leftEye, const vk::Image& rightEye,
                                           const vk::Image& leftDepth, const vk::Image& rightDepth,
                                           const gpu::StereoConstants& c) const {
  if (c.tapCount < 0 || c.tapCount > S3D_STEREO_MAX_TAPS)
    throw std::invalid_argument("hybrid base depth: the gather's tap count is out of range (use makeStereoConstants)");
  for (const vk::Image* image :
       {&centerColor, &linearDepth, &deviceDepth, &leftEye, &rightEye, &leftDepth, &rightDepth})
    if (int(image->width) != c.width || int(image->height) != c.height)
      throw std::invalid_argument("hybrid base depth: an image's size does not match the gather's constants");
  const bool shortTaps = c.tapCount <= S3D_STEREO_SMALL_TAP_CAPACITY;
  vk::Unique<VkPipeline>& pipeline = shortTaps ? gatherShortTaps_ : gatherAllTaps_;
  if (!pipeline)
    pipeline = vk::createComputePipeline(*context_, gatherLayout_.layout,
                                         shortTaps ? std::span<const std::uint32_t>(spirv_stereo_seed_base_depth_comp)
                                                   : std::span<const std::uint32_t>(spirv_stereo_search_base_depth_comp));
  VkDescriptorImageInfo infos[] = {{VK_NULL_HANDLE, centerColor.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {VK_NULL_HANDLE, leftEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {VK_NULL_HANDLE, rightEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {nearest_.get(), deviceDepth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                   {VK_NULL_HANDLE, leftDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                   {VK_NULL_HANDLE, rightDepth.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[7];
  for (std::uint32_t binding = 0; binding < 7; ++binding)
    writes[binding] = binding == 4 ? vk::sampledImageWrite(binding, &infos[binding])
                                   : vk::storageImageWrite(binding, &infos[binding]);
  writes[4].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, gatherLayout_.layout, 0, 7, writes);
  vkCmdPushConstants(cmd, gatherLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  const auto groups = [](int size) {
    return std::uint32_t((size + S3D_STEREO_GROUP_SIZE - 1) / S3D_STEREO_GROUP_SIZE);
  };
  vkCmdDispatch(cmd, groups(c.width), groups(c.height), 1);
}

}  // namespace s3d::stereo
