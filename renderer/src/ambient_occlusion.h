#pragma once
// Screen-space ambient occlusion at half resolution (ssao, then ssao-blur), upsampled by the lighting pass.
// Reads device depth only (normals come from depth), the frame constants and the tile buffer; writes two
// half-resolution RG16F images (occlusion, linear depth), the blurred one left readable by compute.
#include <cstdint>
#include <memory>

#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"
#include "tile_lists.h"

namespace s3d::renderer::detail {

class AmbientOcclusion {
 public:
  // counting: the renderer counts shaded pixels (RendererOptions::countShadedPixels).
  AmbientOcclusion(vk::Context& context, std::uint32_t renderWidth, std::uint32_t renderHeight, bool counting);

  std::uint32_t width() const { return occlusion_.width; }  // ceil(render size / 2)
  std::uint32_t height() const { return occlusion_.height; }

  // ssao: `depth` sampled by compute (SHADER_READ_ONLY). A masked render runs over the tile buffer's
  // ambient-region list (indirect), an unmasked one over every tile.
  void recordOcclusion(VkCommandBuffer cmd, const vk::Image& depth, VkBuffer frameBuffer, VkBuffer tiles, bool masked);
  // ssao-blur: leaves the result readable by compute.
  void recordBlur(VkCommandBuffer cmd, VkBuffer frameBuffer, VkBuffer tiles, bool masked);
  // Without ambient occlusion this frame: the result readable (and never read), so lighting can bind it.
  void recordUnused(VkCommandBuffer cmd);
  VkDescriptorImageInfo result() const;

 private:
  void dispatch(VkCommandBuffer cmd, VkBuffer tiles, bool masked) const;
  void pushDescriptors(VkCommandBuffer cmd, VkBuffer frameBuffer, VkDescriptorImageInfo input, const vk::Image& output,
                       VkBuffer tiles) const;

  vk::Context& context_;
  vk::Image occlusion_, blurred_;
  vk::Unique<VkSampler> nearest_;
  vk::PipelineLayout layout_;  // both passes: frame, input (sampled), output (storage), tiles
  std::unique_ptr<TilePipelines> occlusionPipelines_, blurPipelines_;
};

}  // namespace s3d::renderer::detail
