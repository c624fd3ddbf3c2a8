#include "s3d/stereo/forward_pass.h"

#include <stdexcept>

#include "s3d/stereo/detail/eye_pair_pipeline.h"

// clang-format off
#include <s3d_spirv/stereo_forward_clear_comp.h>
#include <s3d_spirv/stereo_forward_resolve_comp.h>
#include <s3d_spirv/stereo_forward_splat_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

constexpr VkFormat kKeyFormat = VK_FORMAT_R32_UINT;
// The z-buffers between dispatches: atomics read and write them.
constexpr vk::ImageState kKeysReadWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};

}  // namespace

ForwardStereoPass::ForwardStereoPass(const vk::Context& context) : context_(&context) {
  VkDescriptorSetLayoutBinding bindings[6];
  for (std::uint32_t i = 0; i < 6; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  layout_ = vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::ForwardConstants), VK_SHADER_STAGE_COMPUTE_BIT);
  clear_ = vk::createComputePipeline(context, layout_.layout, spirv_stereo_forward_clear_comp);
  splat_ = vk::createComputePipeline(context, layout_.layout, spirv_stereo_forward_splat_comp);
  resolve_ = vk::createComputePipeline(context, layout_.layout, spirv_stereo_forward_resolve_comp);
}

void ForwardStereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                               const vk::Image& leftEye, const vk::Image& rightEye,
                               const gpu::ForwardConstants& c) const {
  for (const vk::Image* image : {&centerColor, &linearDepth, &leftEye, &rightEye})
    if (int(image->width) != c.width || int(image->height) != c.height)
      throw std::invalid_argument("ForwardStereoPass: image size does not match the constants");
  const bool fresh = !zBuffers_ || int(zBuffers_->left.width) != c.width || int(zBuffers_->left.height) != c.height;
  if (fresh) {
    auto keys = [&] {
      return vk::createImage(*context_, kKeyFormat, std::uint32_t(c.width), std::uint32_t(c.height),
                             VK_IMAGE_USAGE_STORAGE_BIT);
    };
    zBuffers_ = ZBuffers{keys(), keys()};
  }
  const ZBuffers& z = *zBuffers_;
  // Undefined first time (or after a resize), else after the previous record's resolve read them.
  for (const vk::Image* keys : {&z.left, &z.right}) vk::transition(cmd, *keys, fresh ? vk::kUndefined : kKeysReadWrite, kKeysReadWrite);
  VkDescriptorImageInfo infos[6] = {{VK_NULL_HANDLE, centerColor.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, leftEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, rightEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, z.left.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, z.right.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[6];
  for (std::uint32_t i = 0; i < 6; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  const std::uint32_t groupsX = std::uint32_t((c.width + S3D_FORWARD_GROUP_SIZE - 1) / S3D_FORWARD_GROUP_SIZE);
  const std::uint32_t groupsY = std::uint32_t((c.height + S3D_FORWARD_GROUP_SIZE - 1) / S3D_FORWARD_GROUP_SIZE);
  for (VkPipeline pipeline : {clear_.get(), splat_.get(), resolve_.get()}) {
    if (pipeline != clear_.get())
      for (const vk::Image* keys : {&z.left, &z.right}) vk::transition(cmd, *keys, kKeysReadWrite, kKeysReadWrite);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 6, writes);
    vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
  }
}

const vk::Image& ForwardStereoPass::keys(Eye eye) const {
  if (!zBuffers_) throw std::logic_error("ForwardStereoPass::keys: nothing recorded yet");
  return eye == Eye::Left ? zBuffers_->left : zBuffers_->right;
}

StereoPair synthesizeForwardOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                  const gpu::ForwardConstants& constants) {
  return detail::runOnCpuImages(context, ForwardStereoPass(context), center, linearDepth, constants);
}

}  // namespace s3d::stereo
