#version 450
// Hybrid, pass 3: both eyes' masks (1 = render this pixel from the eye camera) from the cells' bins and the
// thresholds: every cell at or above the threshold bin, and the split bin's cells up to the split count in raster
// order, each writing its pixels inside the crop (hybridMaskReference in hybrid.h). One workgroup per row of cells;
// each invocation owns a run of its cells, counts the run's split-bin cells, and ranks them on top of the runs
// before it and the rows above (the threshold pass's offsets): one barrier per row, or a parallel scan of the runs
// for a large group (the row group is a specialization constant, hybrid_shared.h).
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(constant_id = 0) const int kGroup = S3D_HYBRID_ROW_GROUP;  // invocations per row
layout(local_size_x_id = 0) in;

layout(binding = 0, r32ui) uniform readonly uimage2D leftBins;       // per cell
layout(binding = 1, r32ui) uniform readonly uimage2D rightBins;
layout(binding = 2, r32ui) uniform readonly uimage2D thresholds;    // S3D_HYBRID_THRESHOLD_FIELDS x 2
layout(binding = 3, r32ui) uniform readonly uimage2D splitOffsets;  // the grid's height x 2
layout(binding = 4, r32ui) uniform writeonly uimage2D leftMask;
layout(binding = 5, r32ui) uniform writeonly uimage2D rightMask;

layout(push_constant) uniform Push { HybridConstants c; };  // the image's (its cell gives the grid)

shared uvec2 runSplitPixels[kGroup];  // each run's split-bin cells, left and right

bool classified(int x) { return x >= hybridGridCropBegin(c.cropBegin, c.cell) && x < hybridGridCropEnd(c.cropEnd, c.cell); }

// Cell (x, y)'s pixels inside the crop.
void storeCell(int x, int y, bool left, bool right) {
  ivec2 first = ivec2(max(x * c.cell, c.cropBegin), y * c.cell);
  ivec2 end = ivec2(min(x * c.cell + c.cell, c.cropEnd), min(y * c.cell + c.cell, c.height));
  for (int py = first.y; py < end.y; ++py)
    for (int px = first.x; px < end.x; ++px) {
      imageStore(leftMask, ivec2(px, py), uvec4(left ? 1u : 0u));
      imageStore(rightMask, ivec2(px, py), uvec4(right ? 1u : 0u));
    }
}

void main() {
  int local = int(gl_LocalInvocationIndex);
  int y = int(gl_WorkGroupID.x);
  // The cropped columns stay unmasked: written here, since a cell across the crop's edge writes only its inside.
  for (int x = local; x < c.width; x += kGroup)
    if (x < c.cropBegin || x >= c.cropEnd)
      for (int py = y * c.cell; py < min(y * c.cell + c.cell, c.height); ++py) {
        imageStore(leftMask, ivec2(x, py), uvec4(0u));
        imageStore(rightMask, ivec2(x, py), uvec4(0u));
      }
  uvec2 threshold = uvec2(imageLoad(thresholds, ivec2(0, 0)).r, imageLoad(thresholds, ivec2(0, 1)).r);
  uvec2 splitBin = uvec2(imageLoad(thresholds, ivec2(2, 0)).r, imageLoad(thresholds, ivec2(2, 1)).r);
  uvec2 split = uvec2(imageLoad(thresholds, ivec2(3, 0)).r, imageLoad(thresholds, ivec2(3, 1)).r);
  int gridWidth = hybridGridSize(c.width, c.cell);
  int runLength = (gridWidth + kGroup - 1) / kGroup;
  int runBegin = min(local * runLength, gridWidth), runStop = min(runBegin + runLength, gridWidth);
  // The split-bin pixels before this run: the rows above, then this row's runs before it.
  uvec2 before = uvec2(0u);
  if (split.x > 0u || split.y > 0u) {  // uniform
    uvec2 own = uvec2(0u);
    for (int x = runBegin; x < runStop; ++x)
      if (classified(x)) {
        own.x += split.x > 0u && imageLoad(leftBins, ivec2(x, y)).r == splitBin.x ? 1u : 0u;
        own.y += split.y > 0u && imageLoad(rightBins, ivec2(x, y)).r == splitBin.y ? 1u : 0u;
      }
    runSplitPixels[local] = own;
    barrier();
    if (split.x > 0u) before.x = imageLoad(splitOffsets, ivec2(y, 0)).r;
    if (split.y > 0u) before.y = imageLoad(splitOffsets, ivec2(y, 1)).r;
    if (kGroup <= 32) {
      for (int r = 0; r < local; ++r) before += runSplitPixels[r];
    } else {  // inclusive prefix sums over the runs (Hillis-Steele), less this run's own
      for (int step = 1; step < kGroup; step <<= 1) {
        uvec2 add = local >= step ? runSplitPixels[local - step] : uvec2(0u);
        barrier();
        runSplitPixels[local] += add;
        barrier();
      }
      before += runSplitPixels[local] - own;
    }
  }
  for (int x = runBegin; x < runStop; ++x) {
    bool inside = classified(x);
    uvec2 bins = inside ? uvec2(imageLoad(leftBins, ivec2(x, y)).r, imageLoad(rightBins, ivec2(x, y)).r) : uvec2(0u);
    bool left = inside && bins.x >= threshold.x, right = inside && bins.y >= threshold.y;
    if (inside && bins.x == splitBin.x) left = before.x++ < split.x;  // (the split bin lies below the threshold)
    if (inside && bins.y == splitBin.y) right = before.y++ < split.y;
    storeCell(x, y, left, right);
  }
}
