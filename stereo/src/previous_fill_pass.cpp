#include "s3d/stereo/previous_fill_pass.h"

#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_previous_fill_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

// The forward pass's z-buffers as its dispatches leave them (forward_pass.cpp).
constexpr vk::ImageState kKeysReadWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
constexpr vk::ImageState kComputeReadWrite = kKeysReadWrite;

}  // namespace

PreviousFillPass::PreviousFillPass(const vk::Context& context) : context_(&context) {
  VkDescriptorSetLayoutBinding bindings[6];
  for (std::uint32_t i = 0; i < 6; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  layout_ = vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::PreviousFillConstants), VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context, layout_.layout, spirv_stereo_previous_fill_comp);
}

void PreviousFillPass::record(VkCommandBuffer cmd, const ForwardStereoPass& forward, const vk::Image& leftEye,
                              const vk::Image& rightEye, const gpu::ForwardConstants& constants,
                              const std::array<gpu::EyeMotion, 2>& motion) const {
  for (const vk::Image* image : {&leftEye, &rightEye, &forward.keys(Eye::Left), &forward.keys(Eye::Right)})
    if (int(image->width) != constants.width || int(image->height) != constants.height)
      throw std::invalid_argument("PreviousFillPass: image size does not match the constants");
  const bool resized = !history_ || int((*history_)[0][0].color.width) != constants.width ||
                       int((*history_)[0][0].color.height) != constants.height;
  if (resized) {
    auto image = [&](VkFormat format) {
      return vk::createImage(*context_, format, std::uint32_t(constants.width), std::uint32_t(constants.height),
                             VK_IMAGE_USAGE_STORAGE_BIT);
    };
    history_.emplace();
    for (auto& slot : *history_)
      for (EyeImages& eye : slot) eye = {image(VK_FORMAT_R8G8B8A8_UNORM), image(VK_FORMAT_R32_SFLOAT)};
    fresh_ = true;
  }
  const bool useHistory = hasHistory_ && !resized;
  const auto& previous = (*history_)[std::size_t(previous_)];
  const auto& current = (*history_)[std::size_t(1 - previous_)];
  for (int e = 0; e < 2; ++e) {
    for (const vk::Image* image : {&previous[std::size_t(e)].color, &previous[std::size_t(e)].depth})
      vk::transition(cmd, *image, fresh_ ? vk::kUndefined : vk::kComputeWrite, vk::kComputeRead);
    // This frame's history was read as the previous one a frame ago (or by an earlier record of this frame).
    for (const vk::Image* image : {&current[std::size_t(e)].color, &current[std::size_t(e)].depth})
      vk::transition(cmd, *image, fresh_ ? vk::kUndefined : kComputeReadWrite, vk::kComputeWrite);
  }
  for (const vk::Image* eye : {&leftEye, &rightEye}) vk::transition(cmd, *eye, vk::kComputeWrite, kComputeReadWrite);
  for (Eye eye : {Eye::Left, Eye::Right}) vk::transition(cmd, forward.keys(eye), kKeysReadWrite, kKeysReadWrite);
  fresh_ = false;

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  const std::uint32_t groupsX = std::uint32_t((constants.width + S3D_PREVIOUS_FILL_GROUP_SIZE - 1) / S3D_PREVIOUS_FILL_GROUP_SIZE);
  const std::uint32_t groupsY = std::uint32_t((constants.height + S3D_PREVIOUS_FILL_GROUP_SIZE - 1) / S3D_PREVIOUS_FILL_GROUP_SIZE);
  for (int e = 0; e < 2; ++e) {
    const Eye eye = e == 0 ? Eye::Left : Eye::Right;
    const vk::Image* images[6] = {e == 0 ? &leftEye : &rightEye,        &forward.keys(eye),
                                  &previous[std::size_t(e)].color,      &previous[std::size_t(e)].depth,
                                  &current[std::size_t(e)].color,       &current[std::size_t(e)].depth};
    VkDescriptorImageInfo infos[6];
    VkWriteDescriptorSet writes[6];
    for (std::uint32_t i = 0; i < 6; ++i) {
      infos[i] = {VK_NULL_HANDLE, images[i]->view, VK_IMAGE_LAYOUT_GENERAL};
      writes[i] = vk::storageImageWrite(i, &infos[i]);
    }
    const gpu::PreviousFillConstants c = makePreviousFillConstants(constants, motion[std::size_t(e)], useHistory);
    context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 6, writes);
    vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
  }
  // The eyes leave in compute-write state, as the forward pass leaves them (its callers read them back from it).
  for (const vk::Image* eye : {&leftEye, &rightEye}) vk::transition(cmd, *eye, kComputeReadWrite, vk::kComputeWrite);
  recorded_ = true;
}

void PreviousFillPass::advance() {
  if (!recorded_) return;
  previous_ = 1 - previous_;
  hasHistory_ = true;
  recorded_ = false;
}

}  // namespace s3d::stereo
