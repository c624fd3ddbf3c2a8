#pragma once
// The previous-frame fill (previous_fill_shared.h) on the GPU, recorded right after ForwardStereoPass: the
// forward method's holes take the previous frame's eyes, reprojected with their depth and the camera's motion.
// The pass owns the history (per eye an RGBA8 colour and an R32F depth image, two of each: the previous frame's
// and this frame's), created at the first record for the size.
#include <array>
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/forward_pass.h"
#include "s3d/stereo/previous_fill.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class PreviousFillPass {
 public:
  explicit PreviousFillPass(const vk::Context& context);

  // Reads: the eyes ForwardStereoPass::record just wrote (RGBA8, GENERAL, compute writes) and its z-buffers
  // (construct it with ForwardKeys::Kept); the previous frame's history. Writes: the eyes (filled in place, left in compute-write state) and this frame's
  // history. Records the barriers it needs after the forward pass. Recording it again before advance() redoes the
  // same frame (the same history is read and written again), so a frame may be recorded for warm-up and timing.
  void record(VkCommandBuffer cmd, const ForwardStereoPass& forward, const vk::Image& leftEye, const vk::Image& rightEye,
              const gpu::ForwardConstants& constants, const std::array<gpu::EyeMotion, 2>& motion) const;
  // The frame is done: its history becomes the previous frame's (submit the recorded frames in order).
  void advance();
  // The next frame has no history (a camera cut, or the first frame); a record at a new size also starts afresh.
  void reset() { hasHistory_ = false; }
  bool hasHistory() const { return hasHistory_; }

 private:
  struct EyeImages {
    vk::Image color, depth;
  };
  const vk::Context* context_;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;
  // [slot][eye]: slot `previous_` holds the previous frame's history, the other this frame's.
  mutable std::optional<std::array<std::array<EyeImages, 2>, 2>> history_;
  mutable bool fresh_ = true;  // the images were just created (undefined contents)
  int previous_ = 0;
  bool hasHistory_ = false;
  mutable bool recorded_ = false;
};

}  // namespace s3d::stereo
