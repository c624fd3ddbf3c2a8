#version 450
// Hybrid, pass 4 (per eye): masked eye pixels take the color the real eye camera rendered; all others keep the
// displaced color.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, rgba8) uniform image2D eye;
layout(binding = 1, rgba8) uniform readonly image2D renderedEye;
layout(binding = 2, r32ui) uniform readonly uimage2D mask;

layout(push_constant) uniform Push { HybridConstants c; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  if (imageLoad(mask, pixel).r != 0u) imageStore(eye, pixel, imageLoad(renderedEye, pixel));
}
