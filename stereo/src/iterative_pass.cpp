#include "s3d/stereo/iterative_pass.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/stereo_pass.h"

// clang-format off
#include <s3d_spirv/stereo_iterative_comp.h>
#include <s3d_spirv/stereo_iterative_tiled_comp.h>
// clang-format on

namespace s3d::stereo {

IterativeStereoPass::IterativeStereoPass(const vk::Context& context, StereoKernel kernel)
    : context_(&context),
      kernel_(kernel),
      deviceRunsRowTiles_(detail::deviceRunsRowTiles(context)),
      perPixel_(spirv_stereo_iterative_comp, sizeof(gpu::IterativeConstants), S3D_ITERATIVE_GROUP_SIZE,
                S3D_ITERATIVE_GROUP_SIZE),
      rowTiles_(spirv_stereo_iterative_tiled_comp, sizeof(gpu::IterativeConstants), S3D_STEREO_ROW_TILE, 1) {}

void IterativeStereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                                 const vk::Image& leftEye, const vk::Image& rightEye,
                                 const gpu::IterativeConstants& constants) const {
  // The shader trusts these: they bound its loops and the tap array.
  if (constants.iterations < 1 || constants.iterations > S3D_ITERATIVE_MAX_ITERATIONS ||
      constants.startTapCount < 0 || constants.startTapCount > S3D_ITERATIVE_START_TAPS)
    throw std::invalid_argument("IterativeStereoPass: iterations or start taps out of range (use makeIterativeConstants)");
  const bool rowTiles =
      deviceRunsRowTiles_ && usesRowTiles(kernel_, rowTileMargin(constants), context_->isCpuDevice());
  const detail::LazyEyePairPipeline& pipeline = rowTiles ? rowTiles_ : perPixel_;
  detail::recordEyePairDispatch(cmd, *context_, pipeline.get(*context_), centerColor, linearDepth, leftEye, rightEye, &constants,
                                constants.width, constants.height, "IterativeStereoPass");
}

StereoPair synthesizeIterativeOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                    const gpu::IterativeConstants& constants, StereoKernel kernel) {
  return detail::runOnCpuImages(context, IterativeStereoPass(context, kernel), center, linearDepth, constants);
}

}  // namespace s3d::stereo
