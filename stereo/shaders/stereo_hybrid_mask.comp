#version 450
// Hybrid, pass 3: both eyes' masks (1 = render this pixel from the eye camera) from the cells' bins and the
// thresholds, one invocation per cell (a run of cells on a CPU device): a cell is masked at or above the threshold
// bin, or in the split bin up to the split's last cell in raster order (found by the threshold pass); it writes its
// pixels, those outside the crop never masked (hybridMaskReference in hybrid.h). Per cell rather than per pixel, so
// a cell's pixels share its loads (measured faster: docs/RESULTS.md "The mask pass per cell").
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

// Cells per invocation along a row: one on a GPU; a run on a CPU device, so the thresholds' loads are shared.
layout(constant_id = 0) const int kCellsPerInvocation = 1;
layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, r32ui) uniform readonly uimage2D leftBins;    // per cell
layout(binding = 1, r32ui) uniform readonly uimage2D rightBins;
layout(binding = 2, r32ui) uniform readonly uimage2D thresholds;  // S3D_HYBRID_THRESHOLD_FIELDS x 2
layout(binding = 3, r32ui) uniform writeonly uimage2D leftMask;
layout(binding = 4, r32ui) uniform writeonly uimage2D rightMask;

layout(push_constant) uniform Push { HybridConstants c; };  // the image's (its cell gives the grid)

// An eye's threshold bin and split bin.
uvec2 eyeThreshold(int eye) {
  return uvec2(imageLoad(thresholds, ivec2(0, eye)).r, imageLoad(thresholds, ivec2(2, eye)).r);
}

// Whether cell `cell` of bin `bin` is masked for eye `eye` (its threshold and split bin given). The split's last
// cell is loaded only for a cell of the split bin.
bool masked(ivec2 cell, uint bin, int eye, uvec2 thresholdAndSplitBin) {
  if (bin >= thresholdAndSplitBin.x) return true;
  if (bin != thresholdAndSplitBin.y) return false;  // (the split bin lies below the threshold; none: S3D_HYBRID_NO_PIXEL)
  ivec2 last = ivec2(imageLoad(thresholds, ivec2(5, eye)).r, imageLoad(thresholds, ivec2(4, eye)).r);
  return cell.y < last.y || (cell.y == last.y && cell.x <= last.x);
}

// A cell across the crop's edge is classified; one wholly outside is not (its bin is 0 and never read).
bool classified(int cellX) {
  return cellX >= hybridGridCropBegin(c.cropBegin, c.cell) && cellX < hybridGridCropEnd(c.cropEnd, c.cell);
}

// The cell's pixels in both masks, those outside the crop unmasked.
void writeCell(ivec2 cell, bool left, bool right) {
  ivec2 first = cell * c.cell, end = min(first + c.cell, ivec2(c.width, c.height));
  for (int y = first.y; y < end.y; ++y)
    for (int x = first.x; x < end.x; ++x) {
      bool inside = x >= c.cropBegin && x < c.cropEnd;
      imageStore(leftMask, ivec2(x, y), uvec4(inside && left ? 1u : 0u));
      imageStore(rightMask, ivec2(x, y), uvec4(inside && right ? 1u : 0u));
    }
}

void main() {
  ivec2 grid = ivec2(hybridGridSize(c.width, c.cell), hybridGridSize(c.height, c.cell));
  if (kCellsPerInvocation == 1) {  // a GPU: one cell, each threshold loaded where it is needed
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (cell.x >= grid.x || cell.y >= grid.y) return;
    bool inside = classified(cell.x);
    bool left = inside && masked(cell, imageLoad(leftBins, cell).r, 0, eyeThreshold(0));
    bool right = inside && masked(cell, imageLoad(rightBins, cell).r, 1, eyeThreshold(1));
    writeCell(cell, left, right);
    return;
  }
  // A CPU device: a run of cells along the row, the thresholds loaded once (uniform, but loaded per SIMD lane).
  ivec2 first = ivec2(gl_GlobalInvocationID.x * kCellsPerInvocation, gl_GlobalInvocationID.y);
  if (first.x >= grid.x || first.y >= grid.y) return;
  uvec2 leftThreshold = eyeThreshold(0), rightThreshold = eyeThreshold(1);
  for (int x = first.x; x < min(first.x + kCellsPerInvocation, grid.x); ++x) {
    ivec2 cell = ivec2(x, first.y);
    bool inside = classified(x);
    writeCell(cell, inside && masked(cell, imageLoad(leftBins, cell).r, 0, leftThreshold),
              inside && masked(cell, imageLoad(rightBins, cell).r, 1, rightThreshold));
  }
}
