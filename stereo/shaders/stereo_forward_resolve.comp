#version 450
// Forward method, key-image kernel, last dispatch, for devices without the subgroup operations of
// stereo_forward_resolve_rows.comp: each eye pixel shows its winning source at the sub-pixel position, or fills
// a disocclusion from the background side, searching its hole's edges alone.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"
#include "stereo_forward_resolve.glsl"
#include "stereo_forward_resolve_images.glsl"

layout(local_size_x = S3D_FORWARD_GROUP_SIZE, local_size_y = S3D_FORWARD_GROUP_SIZE) in;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  emptyNextKeys(pixel);
  resolvePixel(pixel);
}
