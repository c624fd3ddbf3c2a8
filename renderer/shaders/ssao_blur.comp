#version 450
// The half-resolution ambient occlusion's depth-aware blur: a 5x5 window whose edge taps weigh half, so every
// one of the 4x4 kernel turns weighs the same (the pattern averages out exactly on a plane), each tap also
// weighted by how near its depth is to the centre's (no occlusion bleeds across a depth edge).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D rawOcclusion;  // occlusion, linear depth
layout(binding = 2, rg16f) uniform writeonly image2D blurredOcclusion;
#define S3D_TILES_BINDING 3
#include "tiles.glsl"

void main() {
  ivec2 texel = ambientTile() * S3D_COMPUTE_GROUP_SIZE + ivec2(gl_LocalInvocationID.xy);
  ivec2 size = ivec2(frame.ambientOcclusion.yz);
  if (any(greaterThanEqual(texel, size))) return;
  countShaded(S3D_COUNT_SSAO_BLUR, 1u);
  vec2 centre = texelFetch(rawOcclusion, texel, 0).rg;
  if (isinf(centre.y)) {
    imageStore(blurredOcclusion, texel, vec4(centre, 0.0, 0.0));
    return;
  }
  float sum = 0.0, weightSum = 0.0;
  for (int y = -2; y <= 2; ++y)
    for (int x = -2; x <= 2; ++x) {
      vec2 tap = texelFetch(rawOcclusion, clamp(texel + ivec2(x, y), ivec2(0), size - 1), 0).rg;
      float window = (abs(x) == 2 ? 0.5 : 1.0) * (abs(y) == 2 ? 0.5 : 1.0);
      float weight = window * ambientDepthWeight(tap.y, centre.y);
      sum += weight * tap.x;
      weightSum += weight;
    }
  imageStore(blurredOcclusion, texel, vec4(sum / weightSum, centre.y, 0.0, 0.0));  // the centre weighs 1
}
