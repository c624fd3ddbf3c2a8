#pragma once
// The resolve (shaders/resolve.comp): the lit HDR image to the display image (exposure, filmic curve, sRGB; the
// supersamples of an output pixel averaged after the curve) and device depth to the stereo pass's linear depth
// (the nearest sample's). It runs as its own pass only after a transparent pass or with supersampling; otherwise
// the lighting pass writes the same outputs in place.
//
// Reads: the HDR image (storage, GENERAL; written by lighting or the transparent pass), device depth (sampled by
// compute), the frame constants, the tile buffer (a masked render also the shade mask). Writes: the display
// colour, the resolved HDR colour and the linear depth (storage images at output size, GENERAL), left in
// vk::kComputeWrite state.
#include <cstdint>
#include <memory>

#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"
#include "tile_lists.h"

namespace s3d::renderer::detail {

class ResolvePass {
 public:
  // counting: the renderer counts shaded pixels (RendererOptions::countShadedPixels).
  ResolvePass(vk::Context& context, bool counting);

  struct Inputs {
    const vk::Image& hdr;    // render size
    bool hdrJustWritten;     // lighting wrote it last (kComputeWrite); false: the transparent pass left it kComputeRead
    const vk::Image& depth;  // sampled by compute
    VkBuffer frameConstants, tiles;
    VkDescriptorImageInfo shadeMask;  // the tile lists' mask descriptor (placeholder when unmasked)
    bool masked;
    std::uint32_t supersample, outputWidth, outputHeight;
  };
  struct Outputs {
    const vk::Image& display;
    const vk::Image& resolvedHdr;
    const vk::Image& linearDepth;
  };
  void record(VkCommandBuffer cmd, const Inputs& inputs, const Outputs& outputs);

 private:
  vk::Context& context_;
  vk::PipelineLayout layout_;
  std::unique_ptr<TilePipelines> pipelines_;
  vk::Unique<VkSampler> nearest_;
};

}  // namespace s3d::renderer::detail
