#version 450
// Hybrid, pass 2: each eye's threshold from its histogram (workgroup x = eye), as hybridThreshold in hybrid.h: the
// lowest bin whose pixels and all above it stay within the budget's cap, then the share of the bin below that the
// cap leaves (its ties split in raster order). The split ends at one cell: its row from the rows' histograms, its
// column from a scan of that one row, so the mask pass decides each cell alone. Found on the GPU so a frame needs
// no read-back between the classification and the masked render.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_THRESHOLD_GROUP) in;

layout(binding = 0, r32ui) uniform readonly uimage2D histogram;      // S3D_HYBRID_BINS x 2
layout(binding = 1, r32ui) uniform readonly uimage2D rowHistograms;  // 2 S3D_HYBRID_BINS x height
layout(binding = 2, r32ui) uniform writeonly uimage2D thresholds;    // S3D_HYBRID_THRESHOLD_FIELDS x 2
layout(binding = 3, r32ui) uniform readonly uimage2D leftBins;       // per cell
layout(binding = 4, r32ui) uniform readonly uimage2D rightBins;

layout(push_constant) uniform Push { HybridConstants c; };  // the grid's

const uint kGroup = S3D_HYBRID_THRESHOLD_GROUP;
shared uint above[S3D_HYBRID_BINS];  // pixels in this bin and every bin above it; then per-invocation sums
shared uint lowestBin;
shared uint splitRow, splitRank;  // the row holding the split's last cell, and that cell's rank in the row (from 1)
shared uint splitColumn;

// Inclusive prefix sums of `above` over the group's invocations (Hillis-Steele); returns this invocation's sum
// of the invocations before it.
uint sumBefore(uint own) {
  uint local = gl_LocalInvocationID.x;
  above[local] = own;
  barrier();
  for (uint step = 1u; step < kGroup; step <<= 1) {
    uint add = local >= step ? above[local - step] : 0u;
    barrier();
    above[local] += add;
    barrier();
  }
  return above[local] - own;
}

// Whether cell (x, y) of the eye's bins is in `bin`.
bool isSplitCell(int eye, int x, int y, uint bin) {
  uint cellBin = eye == 0 ? imageLoad(leftBins, ivec2(x, y)).r : imageLoad(rightBins, ivec2(x, y)).r;
  return cellBin == bin;
}

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
  barrier();  // everyone has read `above`: it now holds the invocations' sums

  if (split > 0u) {  // uniform: the row where the split's count is reached, a block of rows per invocation
    uint rowsPer = (uint(c.height) + kGroup - 1u) / kGroup;
    uint firstRow = bin * rowsPer, endRow = min(firstRow + rowsPer, uint(c.height));
    uint own = 0u;
    for (uint row = firstRow; row < endRow; ++row)
      own += imageLoad(rowHistograms, ivec2(eye * S3D_HYBRID_BINS + int(splitBin), int(row))).r;
    uint before = sumBefore(own);
    for (uint row = firstRow; row < endRow; ++row) {
      uint count = imageLoad(rowHistograms, ivec2(eye * S3D_HYBRID_BINS + int(splitBin), int(row))).r;
      if (before < split && split <= before + count) {  // one row in all
        splitRow = row;
        splitRank = split - before;
      }
      before += count;
    }
    barrier();
    // That row's split-bin cells inside the crop, a run of columns per invocation: the one holding the rank-th.
    int y = int(splitRow);
    int columns = c.cropEnd - c.cropBegin, runLength = (columns + int(kGroup) - 1) / int(kGroup);
    int runBegin = c.cropBegin + min(int(bin) * runLength, columns), runEnd = min(runBegin + runLength, c.cropEnd);
    uint runCells = 0u;
    for (int x = runBegin; x < runEnd; ++x) runCells += isSplitCell(eye, x, y, splitBin) ? 1u : 0u;
    uint rank = sumBefore(runCells);
    if (rank < splitRank && splitRank <= rank + runCells)
      for (int x = runBegin; x < runEnd; ++x)
        if (isSplitCell(eye, x, y, splitBin) && ++rank == splitRank) splitColumn = uint(x);
    barrier();
  }
  if (bin == 0u) {
    imageStore(thresholds, ivec2(0, eye), uvec4(threshold));
    imageStore(thresholds, ivec2(1, eye), uvec4(wholeBins + split));
    imageStore(thresholds, ivec2(2, eye), uvec4(splitBin));
    imageStore(thresholds, ivec2(3, eye), uvec4(split));
    imageStore(thresholds, ivec2(4, eye), uvec4(split > 0u ? splitRow : 0u));
    imageStore(thresholds, ivec2(5, eye), uvec4(split > 0u ? splitColumn : 0u));
  }
}
