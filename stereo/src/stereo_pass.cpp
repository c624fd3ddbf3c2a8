#include "s3d/stereo/stereo_pass.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_seed_comp.h>
// clang-format on

namespace s3d::stereo {

StereoPass::StereoPass(const vk::Context& context)
    : context_(&context),
      pipeline_(detail::createEyePairPipeline(context, spirv_stereo_seed_comp, sizeof(gpu::StereoConstants),
                                              S3D_STEREO_GROUP_SIZE)) {}

void StereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                        const vk::Image& leftEye, const vk::Image& rightEye,
                        const gpu::StereoConstants& constants) const {
  detail::recordEyePairDispatch(cmd, *context_, pipeline_, centerColor, linearDepth, leftEye, rightEye, &constants,
                                constants.width, constants.height, "StereoPass");
}

void StereoPass::recordInputBarriers(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                                     const vk::Image& leftEye, const vk::Image& rightEye) {
  vk::transition(cmd, centerColor, vk::kComputeWrite, vk::kComputeRead);
  vk::transition(cmd, linearDepth, vk::kComputeWrite, vk::kComputeRead);
  vk::transition(cmd, leftEye, vk::kUndefined, vk::kComputeWrite);
  vk::transition(cmd, rightEye, vk::kUndefined, vk::kComputeWrite);
}

void StereoPass::recordInputRelease(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth) {
  vk::transition(cmd, centerColor, vk::kComputeRead, vk::kComputeWrite);
  vk::transition(cmd, linearDepth, vk::kComputeRead, vk::kComputeWrite);
}

StereoPair synthesizeStereoOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                 const gpu::StereoConstants& constants) {
  return detail::runOnCpuImages(context, StereoPass(context), center, linearDepth, constants);
}

}  // namespace s3d::stereo
