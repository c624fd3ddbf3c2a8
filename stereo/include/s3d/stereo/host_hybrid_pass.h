#pragma once
// The hybrid for a host's own renderer (stereo_frame.h, StereoMethod::Hybrid): the base search into the host's
// eyes, the classification, threshold and masks (HybridPass), and each eye's mask as a depth image the host draws
// that eye with, so that its ordinary depth test leaves every unmasked pixel alone. Everything is made at
// construction; recording allocates nothing.
#include <cstdint>

#include <vulkan/vulkan.h>

#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/stereo/hybrid_pass.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class HostHybridPass {
 public:
  // cell: the classification's (hybridCellFor); recordKernel refuses parameters of another.
  HostHybridPass(vk::Context& context, std::uint32_t width, std::uint32_t height, StereoKernel kernel, int cell);

  // Inside HostStereoPass::record as its kernel (inputs and eyes GENERAL, ordered after the conversion): the base
  // displacement (parameters' hybridBase) into the eyes, the masks, and both eyes' mask depth into the pass's
  // buffer (reversedZ: far is 0), ordered before recordMaskCopies' copies.
  void recordKernel(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                    const vk::Image& leftEye, const vk::Image& rightEye, const StereoParameters& parameters,
                    bool reversedZ);
  // Copies each eye's mask depth into the host's D32 image (depth aspect, its layer). With a stage in the
  // HostImage, barriers from its layout, stage and access into TRANSFER_DST_OPTIMAL and back; with
  // VK_PIPELINE_STAGE_2_NONE the image must already be in TRANSFER_DST_OPTIMAL or GENERAL and the host orders
  // its depth tests after the copy (stage COPY, access TRANSFER_WRITE) itself.
  void recordMaskCopies(VkCommandBuffer cmd, const HostImage& leftMask, const HostImage& rightMask) const;

 private:
  const vk::Context* context_;
  std::uint32_t width_, height_;
  StereoPass displacement_;
  HybridPass hybrid_;
  HybridPass::Images images_;
  vk::Buffer depths_;  // both eyes' mask depth, left then right, width x height floats each
  vk::PipelineLayout depthLayout_;
  vk::Unique<VkPipeline> depthPipeline_;
};

}  // namespace s3d::stereo
