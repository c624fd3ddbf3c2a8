#include "s3d/stereo/stereo_pass.h"

#include "s3d/stereo/row_tile_shared.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_search_comp.h>
#include <s3d_spirv/stereo_search_tiled_comp.h>
#include <s3d_spirv/stereo_seed_comp.h>
#include <s3d_spirv/stereo_seed_tiled_comp.h>
// clang-format on

namespace s3d::stereo {

namespace {

// The tap array comes last: a variant with a shorter array reads (and is pushed) only this prefix.
constexpr std::uint32_t pushBytesFor(int tapCapacity) {
  return std::uint32_t(offsetof(gpu::StereoConstants, tapOffsetPx) + sizeof(int) * std::size_t(tapCapacity));
}
static_assert(pushBytesFor(S3D_STEREO_MAX_TAPS) == sizeof(gpu::StereoConstants));

}  // namespace

StereoPass::StereoPass(const vk::Context& context, StereoKernel kernel)
    : context_(&context),
      kernel_(kernel),
      deviceRunsRowTiles_(detail::deviceRunsRowTiles(context)),
      shortTaps_(spirv_stereo_seed_comp, pushBytesFor(S3D_STEREO_SMALL_TAP_CAPACITY), S3D_STEREO_GROUP_SIZE,
                 S3D_STEREO_GROUP_SIZE),
      allTaps_(spirv_stereo_search_comp, pushBytesFor(S3D_STEREO_MAX_TAPS), S3D_STEREO_GROUP_SIZE, S3D_STEREO_GROUP_SIZE),
      shortTapsTiled_(spirv_stereo_seed_tiled_comp, pushBytesFor(S3D_STEREO_SMALL_TAP_CAPACITY), S3D_STEREO_ROW_TILE, 1),
      allTapsTiled_(spirv_stereo_search_tiled_comp, pushBytesFor(S3D_STEREO_MAX_TAPS), S3D_STEREO_ROW_TILE, 1) {}

void StereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                        const vk::Image& leftEye, const vk::Image& rightEye,
                        const gpu::StereoConstants& constants) const {
  if (constants.tapCount < 0 || constants.tapCount > S3D_STEREO_MAX_TAPS)
    throw std::invalid_argument("StereoPass: tap count out of range (use makeStereoConstants)");
  const bool shortTaps = constants.tapCount <= S3D_STEREO_SMALL_TAP_CAPACITY;
  const bool rowTiles =
      deviceRunsRowTiles_ && usesRowTiles(kernel_, rowTileMargin(constants), context_->isCpuDevice());
  const detail::LazyEyePairPipeline& pipeline =
      rowTiles ? (shortTaps ? shortTapsTiled_ : allTapsTiled_) : (shortTaps ? shortTaps_ : allTaps_);
  detail::recordEyePairDispatch(cmd, *context_, pipeline.get(*context_), centerColor, linearDepth, leftEye, rightEye, &constants,
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
                                 const gpu::StereoConstants& constants, StereoKernel kernel) {
  return detail::runOnCpuImages(context, StereoPass(context, kernel), center, linearDepth, constants);
}

}  // namespace s3d::stereo
