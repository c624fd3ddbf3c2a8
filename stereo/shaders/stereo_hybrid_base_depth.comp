#version 450
// Hybrid with ray-cast eye surfaces: per eye pixel, the center's device depth at the texel the gather base filters
// it from (its source column, rounded to the nearest texel and clamped to the row), for both eyes. The eye render
// casts rays for its masked pixels only and gives the others of the ambient occlusion's region this depth, so the
// occlusion finds the displaced surfaces around them (the eye cameras share the center's near and far planes, so a
// surface's device depth is the same in an eye; the first-person layer keeps its own depth slice).
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;
// The gather base's tap array as compiled (detail/base_tap_pipelines.h): short for the seed and short searches
layout(constant_id = 0) const int kBaseTapCapacity = S3D_STEREO_MAX_TAPS;

layout(binding = 0, r32f) uniform readonly image2D linearDepth;
layout(binding = 1) uniform sampler2D deviceDepth;  // the center's (a depth attachment: sampled, not storage)
layout(binding = 2, r32f) uniform writeonly image2D leftDepth;
layout(binding = 3, r32f) uniform writeonly image2D rightDepth;

layout(push_constant) uniform Push { HybridConstants c; };

float depthAt(int x, int y) {
  return sanitizedDepth(imageLoad(linearDepth, ivec2(clamp(x, 0, c.width - 1), y)).r, c.zeroParallaxDistance);
}

#undef S3D_STEREO_TAP_CAPACITY
#define S3D_STEREO_TAP_CAPACITY kBaseTapCapacity
#define S3D_GATHER_TAP_COUNT c.baseTapCount
#define S3D_GATHER_TAP_OFFSET_PX c.baseTapOffsetPx
#include "stereo_gather_source.glsl"

// The center device depth at the texel nearest eye pixel (x, y)'s source column (ties to the right, as the
// classification's nearest landing).
float sourceDeviceDepth(int x, int y, int direction) {
  float column = gatherSourceColumn(x, direction, minDepthOverTaps(x, y, direction));
  return texelFetch(deviceDepth, ivec2(nearestSourceTexel(column), y), 0).r;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  imageStore(leftDepth, pixel, vec4(sourceDeviceDepth(pixel.x, pixel.y, +1)));
  imageStore(rightDepth, pixel, vec4(sourceDeviceDepth(pixel.x, pixel.y, -1)));
}
