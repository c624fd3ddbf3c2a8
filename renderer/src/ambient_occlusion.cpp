#include "ambient_occlusion.h"

#include "compute_binding.h"


#include "s3d/renderer/renderer_shared.h"
#include "s3d/vk/check.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/ssao_blur_comp.h>
#include <s3d_spirv/ssao_comp.h>
// clang-format on

namespace s3d::renderer::detail {
namespace {

constexpr VkFormat kOcclusionFormat = VK_FORMAT_R16G16_SFLOAT;  // occlusion, linear depth (+inf: none)
constexpr vk::ImageState kSampledByCompute{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                           VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

using detail::computeBinding;

}  // namespace

AmbientOcclusion::AmbientOcclusion(vk::Context& context, std::uint32_t renderWidth, std::uint32_t renderHeight,
                                   bool counting)
    : context_(context) {
  const std::uint32_t w = (renderWidth + 1) / 2, h = (renderHeight + 1) / 2;
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  occlusion_ = vk::createImage(context_, kOcclusionFormat, w, h, usage);
  blurred_ = vk::createImage(context_, kOcclusionFormat, w, h, usage);
  nearest_ = vk::createNearestClampSampler(context_);
  const VkDescriptorSetLayoutBinding bindings[] = {
      computeBinding(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER), computeBinding(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
      computeBinding(2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE), computeBinding(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  layout_ = vk::createPushDescriptorLayout(context_, bindings, 0, 0);
  occlusionPipelines_ = std::make_unique<TilePipelines>(context_, layout_.layout, spirv_ssao_comp, counting);
  blurPipelines_ = std::make_unique<TilePipelines>(context_, layout_.layout, spirv_ssao_blur_comp, counting);
}

void AmbientOcclusion::dispatch(VkCommandBuffer cmd, VkBuffer tiles, bool masked) const {
  // One 8x8 group of texels per render tile of 16x16 pixels.
  if (masked)
    vkCmdDispatchIndirect(cmd, tiles, TileLists::kAmbientTilesDispatch);
  else
    vkCmdDispatch(cmd, (occlusion_.width + S3D_COMPUTE_GROUP_SIZE - 1) / S3D_COMPUTE_GROUP_SIZE,
                  (occlusion_.height + S3D_COMPUTE_GROUP_SIZE - 1) / S3D_COMPUTE_GROUP_SIZE, 1);
}

void AmbientOcclusion::pushDescriptors(VkCommandBuffer cmd, VkBuffer frameBuffer, VkDescriptorImageInfo input,
                                       const vk::Image& output, VkBuffer tiles) const {
  VkDescriptorBufferInfo frameInfo{frameBuffer, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo outputInfo{VK_NULL_HANDLE, output.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorBufferInfo tileInfo{tiles, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo), vk::sampledImageWrite(1, &input),
                                   vk::storageImageWrite(2, &outputInfo), vk::uniformBufferWrite(3, &tileInfo)};
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[3].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 4, writes);
}

void AmbientOcclusion::recordOcclusion(VkCommandBuffer cmd, const vk::Image& depth, VkBuffer frameBuffer,
                                       VkBuffer tiles, bool masked) {
  vk::transition(cmd, occlusion_, vk::kUndefined, vk::kComputeWrite);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, occlusionPipelines_->get(masked));
  pushDescriptors(cmd, frameBuffer, {nearest_, depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}, occlusion_, tiles);
  dispatch(cmd, tiles, masked);
}

void AmbientOcclusion::recordBlur(VkCommandBuffer cmd, VkBuffer frameBuffer, VkBuffer tiles, bool masked) {
  vk::transition(cmd, occlusion_, vk::kComputeWrite, kSampledByCompute);
  vk::transition(cmd, blurred_, vk::kUndefined, vk::kComputeWrite);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, blurPipelines_->get(masked));
  pushDescriptors(cmd, frameBuffer, {nearest_, occlusion_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}, blurred_, tiles);
  dispatch(cmd, tiles, masked);
  vk::transition(cmd, blurred_, vk::kComputeWrite, kSampledByCompute);
}

void AmbientOcclusion::recordUnused(VkCommandBuffer cmd) {
  vk::transition(cmd, blurred_, vk::kUndefined, kSampledByCompute);
}

VkDescriptorImageInfo AmbientOcclusion::result() const {
  return {nearest_, blurred_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

}  // namespace s3d::renderer::detail
