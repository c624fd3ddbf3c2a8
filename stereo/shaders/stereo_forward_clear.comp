#version 450
// Forward method, dispatch 1 of 3: empty z-buffers for both eyes.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  imageStore(leftKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
  imageStore(rightKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
}
