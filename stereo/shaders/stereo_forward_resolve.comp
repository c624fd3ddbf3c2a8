#version 450
// Forward method, key-image kernel, dispatch 3 of 3: each eye pixel shows its winning source at the sub-pixel
// position, or fills a disocclusion from the background side.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"
#include "stereo_forward_resolve.glsl"

layout(local_size_x = S3D_FORWARD_GROUP_SIZE, local_size_y = S3D_FORWARD_GROUP_SIZE) in;

float depthAt(int x, int y) { return imageLoad(linearDepth, ivec2(x, y)).r; }

uint keyAt(bool leftEyeKeys, int x, int y) {
  return leftEyeKeys ? imageLoad(leftKeys, ivec2(x, y)).r : imageLoad(rightKeys, ivec2(x, y)).r;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  resolvePixel(pixel);
}
