#version 450
// Hybrid, pass 2: each eye's threshold bin from its histogram (workgroup x = eye): the lowest bin whose pixels
// and all above it stay within the budget's cap (hybridThreshold in hybrid.h), found on the GPU so a frame
// needs no read-back between the classification and the masked render.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_THRESHOLD_GROUP) in;

layout(binding = 0, r32ui) uniform readonly uimage2D histogram;  // S3D_HYBRID_BINS x 2
layout(binding = 1, r32ui) uniform writeonly uimage2D thresholds;  // 2 x 2: (0, eye) bin, (1, eye) masked pixels

layout(push_constant) uniform Push { HybridConstants c; };

shared uint above[S3D_HYBRID_BINS];  // pixels in this bin and every bin above it
shared uint lowestBin;

void main() {
  int eye = int(gl_WorkGroupID.x);
  uint bin = gl_LocalInvocationID.x;
  above[bin] = imageLoad(histogram, ivec2(int(bin), eye)).r;
  if (bin == 0u) lowestBin = S3D_HYBRID_NO_PIXEL;
  barrier();
  // Suffix sums (Hillis-Steele): counts fit 32 bits (at most 2^26 pixels per image).
  for (uint step = 1u; step < S3D_HYBRID_BINS; step <<= 1) {
    uint add = bin + step < S3D_HYBRID_BINS ? above[bin + step] : 0u;
    barrier();
    above[bin] += add;
    barrier();
  }
  // The sums fall as the bin rises, so the bins within the cap are one run up to the top.
  if (above[bin] <= c.maskedPixelCap) atomicMin(lowestBin, bin);
  barrier();
  if (bin == 0u) {
    uint masked = lowestBin < S3D_HYBRID_BINS ? above[lowestBin] : 0u;
    imageStore(thresholds, ivec2(0, eye), uvec4(lowestBin));
    imageStore(thresholds, ivec2(1, eye), uvec4(masked));
  }
}
