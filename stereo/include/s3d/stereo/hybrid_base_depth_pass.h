#pragma once
// The hybrid's base depth on the GPU (shaders/stereo_hybrid_base_depth.comp, or with the gather base itself in
// stereo_*_base_depth.comp; math and reference in hybrid_base_depth.h): both eyes' device depth from the center's, at
// the gather base's source texels.
#include <vulkan/vulkan.h>

#include "s3d/stereo/detail/base_tap_pipelines.h"
#include "s3d/stereo/hybrid_shared.h"
#include "s3d/stereo/stereo_shared.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class HybridBaseDepthPass {
 public:
  explicit HybridBaseDepthPass(const vk::Context& context);

  // An R32_SFLOAT storage image (readable back) for one eye's depth.
  static vk::Image createEyeDepth(const vk::Context& context, std::uint32_t width, std::uint32_t height);

  // linearDepth: the center's (R32F, GENERAL); deviceDepth: the center's device depth (D32_SFLOAT or R32_SFLOAT,
  // VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampled); both written earlier and made visible to compute by the
  // caller. leftDepth, rightDepth: R32_SFLOAT storage images in GENERAL, written by one compute dispatch (the
  // caller orders later reads). Throws std::invalid_argument for another size than the constants' or constants
  // without a gather base.
  void record(VkCommandBuffer cmd, const vk::Image& linearDepth, const vk::Image& deviceDepth, const vk::Image& leftDepth,
              const vk::Image& rightDepth, const gpu::HybridConstants& constants) const;
  // The gather base itself (seed or search, `gather` its constants: makeStereoConstants of the hybrid's
  // displacementParameters) into leftEye and rightEye, as StereoPass::record writes them per pixel, and the base
  // depth, as record() writes it for the same frame's hybrid constants, in one dispatch that finds each source column
  // once (a frame's base and base depth for the cost of the base and the depth's writes). Images and states as in
  // StereoPass::record and record(). Throws std::invalid_argument for a size other than the constants' or a tap count
  // out of range.
  void recordWithGather(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                        const vk::Image& deviceDepth, const vk::Image& leftEye, const vk::Image& rightEye,
                        const vk::Image& leftDepth, const vk::Image& rightDepth,
                        const gpu::StereoConstants& gather) const;

 private:
  const vk::Context* context_;
  vk::Unique<VkSampler> nearest_;
  vk::PipelineLayout layout_;
  detail::BaseTapPipelines pipeline_;
  vk::PipelineLayout gatherLayout_;
  // Made at first use (a CPU device compiles at creation, and its hybrid rasterizes the eyes: no base depth).
  mutable vk::Unique<VkPipeline> gatherShortTaps_;  // up to S3D_STEREO_SMALL_TAP_CAPACITY taps (the default base)
  mutable vk::Unique<VkPipeline> gatherAllTaps_;    // up to S3D_STEREO_MAX_TAPS
};

}  // namespace s3d::stereo
