#pragma once
// The frame's depth range (depth_range.h) on the GPU: one compute dispatch over the linear depth image into a
// small device buffer (nearest, farthest, sky and invalid counts, 192 histogram bins: 784 bytes), copied to a
// host-visible one: the only thing read back.
#include <cstdint>
#include <functional>
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/depth_range.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class DepthRangePass {
 public:
  explicit DepthRangePass(const vk::Context& context);
  // Clears the result buffer and reduces `linearDepth` (R32F, GENERAL, readable by compute shaders).
  void record(VkCommandBuffer cmd, const vk::Image& linearDepth) const;
  // The same for a host's depth buffer as it is, sampled: D32, D24S8 or D16 linearized with `projection` as the
  // stereo pass reads it (the first-person layer pushed by the weapon offset and scale), or R32F linear depth. With
  // a stage in the HostImage, s3d barriers it from its layout into a readable one and back (as HostStereoPass);
  // with VK_PIPELINE_STAGE_2_NONE it must be in a layout a compute shader samples. Throws std::invalid_argument
  // naming the problem for another format or an unreadable layout.
  void recordHost(VkCommandBuffer cmd, const HostImage& depth, std::uint32_t width, std::uint32_t height,
                  const HostProjection& projection, float weaponDepthOffset = 1.0f, float weaponDepthScale = 1.0f) const;
  // The result of the last recorded dispatch, once its submission has completed.
  DepthRange result() const;

 private:
  // Clears the counters, dispatches the bound reduction over width x height, copies the result back.
  void recordReduction(VkCommandBuffer cmd, const std::function<void()>& bindAndPush, std::uint32_t width,
                       std::uint32_t height) const;

  const vk::Context* context_;
  vk::PipelineLayout layout_, hostLayout_;
  vk::Unique<VkPipeline> pipeline_, hostPipeline_;
  vk::Unique<VkSampler> sampler_;  // nearest, clamped: the host depth's texels as they are
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
