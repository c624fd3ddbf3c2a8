#pragma once
// The forward method (forward.h) on the GPU: a drop-in for StereoPass with the same four bindings, plus two
// z-buffers (R32UI, one per eye) it owns, created at the first record for the image size and reused (a record
// at another size replaces them: finish command buffers using the old size first).
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/forward.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// Reads: center color (RGBA8, display-encoded) and linear depth (R32F), both in VK_IMAGE_LAYOUT_GENERAL.
// Writes: left and right eye (RGBA8, GENERAL). Three dispatches (clear the z-buffers; splat; resolve and fill)
// with compute barriers between them; StereoPass::recordInputBarriers / recordInputRelease apply unchanged.
class ForwardStereoPass {
 public:
  explicit ForwardStereoPass(const vk::Context& context);
  void record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
              const vk::Image& leftEye, const vk::Image& rightEye, const gpu::ForwardConstants& constants) const;
  // The z-buffer of one eye after the last record (R32UI, GENERAL, last accessed by compute shader reads and
  // writes): a pass recorded after this one reads it to know the holes (previous_fill_pass.h). Throws before a record.
  const vk::Image& keys(Eye eye) const;

 private:
  const vk::Context* context_;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> clear_, splat_, resolve_;
  struct ZBuffers {
    vk::Image left, right;
  };
  mutable std::optional<ZBuffers> zBuffers_;
};

// Uploads CPU images, runs the pass once and reads both eyes back (tests, tools).
StereoPair synthesizeForwardOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                  const gpu::ForwardConstants& constants);

}  // namespace s3d::stereo
