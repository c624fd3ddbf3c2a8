#version 450
// The iterative gather method (iterative_shared.h): one invocation solves the pixel of both eyes.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/iterative_shared.h"

layout(local_size_x = S3D_ITERATIVE_GROUP_SIZE, local_size_y = S3D_ITERATIVE_GROUP_SIZE) in;

layout(binding = 0, rgba8) uniform readonly image2D centerColor;
layout(binding = 1, r32f) uniform readonly image2D linearDepth;
layout(binding = 2, rgba8) uniform writeonly image2D leftEye;
layout(binding = 3, rgba8) uniform writeonly image2D rightEye;

layout(push_constant) uniform Push { IterativeConstants c; };

// NaN, zero and negative depth read as the zero-parallax plane, as in the seed (sanitizedDepth).
float depthAtTexel(float position, int y) {
  return sanitizedDepth(imageLoad(linearDepth, ivec2(iterativeDepthTexel(c, position), y)).r, c.zeroParallaxDistance);
}

// Horizontal linear filter at texel coordinate u (texel centers at integers), clamped to the edge; the
// seed's sampleRow, so maxSeparation = 0 returns the center view bit for bit.
vec4 sampleRow(int y, float u) {
  float base = floor(u);
  float fraction = u - base;
  vec4 a = imageLoad(centerColor, ivec2(clamp(int(base), 0, c.width - 1), y));
  vec4 b = imageLoad(centerColor, ivec2(clamp(int(base) + 1, 0, c.width - 1), y));
  return a * (1.0 - fraction) + b * fraction;
}

// The eye's color at the target pixel; direction +1 is the left eye, -1 the right (same order as the C++).
vec4 solveEye(ivec2 pixel, float direction) {
  float target = float(pixel.x);
  IterativeSearch search = iterativeBegin(c, target, direction);
  // Near start: the nearest surface over the separation range; each tap is also a candidate solution.
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
  vec4 color = sampleRow(pixel.y, iterativeSourcePosition(search));
  // The fill flag replaces the alpha (the weapon mask) only when asked for: 0 for a disocclusion filled from the
  // background, 1 elsewhere.
  if (c.markFilled != 0) color.a = search.converged ? 1.0 : 0.0;
  return color;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges, as in the seed
    imageStore(leftEye, pixel, vec4(0, 0, 0, 1));
    imageStore(rightEye, pixel, vec4(0, 0, 0, 1));
    return;
  }
  imageStore(leftEye, pixel, solveEye(pixel, 1.0));
  imageStore(rightEye, pixel, solveEye(pixel, -1.0));
}
