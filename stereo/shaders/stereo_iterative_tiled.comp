#version 450
// stereo_iterative.comp on row tiles (stereo_row_tile.glsl): the same solver, every depth and color fetch
// from shared memory. Every fetch stays within maxParallaxPx of the pixel, so the margin covers them all.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/iterative_shared.h"

layout(binding = 0, rgba8) uniform readonly image2D centerColor;
layout(binding = 1, r32f) uniform readonly image2D linearDepth;
layout(binding = 2, rgba8) uniform writeonly image2D leftEye;
layout(binding = 3, rgba8) uniform writeonly image2D rightEye;

layout(push_constant) uniform Push { IterativeConstants c; };

#include "stereo_row_tile.glsl"

float depthAtTexel(float position, int y) {
  return tileDepthAt(iterativeDepthTexel(c, position));
}

// The eye's color at the target pixel; direction +1 is the left eye, -1 the right (same order as the C++).
vec4 solveEye(ivec2 pixel, float direction, bool depthIsFlat) {
  float target = float(pixel.x);
  if (depthIsFlat) {
    // Flat depth d over the tile and its margin: every tap and iterate reads d and maps to the same
    // t + P(d); the near start lands on it with residual 0, so the solver converges there (not filled).
    return tileSampleRow(pixel.y, iterativeNextPosition(c, target, direction, tileDepth[0]), c.width);
  }
  IterativeSearch search = iterativeBegin(c, target, direction);
  float minDepth = S3D_INFINITY;
  for (int i = 0; i < c.startTapCount; ++i) {
    float tap = target + direction * float(c.startTapOffsetPx[i]);
    float depth = depthAtTexel(tap, pixel.y);
    search = iterativeConsiderSolution(search, c, target, direction, tap, depth);
    minDepth = iterativeNearerDepth(minDepth, depth);
  }
  float starts[2] = float[2](iterativeFarStart(c, target, direction), iterativeNextPosition(c, target, direction, minDepth));
  for (int s = 0; s < 2; ++s) {
    float position = starts[s];
    for (int k = 0; k < c.iterations; ++k) {
      float depth = depthAtTexel(position, pixel.y);
      search = iterativeConsider(search, c, target, direction, position, depth);
      position = iterativeNextPosition(c, target, direction, depth);
    }
  }
  vec4 color = tileSampleRow(pixel.y, iterativeSourcePosition(search), c.width);
  // The fill flag replaces the alpha (the weapon mask) only when asked for: 0 for a disocclusion filled from the
  // background, 1 elsewhere.
  if (c.markFilled != 0) color.a = search.converged ? 1.0 : 0.0;
  return color;
}

void main() {
  int tileX = int(gl_WorkGroupID.x) * S3D_STEREO_ROW_TILE;
  ivec2 pixel = ivec2(tileX + int(gl_LocalInvocationID.x), int(gl_WorkGroupID.y));
  int interiorBegin = max(tileX, c.cropBegin);
  int interiorEnd = min(min(tileX + S3D_STEREO_ROW_TILE, c.cropEnd), c.width);
  bool depthIsFlat = false;
  if (interiorBegin < interiorEnd) {  // uniform over the group: a tile inside the crop loads nothing
    int largestTap = 0;
    for (int i = 0; i < c.startTapCount; ++i) largestTap = max(largestTap, c.startTapOffsetPx[i]);
    int margin = rowTileMarginPx(c.maxParallaxPx, largestTap);
    depthIsFlat = loadRowTile(interiorBegin, interiorEnd, pixel.y, margin, c.width, c.zeroParallaxDistance) &&
           margin <= S3D_STEREO_ROW_TILE_MARGIN && c.startTapCount > 0;
  }
  if (pixel.x >= c.width) return;
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges, as in the seed
    imageStore(leftEye, pixel, vec4(0, 0, 0, 1));
    imageStore(rightEye, pixel, vec4(0, 0, 0, 1));
    return;
  }
  imageStore(leftEye, pixel, solveEye(pixel, 1.0, depthIsFlat));
  imageStore(rightEye, pixel, solveEye(pixel, -1.0, depthIsFlat));
}
