#pragma once
// The frame's depth range (depth_range.h) on the GPU: one compute dispatch over the linear depth image into a
// small device buffer (nearest, farthest, sky and invalid counts, 192 histogram bins: 784 bytes), copied to a
// host-visible one: the only thing read back.
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/depth_range.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class DepthRangePass {
 public:
  explicit DepthRangePass(const vk::Context& context);
  // Clears the result buffer and reduces `linearDepth` (R32F, GENERAL, readable by compute shaders).
  void record(VkCommandBuffer cmd, const vk::Image& linearDepth) const;
  // The result of the last recorded dispatch, once its submission has completed.
  DepthRange result() const;

 private:
  const vk::Context* context_;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;
  vk::Buffer counters_;  // device memory: the dispatch's atomics
  vk::Buffer buffer_;    // host-visible and coherent: the copy of counters_ read straight from the mapping
};

struct TimedDepthRange {
  DepthRange range;
  std::optional<double> gpuMs;  // the dispatch alone, from timestamps; empty without them
};

// Reduces an image the renderer left in vk::kComputeWrite state (and leaves it so).
TimedDepthRange reduceDepthRangeTimed(vk::Context& context, const DepthRangePass& pass, const vk::Image& linearDepth);

// Uploads a CPU image and reduces it (tests).
DepthRange reduceDepthRangeOnGpu(vk::Context& context, const DepthImage& linearDepth);

}  // namespace s3d::stereo
