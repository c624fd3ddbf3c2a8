#version 450
// Forward method, key-image kernel: empty z-buffers for both eyes, only where the pair to splat into is not
// already empty (its first use; after that the previous record's resolve emptied it).
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"

layout(local_size_x = S3D_FORWARD_GROUP_SIZE, local_size_y = S3D_FORWARD_GROUP_SIZE) in;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  imageStore(leftKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
  imageStore(rightKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
}
