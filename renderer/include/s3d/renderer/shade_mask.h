#pragma once
// The pixels a masked render shades: DeferredRenderer::render and the ray-cast visibility pass take it.
#include <cstdint>

#include "s3d/vk/resources.h"

namespace s3d::renderer {

// Which pixels a render shades (the hybrid stereo method renders only the eye pixels displacement gets wrong).
//
// `image`: VK_FORMAT_R32_UINT, exactly the renderer's output size (width() x height()), created with
// VK_IMAGE_USAGE_STORAGE_BIT, in VK_IMAGE_LAYOUT_GENERAL; its writes submitted before render() (render records a
// barrier from any earlier write on its queue, then reads it as a storage image in compute and fragment
// shaders). A pixel is shaded where its value >= threshold, so a classification's bin image can be passed with
// its threshold bin as is (1: every nonzero pixel). With supersampling the value covers all samples of its pixel.
//
// What a masked render does: the G-buffer still rasterizes all geometry, but every pixel outside the mask has
// the nearest depth before it draws, so its fragments fail the depth test before shading; ambient occlusion
// (with a depth-only pass of its own, so its samples see real depth outside the mask) runs on the tiles of the
// mask and their neighbours; lighting and the resolve run on the mask's tiles only (found on the GPU) and skip
// unmasked pixels inside them; shadow maps render as for a full frame (or come from a shadow source: render's
// third argument).
//
// Outputs outside the mask are undefined after a masked render: displayColor, linearDepth, hdrColor and the
// read*() masks there may hold anything (the previous frame, zeros, the depth fill). Inside it they equal the
// unmasked render's (tests: within one 8-bit level and 1e-5 relative depth).
//
// The first masked render creates the masked pipeline variants and, with ambient occlusion, a render-size depth
// image; later renders allocate nothing. render() submits on the context's queue and waits, so the mask may be
// rewritten as soon as it returns.
struct ShadeMask {
  const vk::Image* image = nullptr;
  std::uint32_t threshold = 1;
  // How the shaded pixels' surfaces are found. Raster: the G-buffer pass above. RayCast: the ray-cast visibility
  // pass (raycast_visibility.h) casts the mask's pixels through the BVH given to setSurfaceBvh and the G-buffer
  // resolve, lighting and resolve shade them: no depth clear and no raster pass (compute runs on all of a GPU,
  // the raster side on a small part of it). With ambient occlusion the occlusion's region (the masked tiles and
  // their 8 neighbours) gets surfaces: its masked pixels cast, its other pixels cast too, or given uncastDepth's
  // depth where there is one; its samples beyond that region find no surface: near the region's border an
  // occluder further away than a tile is missed (docs/RESULTS.md, "The budget by ray casting, current build").
  // A null image with RayCast casts and shades every pixel.
  enum class Surfaces { Raster, RayCast };
  Surfaces surfaces = Surfaces::Raster;
  // RayCast with a mask and ambient occlusion only (ignored without ambient occlusion): the device depth of the
  // unmasked pixels, which are then not cast (a hybrid's eye: the center's depth where its base displacement
  // samples, stereo::HybridBaseDepthPass). VK_FORMAT_R32_SFLOAT, the mask's size and layout, written by compute
  // before render() (the ray-cast pass orders earlier compute writes before its reads).
  const vk::Image* uncastDepth = nullptr;
  // The image the shaded pixels' display colour is written into instead of displayColor() (every pixel without a
  // mask), its other pixels left as they are (a hybrid's displaced eye: no composite pass after the render);
  // displayColor() is then undefined. VK_FORMAT_R8G8B8A8_UNORM, the output size, storage usage, in
  // VK_IMAGE_LAYOUT_GENERAL, written or read by compute before render(), which orders its writes after that and
  // leaves it in the same state.
  const vk::Image* displayTarget = nullptr;
};

}  // namespace s3d::renderer
