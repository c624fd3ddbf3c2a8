#include "s3d/stereo/stereo_pass.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_search_comp.h>
#include <s3d_spirv/stereo_seed_comp.h>
// clang-format on

namespace s3d::stereo {

namespace {

// The tap array comes last: a variant with a shorter array reads (and is pushed) only this prefix.
constexpr std::uint32_t pushBytesFor(int tapCapacity) {
  return std::uint32_t(offsetof(gpu::StereoConstants, tapOffsetPx) + sizeof(int) * std::size_t(tapCapacity));
}
static_assert(pushBytesFor(S3D_STEREO_MAX_TAPS) == sizeof(gpu::StereoConstants));

}  // namespace

StereoPass::StereoPass(const vk::Context& context)
    : context_(&context),
      shortTaps_(detail::createEyePairPipeline(context, spirv_stereo_seed_comp, pushBytesFor(S3D_STEREO_SMALL_TAP_CAPACITY),
                                               S3D_STEREO_GROUP_SIZE)),
      allTaps_(detail::createEyePairPipeline(context, spirv_stereo_search_comp, pushBytesFor(S3D_STEREO_MAX_TAPS),
                                             S3D_STEREO_GROUP_SIZE)) {}

void StereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                        const vk::Image& leftEye, const vk::Image& rightEye,
                        const gpu::StereoConstants& constants) const {
  if (constants.tapCount < 0 || constants.tapCount > S3D_STEREO_MAX_TAPS)
    throw std::invalid_argument("StereoPass: tap count out of range (use makeStereoConstants)");
  const detail::EyePairPipeline& pipeline = constants.tapCount <= S3D_STEREO_SMALL_TAP_CAPACITY ? shortTaps_ : allTaps_;
  detail::recordEyePairDispatch(cmd, *context_, pipeline, centerColor, linearDepth, leftEye, rightEye, &constants,
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
