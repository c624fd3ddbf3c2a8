#version 450
// Hybrid, pass 2: each eye's threshold from its histogram (workgroup x = eye), as hybridThreshold in hybrid.h: the
// lowest bin whose pixels and all above it stay within the budget's cap, then the share of the bin below that the
// cap leaves (its ties split in raster order), with the split bin's pixels in the rows above each row for the mask
// pass. Found on the GPU so a frame needs no read-back between the classification and the masked render.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_THRESHOLD_GROUP) in;

layout(binding = 0, r32ui) uniform readonly uimage2D histogram;      // S3D_HYBRID_BINS x 2
layout(binding = 1, r32ui) uniform readonly uimage2D rowHistograms;  // 2 S3D_HYBRID_BINS x height
// S3D_HYBRID_THRESHOLD_FIELDS x 2: (0, eye) the threshold bin, (1, eye) the masked pixels, (2, eye) the split bin,
// (3, eye) the split bin's masked pixels.
layout(binding = 2, r32ui) uniform writeonly uimage2D thresholds;
layout(binding = 3, r32ui) uniform writeonly uimage2D splitOffsets;  // height x 2: the split bin's pixels in the rows above

layout(push_constant) uniform Push { HybridConstants c; };

const uint kGroup = S3D_HYBRID_THRESHOLD_GROUP;
shared uint above[S3D_HYBRID_BINS];  // pixels in this bin and every bin above it; then per-invocation row sums
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
  // Below budget 1 (the cap takes fewer than every pixel: a lowest bin above 0) bin 0 and the bins below the floor
  // are never masked.
  uint lowest = uint(max(c.minimumBin, 1));
  uint threshold = lowestBin == 0u ? 0u : max(lowestBin, lowest);
  uint wholeBins = threshold < S3D_HYBRID_BINS ? above[threshold] : 0u;
  // The bin below the threshold holds more than the cap leaves (else it would be taken whole); a bin below the
  // lowest never splits.
  uint splitBin = threshold >= lowest + 1u ? threshold - 1u : S3D_HYBRID_NO_PIXEL;
  uint split = splitBin != S3D_HYBRID_NO_PIXEL ? c.maskedPixelCap - wholeBins : 0u;
  if (split == 0u) splitBin = S3D_HYBRID_NO_PIXEL;
  barrier();  // everyone has read `above`: it now holds row sums

  if (split > 0u) {  // uniform: the split bin's pixels before each row, a block of rows per invocation
    uint rowsPer = (uint(c.height) + kGroup - 1u) / kGroup;
    uint firstRow = bin * rowsPer, endRow = min(firstRow + rowsPer, uint(c.height));
    uint own = 0u;
    for (uint row = firstRow; row < endRow; ++row)
      own += imageLoad(rowHistograms, ivec2(eye * S3D_HYBRID_BINS + int(splitBin), int(row))).r;
    above[bin] = own;
    barrier();
    for (uint step = 1u; step < kGroup; step <<= 1) {  // inclusive prefix sums over the blocks
      uint add = bin >= step ? above[bin - step] : 0u;
      barrier();
      above[bin] += add;
      barrier();
    }
    uint before = above[bin] - own;
    for (uint row = firstRow; row < endRow; ++row) {
      imageStore(splitOffsets, ivec2(int(row), eye), uvec4(before));
      before += imageLoad(rowHistograms, ivec2(eye * S3D_HYBRID_BINS + int(splitBin), int(row))).r;
    }
  }
  if (bin == 0u) {
    imageStore(thresholds, ivec2(0, eye), uvec4(threshold));
    imageStore(thresholds, ivec2(1, eye), uvec4(wholeBins + split));
    imageStore(thresholds, ivec2(2, eye), uvec4(splitBin));
    imageStore(thresholds, ivec2(3, eye), uvec4(split));
  }
}
