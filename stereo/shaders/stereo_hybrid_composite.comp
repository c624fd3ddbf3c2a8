#version 450
// Hybrid, pass 2 (per eye): eye pixels whose score bin reached the budget's threshold take the color the real
// eye camera rendered; all others keep the displaced color.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, rgba8) uniform image2D eye;
layout(binding = 1, rgba8) uniform readonly image2D renderedEye;
layout(binding = 2, r32ui) uniform readonly uimage2D bins;

layout(push_constant) uniform Push { HybridConstants c; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd || pixel.y >= c.height) return;
  if (int(imageLoad(bins, pixel).r) >= c.thresholdBin) imageStore(eye, pixel, imageLoad(renderedEye, pixel));
}
