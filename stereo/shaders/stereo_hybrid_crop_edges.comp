#version 450
// Hybrid at budget 1 (per eye): the eye rendered whole straight into the eye image, whose cropped columns then
// turn black as the displacement leaves them (hybridMaskReference masks only the crop). One invocation per
// cropped pixel: the left strip's columns, then the right strip's.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, rgba8) uniform writeonly image2D eye;

layout(push_constant) uniform Push { HybridConstants c; };

void main() {
  ivec2 slot = ivec2(gl_GlobalInvocationID.xy);
  int x = slot.x < c.cropBegin ? slot.x : c.cropEnd + (slot.x - c.cropBegin);
  if (x >= c.width || slot.y >= c.height) return;
  imageStore(eye, ivec2(x, slot.y), vec4(0, 0, 0, 1));
}
