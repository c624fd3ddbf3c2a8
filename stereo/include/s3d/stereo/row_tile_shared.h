// Row tiles of the stereo passes (docs/DESIGN.md, "Row tiles"), shared by the tiled shaders and the C++ that
// picks them: a workgroup synthesizes a run of S3D_STEREO_ROW_TILE pixels of one row and first copies the
// run plus a margin each side (depth and color) into shared memory with coalesced loads, so every tap,
// iterate and filter fetch after that reads shared memory instead of the images.
#ifndef S3D_STEREO_ROW_TILE_SHARED_H
#define S3D_STEREO_ROW_TILE_SHARED_H

#include "s3d/gpu/shared.h"

#ifdef __cplusplus
namespace s3d::gpu {
using glm::ceil;
}  // namespace s3d::gpu
#endif

S3D_GPU_BEGIN

#define S3D_STEREO_ROW_TILE 256        // pixels (and invocations) per workgroup, one row
#define S3D_STEREO_ROW_TILE_MARGIN 512  // largest margin the shared arrays hold each side (10 KiB in all)
#define S3D_STEREO_ROW_TILE_SPAN (S3D_STEREO_ROW_TILE + 2 * S3D_STEREO_ROW_TILE_MARGIN)

// Columns each side of a pixel whose depth or color its pass may read: the taps (largestTapPx), and the sky's
// displacement maxParallaxPx rounded up, plus one for the nearest-texel rounding and one for the filter's
// second texel. Every depth fetch of every method lies within it; only the color fetch of a seed / search
// pixel whose nearest tap is in front of the screen can point further (its parallax is not bounded), and
// falls back to the image.
S3D_INLINE int rowTileMarginPx(float maxParallaxPx, int largestTapPx) {
  int sky = int(ceil(maxParallaxPx)) + 2;
  return sky > largestTapPx ? sky : largestTapPx;
}

S3D_GPU_END

#endif  // S3D_STEREO_ROW_TILE_SHARED_H
