#version 450
// Hybrid, pass 3: both eyes' masks (1 = render this pixel from the eye camera) from the bins and the thresholds.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, r32ui) uniform readonly uimage2D leftBins;
layout(binding = 1, r32ui) uniform readonly uimage2D rightBins;
layout(binding = 2, r32ui) uniform readonly uimage2D thresholds;
layout(binding = 3, r32ui) uniform writeonly uimage2D leftMask;
layout(binding = 4, r32ui) uniform writeonly uimage2D rightMask;

layout(push_constant) uniform Push { HybridConstants c; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  bool classified = pixel.x >= c.cropBegin && pixel.x < c.cropEnd;
  uint leftThreshold = imageLoad(thresholds, ivec2(0, 0)).r;
  uint rightThreshold = imageLoad(thresholds, ivec2(0, 1)).r;
  imageStore(leftMask, pixel, uvec4(classified && imageLoad(leftBins, pixel).r >= leftThreshold ? 1u : 0u));
  imageStore(rightMask, pixel, uvec4(classified && imageLoad(rightBins, pixel).r >= rightThreshold ? 1u : 0u));
}
