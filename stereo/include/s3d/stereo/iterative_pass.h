#pragma once
// The iterative gather method (iterative.h) on the GPU: a drop-in for StereoPass with the same bindings.
#include <vulkan/vulkan.h>

#include "s3d/stereo/iterative.h"
#include "s3d/stereo/detail/eye_pair_pipeline.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// Reads: center color (RGBA8, display-encoded) and linear depth (R32F), both in VK_IMAGE_LAYOUT_GENERAL.
// Writes: left and right eye (RGBA8, GENERAL). One dispatch produces both eyes. Bindings 0-3 as StereoPass,
// so StereoPass::recordInputBarriers / recordInputRelease apply unchanged; per pixel or on row tiles as StereoPass.
class IterativeStereoPass {
 public:
  explicit IterativeStereoPass(const vk::Context& context, StereoKernel kernel = StereoKernel::Auto);
  void record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
              const vk::Image& leftEye, const vk::Image& rightEye, const gpu::IterativeConstants& constants) const;

 private:
  const vk::Context* context_;
  StereoKernel kernel_;
  bool deviceRunsRowTiles_;
  detail::LazyEyePairPipeline perPixel_;
  detail::LazyEyePairPipeline rowTiles_;
};

// Uploads CPU images, runs the pass once and reads both eyes back (tests, tools).
StereoPair synthesizeIterativeOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                    const gpu::IterativeConstants& constants, StereoKernel kernel = StereoKernel::Auto);

}  // namespace s3d::stereo
