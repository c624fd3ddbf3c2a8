#pragma once
// The frame's depth range (depth_range.h) on the GPU: one compute dispatch over the linear depth image. Its
// workgroups add into small device counters (nearest, farthest, sky and invalid counts, 192 histogram bins: 784
// bytes); the last workgroup to finish writes them into a host-visible buffer, the only thing read back, and resets
// them for the next reduction, so no clear or copy runs between compute passes.
#include <cstdint>
#include <functional>
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/depth_range.h"
#include "s3d/stereo/depth_range_shared.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// How the reduction's dispatch is cut: square workgroups of groupSide^2 invocations, each reducing `run` pixels of a
// row. Any shape gives the same result; the device's (depthReductionShapeFor) is the faster measured there.
struct DepthReductionShape {
  std::uint32_t groupSide = S3D_DEPTH_CPU_GROUP_SIDE;
  std::uint32_t run = S3D_DEPTH_CPU_RUN;
};
inline constexpr DepthReductionShape kDepthReductionCpuShape{S3D_DEPTH_CPU_GROUP_SIDE, S3D_DEPTH_CPU_RUN};
inline constexpr DepthReductionShape kDepthReductionGpuShape{S3D_DEPTH_GPU_GROUP_SIDE, S3D_DEPTH_GPU_RUN};
DepthReductionShape depthReductionShapeFor(const vk::Context& context);

class DepthRangePass {
 public:
  // Uploads the counters' starting values (submits on the context's queue and waits). Without a shape, the
  // device's; a shape beyond the device's workgroup limits throws std::invalid_argument.
  explicit DepthRangePass(vk::Context& context, std::optional<DepthReductionShape> shape = std::nullopt);
  // Reduces `linearDepth` (R32F, GENERAL, readable by compute shaders) into the result. Recordings of one pass run
  // in submission order: each begins with a barrier after the compute work before it on the queue.
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
  // Dispatches the bound reduction over width x height after the queue's earlier compute work.
  void recordReduction(VkCommandBuffer cmd, const std::function<void()>& bindAndPush, std::uint32_t width,
                       std::uint32_t height) const;

  const vk::Context* context_;
  DepthReductionShape shape_;
  vk::PipelineLayout layout_, hostLayout_;
  vk::Unique<VkPipeline> pipeline_, hostPipeline_;
  vk::Unique<VkSampler> sampler_;  // nearest, clamped: the host depth's texels as they are
  vk::Buffer counters_;  // device memory: the dispatch's atomics, at their starting values between dispatches
  vk::Buffer buffer_;    // host-visible and coherent: the last dispatch's result, read straight from the mapping
};

struct TimedDepthRange {
  DepthRange range;
  std::optional<double> gpuMs;  // the dispatch alone, from timestamps; empty without them
};

// Reduces an image the renderer left in vk::kComputeWrite state (and leaves it so).
TimedDepthRange reduceDepthRangeTimed(vk::Context& context, const DepthRangePass& pass, const vk::Image& linearDepth);

// Uploads a CPU image and reduces it (tests), with the device's shape or the one given.
DepthRange reduceDepthRangeOnGpu(vk::Context& context, const DepthImage& linearDepth,
                                 std::optional<DepthReductionShape> shape = std::nullopt);

}  // namespace s3d::stereo
