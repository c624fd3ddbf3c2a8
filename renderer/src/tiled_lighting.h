#pragma once
// The tiled deferred lighting pass: per tile, point and spot lights culled against the tile's depth range and
// the tile classed as sky, unlit or lit (shaders/light_tiles.comp); then per class a variant of
// shaders/lighting.comp, dispatched over the class's tiles: per pixel, ambient x occlusion, the sun with its
// cascaded shadow, the tile's lights with their shadow maps and the material, or the sky. Owns its pipelines
// and the per-frame light buffer.
//
// Reads: device depth, normal/glossiness and material targets and the half-resolution occlusion (sampled by
// compute), the shadow atlases and constants, the frame and object constants, the tile buffer (a masked render
// also the shade mask). Writes: HDR colour (storage image, GENERAL) at every shaded pixel, or, resolving in
// place, the resolve's outputs (display colour, resolved HDR, linear depth) instead.
#include <cstdint>
#include <memory>

#include "s3d/renderer/view_matrices.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"
#include "shadow_maps.h"
#include "tile_lists.h"

namespace s3d::renderer::detail {

class TiledLighting {
 public:
  // counting: the renderer counts shaded pixels (RendererOptions::countShadedPixels).
  TiledLighting(vk::Context& context, bool counting);

  // Sizes the light buffer for the scene's point and spot lights (at most S3D_MAX_LIGHTS).
  void setScene(const Scene& scene);
  // The frame's lights (those whose sphere touches the view frustum) into the light buffer, those with a shadow
  // map this frame first (call after ShadowMaps::schedule).
  void prepareFrame(const Scene& scene, const ViewMatrices& view, const ShadowMaps& shadows);

  struct Inputs {
    const vk::Image& depth;
    const vk::Image& normalGlossiness;
    const vk::Image& material;
    VkDescriptorImageInfo ambientOcclusion;
    VkBuffer frameConstants;
    VkBuffer objectConstants;
    VkBuffer tiles;
    VkDescriptorImageInfo shadeMask;  // the tile lists' mask descriptor (placeholder when unmasked)
    bool masked;
    std::uint32_t tilesX, tilesY;
  };
  struct Outputs {
    const vk::Image& hdr;  // render size
    // The resolve's outputs, written instead when resolveInPlace (render size = output size then).
    const vk::Image& display;
    const vk::Image& resolvedHdr;
    const vk::Image& linearDepth;
    bool resolveInPlace;
    bool displayKeepsUnshaded;  // display is in vk::kComputeWrite and keeps the pixels this render does not shade
  };
  // All outputs in any state (display in vk::kComputeWrite where it keeps its unshaded pixels), left in
  // vk::kComputeWrite (those not written: undefined contents).
  void record(VkCommandBuffer cmd, const Inputs& inputs, const ShadowMaps& shadows, const Outputs& outputs);

 private:
  vk::Context& context_;
  vk::PipelineLayout layout_, classifyLayout_;
  std::unique_ptr<TilePipelines> pipelines_, classifyPipelines_;
  vk::Unique<VkSampler> nearest_;
  vk::Buffer lights_;  // gpu::LightConstants, host visible: the frame's shadowed lights, then the others
  std::uint32_t lightCount_ = 0, shadowedLightCount_ = 0;
  bool sunShadowed_ = false;
};

}  // namespace s3d::renderer::detail
