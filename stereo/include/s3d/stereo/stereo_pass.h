#pragma once
// The stereo compute pass (Listing 4.5) on the GPU.
#include <vulkan/vulkan.h>

#include "s3d/stereo/stereo.h"
#include "s3d/stereo/detail/eye_pair_pipeline.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// Reads: center color (RGBA8, display-encoded) and linear depth (R32F), both in VK_IMAGE_LAYOUT_GENERAL.
// Writes: left and right eye (RGBA8, GENERAL). One dispatch produces both eyes, per pixel or on row tiles
// (`kernel`, chosen per dispatch for Auto); each pipeline is created at its first dispatch.
class StereoPass {
 public:
  explicit StereoPass(const vk::Context& context, StereoKernel kernel = StereoKernel::Auto);
  void record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
              const vk::Image& leftEye, const vk::Image& rightEye, const gpu::StereoConstants& constants) const;

  // Barriers for inputs another compute pass just wrote (vk::kComputeWrite, e.g. the renderer's resolve):
  // before the dispatch the inputs become readable and the eyes writable; after it the inputs go back to
  // the state their producer expects.
  static void recordInputBarriers(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                                  const vk::Image& leftEye, const vk::Image& rightEye);
  static void recordInputRelease(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth);

  static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_R32_SFLOAT;

 private:
  const vk::Context* context_;
  StereoKernel kernel_;
  bool deviceRunsRowTiles_;  // per pixel wherever the device's workgroup limits are too small
  detail::LazyEyePairPipeline shortTaps_;  // up to S3D_STEREO_SMALL_TAP_CAPACITY taps (the seed)
  detail::LazyEyePairPipeline allTaps_;    // up to S3D_STEREO_MAX_TAPS
  detail::LazyEyePairPipeline shortTapsTiled_;
  detail::LazyEyePairPipeline allTapsTiled_;
};

// Uploads CPU images, runs the pass once and reads both eyes back (tests, `s3d convert`).
StereoPair synthesizeStereoOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                 const gpu::StereoConstants& constants, StereoKernel kernel = StereoKernel::Auto);

}  // namespace s3d::stereo
