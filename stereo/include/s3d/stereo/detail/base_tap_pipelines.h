#pragma once
// A hybrid shader that replays the gather base's taps (stereo_gather_source.glsl), compiled for the base's tap
// array: short (a seed or a search of up to S3D_STEREO_SMALL_TAP_CAPACITY taps: the default base) or the full
// S3D_STEREO_MAX_TAPS. A loop unrolled to the full array with most taps guarded off cost the GPU time, so the
// capacity is the shader's last specialization constant; the short pipeline is made at once, the full one at
// first use (lavapipe compiles at creation).
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "s3d/stereo/stereo_shared.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"

namespace s3d::stereo::detail {

class BaseTapPipelines {
 public:
  // constants: the shader's other specialization constants, ids 0, 1, ... as 32-bit words; the tap capacity
  // takes the next id.
  BaseTapPipelines(const vk::Context& context, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                   std::vector<std::uint32_t> constants)
      : context_(&context), layout_(layout), spirv_(spirv), constants_(std::move(constants)) {
    short_ = create(S3D_STEREO_SMALL_TAP_CAPACITY);
  }

  // The pipeline for a base of `tapCount` taps (0: no gather base, the short one).
  VkPipeline forTaps(int tapCount) const {
    if (tapCount <= S3D_STEREO_SMALL_TAP_CAPACITY) return short_.get();
    if (!full_) full_ = create(S3D_STEREO_MAX_TAPS);
    return full_->get();
  }

 private:
  vk::Unique<VkPipeline> create(std::uint32_t capacity) const {
    std::vector<std::uint32_t> values = constants_;
    values.push_back(capacity);
    return vk::createComputePipeline(*context_, layout_, spirv_, vk::SpecializationWords(std::move(values)));
  }

  const vk::Context* context_;
  VkPipelineLayout layout_;
  std::span<const std::uint32_t> spirv_;
  std::vector<std::uint32_t> constants_;
  vk::Unique<VkPipeline> short_;
  mutable std::optional<vk::Unique<VkPipeline>> full_;
};

}  // namespace s3d::stereo::detail
