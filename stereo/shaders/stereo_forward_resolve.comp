#version 450
// Forward method, key-image kernel, last dispatch: each eye pixel shows its winning source at the sub-pixel
// position, or fills a disocclusion from the background side. It also empties the other pair of z-buffers for
// the next record's splat (ForwardStereoPass alternates two pairs), so no frame needs a clear dispatch.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"
#include "stereo_forward_resolve.glsl"

layout(binding = 6, r32ui) uniform writeonly uimage2D nextLeftKeys;
layout(binding = 7, r32ui) uniform writeonly uimage2D nextRightKeys;

layout(local_size_x = S3D_FORWARD_GROUP_SIZE, local_size_y = S3D_FORWARD_GROUP_SIZE) in;

float depthAt(int x, int y) { return imageLoad(linearDepth, ivec2(x, y)).r; }

uint keyAt(bool leftEyeKeys, int x, int y) {
  return leftEyeKeys ? imageLoad(leftKeys, ivec2(x, y)).r : imageLoad(rightKeys, ivec2(x, y)).r;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  imageStore(nextLeftKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
  imageStore(nextRightKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
  resolvePixel(pixel);
}
