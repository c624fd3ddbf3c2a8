#pragma once
// The tile buffer of the renderer's compute passes (gpu::TileHeader, then per tile the ambient-region flag,
// the masked-tile list, the ambient-region list, the lighting classes' lists and the light lists): the masked
// render's tile-list pass (mask-tiles), the indirect dispatch counts it and the lighting's classification leave
// for the passes after them, and the shaded-pixel counters of a counting render.
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "s3d/renderer/renderer_shared.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer::detail {

// The states a shade mask is read in: storage image reads by compute (the tiles, lighting, resolve) and by the
// fragment stage (the G-buffer's depth fill).
inline constexpr vk::ImageState kShadeMaskRead{VK_IMAGE_LAYOUT_GENERAL,
                                               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                               VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
inline constexpr vk::ImageState kShadeMaskComputeRead{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT};

// A compute pass that runs over tiles (tiles.glsl), specialized: constant 0 a masked render, 1 shaded-pixel
// counting, 2... the pass's own switches (`switches`, in order), then its 32-bit values (`values`, in order).
vk::Unique<VkPipeline> createTilePipeline(const vk::Context& context, VkPipelineLayout layout,
                                          std::span<const std::uint32_t> spirv, bool masked, bool counting,
                                          std::span<const bool> switches = {},
                                          std::span<const std::uint32_t> values = {});

// The variants of a tile pass a renderer uses (its counting fixed), each made at its first use: a CPU rasterizer
// runs both sides of every branch, so what a frame does not need is compiled out rather than skipped.
class TilePipelines {
 public:
  // values: the pass's 32-bit specialization constants, the same in every variant (after its switches).
  TilePipelines(const vk::Context& context, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                bool counting, std::vector<std::uint32_t> values = {})
      : context_(&context), layout_(layout), spirv_(spirv), counting_(counting), values_(std::move(values)) {}
  VkPipeline get(bool masked, std::initializer_list<bool> switches = {});

 private:
  const vk::Context* context_;
  VkPipelineLayout layout_;
  std::span<const std::uint32_t> spirv_;
  bool counting_;
  std::vector<std::uint32_t> values_;
  std::map<std::uint32_t, vk::Unique<VkPipeline>> pipelines_;
};

class TileLists {
 public:
  TileLists(vk::Context& context, std::uint32_t renderWidth, std::uint32_t renderHeight);

  std::uint32_t tilesX() const { return tilesX_; }
  std::uint32_t tilesY() const { return tilesY_; }
  VkBuffer buffer() const { return buffer_.buffer; }
  VkDescriptorBufferInfo descriptor() const { return {buffer_.buffer, 0, VK_WHOLE_SIZE}; }
  static constexpr VkDeviceSize kMaskedTilesDispatch = offsetof(gpu::TileHeader, lightingDispatch);
  static constexpr VkDeviceSize kAmbientTilesDispatch = offsetof(gpu::TileHeader, ambientDispatch);

  // Zeroes the counters and the dispatch counts (and, for a masked render, the ambient-region flags) in a compute
  // dispatch reading the frame constants, then makes the buffer readable and writable by compute and readable as
  // indirect arguments. `mask` (masked renders): the host's image, made readable after any earlier write: by
  // compute, and by the fragment stage where `fragmentReads` (a raster G-buffer; a compute-only frame names no
  // graphics stage).
  // `resetAhead`: a masked render whose reset a caller recorded earlier (recordMaskedResetAhead): only the mask's
  // transition and the closing barrier.
  void recordReset(VkCommandBuffer cmd, VkBuffer frameBuffer, const vk::Image* mask, bool fragmentReads,
                   bool resetAhead = false);
  // A masked render's reset dispatch alone, without barriers, for a caller that runs it beside other work: ordered
  // after the previous frame's uses of the buffer, and before the render, by the caller.
  void recordMaskedResetAhead(VkCommandBuffer cmd, VkBuffer frameBuffer) const;
  // mask-tiles: reads the frame constants and the mask; writes the lists and dispatch counts, readable by the
  // compute passes and their indirect dispatches after it.
  void recordBuild(VkCommandBuffer cmd, VkBuffer frameBuffer, const vk::Image& mask);
  // After a compute pass wrote lists or dispatch counts: readable by compute and by indirect dispatches.
  static void recordListsVisible(VkCommandBuffer cmd);
  static constexpr VkDeviceSize tileClassDispatch(std::uint32_t tileClass) {
    return offsetof(gpu::TileHeader, tileClassDispatch) + tileClass * sizeof(glm::uvec4);
  }
  // Counting renders: the render pixels the G-buffer wrote (material target readable by compute).
  void recordCountGBuffer(VkCommandBuffer cmd, VkBuffer frameBuffer, const vk::Image& material, VkSampler nearest);
  // After the last pass: the counters into host memory (readCounts after the submission completes).
  void recordCountReadback(VkCommandBuffer cmd);
  std::array<std::uint32_t, S3D_COUNT_SLOTS> readCounts() const;

  // The mask as a storage-image descriptor, or a 1x1 placeholder for unmasked renders (never read then).
  VkDescriptorImageInfo maskDescriptor(const vk::Image* mask) const;

 private:
  void bindBuildLayoutPass(VkCommandBuffer cmd, VkPipeline pipeline, VkBuffer frameBuffer, const vk::Image* mask) const;

  vk::Context& context_;
  std::uint32_t width_, height_, tilesX_, tilesY_;
  vk::Buffer buffer_;    // device local
  vk::Buffer readback_;  // host visible: the header
  vk::Image placeholderMask_;
  vk::PipelineLayout buildLayout_, countLayout_;
  vk::Unique<VkPipeline> build_, count_, reset_, resetMasked_;
};

}  // namespace s3d::renderer::detail
