#version 450
// The previous-frame fill (previous_fill_shared.h), one eye per dispatch: the forward method's holes take the
// previous frame's eye reprojected with its depth; every pixel's colour and depth become the next frame's history.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/previous_fill_shared.h"

layout(local_size_x = S3D_PREVIOUS_FILL_GROUP_SIZE, local_size_y = S3D_PREVIOUS_FILL_GROUP_SIZE) in;

layout(binding = 0, rgba8) uniform image2D eye;  // the forward method's eye, filled in place
layout(binding = 1, r32ui) uniform readonly uimage2D keys;  // its z-buffer
layout(binding = 2, rgba8) uniform readonly image2D previousEye;
layout(binding = 3, r32f) uniform readonly image2D previousDepth;
layout(binding = 4, rgba8) uniform writeonly image2D historyEye;
layout(binding = 5, r32f) uniform writeonly image2D historyDepth;

layout(push_constant) uniform Push { PreviousFillConstants c; };

// The hole's (background, occluder) depths from its nearest covered neighbours in the row (previousFillEdges).
vec2 holeEdges(ivec2 pixel) {
  uint found[2] = uint[2](S3D_FORWARD_EMPTY, S3D_FORWARD_EMPTY);
  for (int s = 0; s < 2; ++s) {
    for (int i = 1; i <= c.edgeSearchPx; ++i) {
      int column = pixel.x + (s == 0 ? -i : i);
      if (column < 0 || column >= c.width) break;
      uint key = imageLoad(keys, ivec2(column, pixel.y)).r;
      if (key == S3D_FORWARD_EMPTY) continue;
      found[s] = key;
      break;
    }
  }
  return previousFillEdges(found[0], found[1]);
}

// The previous eye around `position` over the texels showing the surface of inverse depth `expected`.
vec4 previousSample(vec2 position, float expected, out float weightSum) {
  ivec2 topLeft = bilinearTopLeft(position);
  vec4 weights = bilinearWeights(position);
  vec4 sum = vec4(0.0);
  weightSum = 0.0;
  for (int tap = 0; tap < 4; ++tap) {
    ivec2 t = topLeft + ivec2(tap & 1, tap >> 1);
    float w = weights[tap];
    if (!(w >= S3D_REPROJECTION_MIN_WEIGHT) || !previousFillInsideEye(c, t)) continue;
    if (!sameSurface(expected, inverseDepthOf(imageLoad(previousDepth, t).r))) continue;
    vec4 texel = imageLoad(previousEye, t);
    if (!(texel.a >= S3D_PREVIOUS_FILL_WORLD_ALPHA)) continue;
    sum += w * texel;
    weightSum += w;
  }
  return sum;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {
    imageStore(historyEye, pixel, vec4(0.0, 0.0, 0.0, 1.0));
    imageStore(historyDepth, pixel, vec4(0.0));
    return;
  }
  uint key = imageLoad(keys, pixel).r;
  vec4 color = imageLoad(eye, pixel);
  if (key != S3D_FORWARD_EMPTY) {
    imageStore(historyEye, pixel, color);
    imageStore(historyDepth, pixel, vec4(forwardKeyLinearDepth(key)));
    return;
  }
  vec2 edges = holeEdges(pixel);
  float background = edges.x;
  float depth = background;
  if (c.hasHistory != 0) {
    float q = inverseDepthOf(background);
    vec2 centre = vec2(pixel) + 0.5;
    for (int k = 0; k < S3D_PREVIOUS_FILL_ITERATIONS && q >= 0.0; ++k) {
      vec3 was = reprojectToPrevious(c.motion, centre, q, c.width, c.height);
      if (was.z < 0.0) break;
      float weightSum;
      vec4 sum = previousSample(was.xy, was.z, weightSum);
      if (weightSum > 0.0 && behindOccluder(q, edges.y)) {
        color = sum / weightSum;
        depth = q > 0.0 ? 1.0 / q : S3D_INFINITY;
        imageStore(eye, pixel, color);
        break;
      }
      ivec2 t = ivec2(int(floor(was.x)), int(floor(was.y)));
      if (!previousFillInsideEye(c, t)) break;
      float previousInverse = inverseDepthOf(imageLoad(previousDepth, t).r);
      if (previousInverse < 0.0 || !(imageLoad(previousEye, t).a >= S3D_PREVIOUS_FILL_WORLD_ALPHA)) break;
      q = reprojectToCurrent(c.motion, vec2(t) + 0.5, previousInverse, c.width, c.height).z;
    }
  }
  imageStore(historyEye, pixel, color);
  imageStore(historyDepth, pixel, vec4(depth));
}
