#version 450
// Forward method, key-image kernel, splat: each center pixel writes its key into every eye pixel it
// covers, nearest wins (a global atomic minimum).
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"
#include "stereo_forward_splat.glsl"

layout(local_size_x = S3D_FORWARD_GROUP_SIZE, local_size_y = S3D_FORWARD_GROUP_SIZE) in;

float depthAt(int x, int y) { return imageLoad(linearDepth, ivec2(x, y)).r; }

void splatKey(bool leftEyeKeys, int column, int y, uint key) {
  if (leftEyeKeys) imageAtomicMin(leftKeys, ivec2(column, y), key);
  else imageAtomicMin(rightKeys, ivec2(column, y), key);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  splatPixel(pixel);
}
