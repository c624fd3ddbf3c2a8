// stereo_gather.glsl on row tiles (stereo_row_tile.glsl): the same taps, minimum and filter, read from shared
// memory. Included by stereo_seed_tiled.comp and stereo_search_tiled.comp, which set S3D_STEREO_TAP_CAPACITY.
#include "s3d/stereo/stereo_shared.h"

layout(binding = 0, rgba8) uniform readonly image2D centerColor;
layout(binding = 1, r32f) uniform readonly image2D linearDepth;
layout(binding = 2, rgba8) uniform writeonly image2D leftEye;
layout(binding = 3, rgba8) uniform writeonly image2D rightEye;

layout(push_constant) uniform Push { StereoConstants c; };

#include "stereo_row_tile.glsl"

// Listing 4.5: minimum depth over the separation range on one side of the pixel.
float minDepthOverTaps(int x, int y, int direction) {
  float minDepth = S3D_INFINITY;
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i)
    if (i < c.tapCount)
      minDepth = min(minDepth, tileDepthAt(clamp(x + direction * c.tapOffsetPx[i], 0, c.width - 1)));
  return minDepth;
}

int tileMargin() {
  int largestTap = 0;
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i)
    if (i < c.tapCount) largestTap = max(largestTap, c.tapOffsetPx[i]);
  return rowTileMarginPx(c.maxSeparation * float(c.width), largestTap);
}

void main() {
  int tileX = int(gl_WorkGroupID.x) * S3D_STEREO_ROW_TILE;
  ivec2 pixel = ivec2(tileX + int(gl_LocalInvocationID.x), int(gl_WorkGroupID.y));
  int interiorBegin = max(tileX, c.cropBegin);
  int interiorEnd = min(min(tileX + S3D_STEREO_ROW_TILE, c.cropEnd), c.width);
  bool depthIsFlat = false;
  if (interiorBegin < interiorEnd) {  // uniform over the group: a tile inside the crop loads nothing
    int margin = tileMargin();
    depthIsFlat = loadRowTile(interiorBegin, interiorEnd, pixel.y, margin, c.width, c.zeroParallaxDistance) &&
           margin <= S3D_STEREO_ROW_TILE_MARGIN && c.tapCount > 0;
  }
  if (pixel.x >= c.width) return;
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges
    imageStore(leftEye, pixel, vec4(0, 0, 0, 1));
    imageStore(rightEye, pixel, vec4(0, 0, 0, 1));
    return;
  }
  // Flat depth over the tile and its margin: every tap reads the same depth, so the minimum is that depth.
  float minDepthLeft = depthIsFlat ? tileDepth[0] : minDepthOverTaps(pixel.x, pixel.y, +1);
  float minDepthRight = depthIsFlat ? tileDepth[0] : minDepthOverTaps(pixel.x, pixel.y, -1);
  float parallaxLeft = parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, minDepthLeft);
  float parallaxRight = parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, minDepthRight);
  // The left eye adds the parallax, the right eye subtracts it.
  imageStore(leftEye, pixel, tileSampleRow(pixel.y, float(pixel.x) + parallaxLeft * float(c.width), c.width));
  imageStore(rightEye, pixel, tileSampleRow(pixel.y, float(pixel.x) - parallaxRight * float(c.width), c.width));
}
