#pragma once
// The nonlinear depth-to-parallax mapping on the GPU (disparity_map.h): one dispatch that rewrites the stereo
// pass's R32F linear depth in place through gpu::mappedDepth, recorded right before the stereo pass. Created
// once; records into the caller's command buffer with push constants only (nothing allocated per frame).
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/disparity_map.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class DisparityMapPass {
 public:
  explicit DisparityMapPass(const vk::Context& context);
  // Maps `linearDepth` (R32F, GENERAL, storage; the caller orders earlier writes before this compute read and
  // the stereo pass's reads after its write, e.g. with vk::kComputeWrite -> vk::kComputeWrite barriers). The
  // identity map records nothing.
  void record(VkCommandBuffer cmd, const vk::Image& linearDepth, const gpu::DisparityMapConstants& map) const;

 private:
  const vk::Context* context_;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;
};

// Maps an image the renderer left in vk::kComputeWrite state (and leaves it so); the GPU time of the dispatch
// from timestamps (empty without them or for the identity).
std::optional<double> mapDepthTimed(vk::Context& context, const DisparityMapPass& pass, const vk::Image& linearDepth,
                                    const gpu::DisparityMapConstants& map);

// Uploads a CPU image, maps it and reads it back (tests).
DepthImage mapDepthOnGpu(vk::Context& context, const DepthImage& linearDepth, const gpu::DisparityMapConstants& map);

}  // namespace s3d::stereo
