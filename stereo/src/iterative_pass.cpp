#include "s3d/stereo/iterative_pass.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "s3d/stereo/stereo_pass.h"

// clang-format off
#include <s3d_spirv/stereo_iterative_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

constexpr VkDescriptorSetLayoutBinding storageImageBinding(std::uint32_t binding) {
  return {binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
}

std::uint32_t groupCount(int size) {
  return std::uint32_t((size + S3D_ITERATIVE_GROUP_SIZE - 1) / S3D_ITERATIVE_GROUP_SIZE);
}

}  // namespace

IterativeStereoPass::IterativeStereoPass(const vk::Context& context) : context_(&context) {
  const VkDescriptorSetLayoutBinding bindings[] = {storageImageBinding(0), storageImageBinding(1),
                                                   storageImageBinding(2), storageImageBinding(3)};
  layout_ = vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::IterativeConstants), VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context, layout_.layout, spirv_stereo_iterative_comp);
}

void IterativeStereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                                 const vk::Image& leftEye, const vk::Image& rightEye,
                                 const gpu::IterativeConstants& constants) const {
  for (const vk::Image* image : {&centerColor, &linearDepth, &leftEye, &rightEye})
    if (int(image->width) != constants.width || int(image->height) != constants.height)
      throw std::invalid_argument("IterativeStereoPass: image size does not match the constants");
  // The shader trusts these: they bound its loops and the tap array.
  if (constants.iterations < 1 || constants.iterations > S3D_ITERATIVE_MAX_ITERATIONS ||
      constants.startTapCount < 0 || constants.startTapCount > S3D_ITERATIVE_START_TAPS)
    throw std::invalid_argument("IterativeStereoPass: iterations or start taps out of range (use makeIterativeConstants)");
  VkDescriptorImageInfo infos[4] = {{VK_NULL_HANDLE, centerColor.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, leftEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, rightEye.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[4];
  for (std::uint32_t i = 0; i < 4; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 4, writes);
  vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
  vkCmdDispatch(cmd, groupCount(constants.width), groupCount(constants.height), 1);
}

StereoPair synthesizeIterativeOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                    const gpu::IterativeConstants& constants) {
  requireSameSize(center, linearDepth, "iterative stereo (color vs depth)");
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image color = vk::createImage(context, StereoPass::kColorFormat, center.width, center.height, usage);
  vk::Image depth = vk::createImage(context, StereoPass::kDepthFormat, center.width, center.height, usage);
  vk::Image left = vk::createImage(context, StereoPass::kColorFormat, center.width, center.height, usage);
  vk::Image right = vk::createImage(context, StereoPass::kColorFormat, center.width, center.height, usage);
  vk::uploadImage(context, color, std::as_bytes(std::span(center.pixels)), vk::kComputeRead);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeRead);
  IterativeStereoPass pass(context);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, left, vk::kUndefined, vk::kComputeWrite);
    vk::transition(cmd, right, vk::kUndefined, vk::kComputeWrite);
    pass.record(cmd, color, depth, left, right, constants);
  });
  StereoPair pair{ImageRGBA8(center.width, center.height), ImageRGBA8(center.width, center.height)};
  for (auto [image, target] : {std::pair{&left, &pair.left}, std::pair{&right, &pair.right}}) {
    std::vector<std::byte> bytes = vk::readbackImage(context, *image, vk::kComputeWrite);
    std::memcpy(target->pixels.data(), bytes.data(), bytes.size());
  }
  return pair;
}

}  // namespace s3d::stereo
