#version 450
// Host hybrid: both eyes' masks as the depth the host's raster tests against, into one buffer (left eye, then
// right), which s3d copies into the host's depth images (depth images are not storage images).
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/host_hybrid_shared.h"

layout(local_size_x = S3D_HOST_HYBRID_GROUP_SIZE, local_size_y = S3D_HOST_HYBRID_GROUP_SIZE) in;

layout(binding = 0, r32ui) uniform readonly uimage2D leftMask;
layout(binding = 1, r32ui) uniform readonly uimage2D rightMask;
layout(binding = 2, std430) writeonly buffer Depths { float depths[]; };

layout(push_constant) uniform Push { HostHybridDepthConstants c; };

float depthOf(uint mask) { return mask != 0u ? c.maskedDepth : c.unmaskedDepth; }

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  int index = pixel.y * c.width + pixel.x;
  depths[index] = depthOf(imageLoad(leftMask, pixel).r);
  depths[c.width * c.height + index] = depthOf(imageLoad(rightMask, pixel).r);
}
