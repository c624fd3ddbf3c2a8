#pragma once
// The G-buffer resolve (shaders/gbuffer_resolve.comp): after the G-buffer pass has rasterized depth and
// visibility ids, it evaluates each pixel's normal/glossiness and material in compute, which runs on the whole
// chip where the raster pass's cost follows the bytes each fragment writes. Pixels the raster pass shaded itself
// (textured objects) are kept; sky pixels get the cleared values. Counts the render pixels with a surface.
//
// With surface materials (ray-cast surfaces, which no raster pass shades) it also textures and flips what the
// raster pass would: textured and double-sided objects, sampling the scene's texels from storage buffers.
//
// Reads: device depth and the visibility target (sampled by compute), the frame and object constants, the index
// and vertex buffers, the tile buffer (a masked render also the shade mask), the surface vertices and texels.
// Writes: the normal/glossiness and material targets (storage images, GENERAL), left sampled by compute
// (SHADER_READ_ONLY) for the passes after it.
#include <cstdint>
#include <memory>

#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"
#include "tile_lists.h"

namespace s3d::renderer::detail {

class GBufferResolve {
 public:
  // counting: the renderer counts shaded pixels (RendererOptions::countShadedPixels).
  GBufferResolve(vk::Context& context, bool counting);

  struct Inputs {
    const vk::Image& depth;       // sampled by compute
    const vk::Image& visibility;  // sampled by compute
    VkBuffer frameConstants, objectConstants, indices, vertices, tiles;
    VkDescriptorImageInfo shadeMask;  // the tile lists' mask descriptor (placeholder when unmasked)
    bool masked;
    std::uint32_t tilesX, tilesY;
    // Read only with surfaceMaterials (any valid buffer otherwise): gpu::SurfaceVertex per vertex, the texture
    // table (first texel, width, height, sRGB per texture) and the RGBA8 texels (surface_texels.glsl).
    VkBuffer surfaceVertices, textureTable, texels;
    bool surfaceMaterials;
  };
  // `targets`: the state the G-buffer pass left them in (kUndefined when it wrote neither).
  void record(VkCommandBuffer cmd, const Inputs& inputs, const vk::Image& normalGlossiness, const vk::Image& material,
              const vk::ImageState& targets);

 private:
  vk::Context& context_;
  vk::PipelineLayout layout_;
  std::unique_ptr<TilePipelines> pipelines_;
  vk::Unique<VkSampler> nearest_;
};

}  // namespace s3d::renderer::detail
