#version 450
// Hybrid, before the classification on cells of more than one pixel: each cell's nearest sanitized linear depth
// over its pixels (hybridGridDepthReference in hybrid.h), the image the classification walks. Its first workgroup
// also zeroes the histogram the classification accumulates into: no transfer clear between the compute passes.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, r32f) uniform readonly image2D linearDepth;
layout(binding = 1, r32f) uniform writeonly image2D gridDepth;
layout(binding = 2, r32ui) uniform writeonly uimage2D histogram;  // S3D_HYBRID_BINS x 2

layout(push_constant) uniform Push { HybridConstants c; };  // the image's

void main() {
  if (gl_WorkGroupID.xy == uvec2(0u))
    for (uint bin = gl_LocalInvocationIndex; bin < 2u * S3D_HYBRID_BINS; bin += gl_WorkGroupSize.x * gl_WorkGroupSize.y)
      imageStore(histogram, ivec2(bin % S3D_HYBRID_BINS, bin / S3D_HYBRID_BINS), uvec4(0u));
  ivec2 cellIndex = ivec2(gl_GlobalInvocationID.xy);
  if (cellIndex.x >= hybridGridSize(c.width, c.cell) || cellIndex.y >= hybridGridSize(c.height, c.cell)) return;
  ivec2 first = cellIndex * c.cell, end = min(first + c.cell, ivec2(c.width, c.height));
  float nearest = S3D_INFINITY;
  for (int y = first.y; y < end.y; ++y)
    for (int x = first.x; x < end.x; ++x)
      nearest = min(nearest, sanitizedDepth(imageLoad(linearDepth, ivec2(x, y)).r, c.zeroParallaxDistance));
  imageStore(gridDepth, cellIndex, vec4(nearest));
}
