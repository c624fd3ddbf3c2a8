#version 450
// Hybrid, pass 3: both eyes' masks (1 = render this pixel from the eye camera) from the cells' bins and the
// thresholds, one invocation per cell: a cell is masked at or above the threshold bin, or in the split bin up to the
// split's last cell in raster order (found by the threshold pass); it writes its pixels, those outside the crop
// never masked (hybridMaskReference in hybrid.h). Per cell rather than per pixel: a GPU's image loads, not its
// memory, bound this pass.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, r32ui) uniform readonly uimage2D leftBins;    // per cell
layout(binding = 1, r32ui) uniform readonly uimage2D rightBins;
layout(binding = 2, r32ui) uniform readonly uimage2D thresholds;  // S3D_HYBRID_THRESHOLD_FIELDS x 2
layout(binding = 3, r32ui) uniform writeonly uimage2D leftMask;
layout(binding = 4, r32ui) uniform writeonly uimage2D rightMask;

layout(push_constant) uniform Push { HybridConstants c; };  // the image's (its cell gives the grid)

// Whether cell `cell` of bin `bin` is masked by eye row `eye` of the thresholds.
bool masked(ivec2 cell, uint bin, int eye) {
  uint threshold = imageLoad(thresholds, ivec2(0, eye)).r, splitBin = imageLoad(thresholds, ivec2(2, eye)).r;
  if (bin >= threshold) return true;
  if (bin != splitBin) return false;  // (the split bin lies below the threshold; none: S3D_HYBRID_NO_PIXEL)
  ivec2 last = ivec2(imageLoad(thresholds, ivec2(5, eye)).r, imageLoad(thresholds, ivec2(4, eye)).r);
  return cell.y < last.y || (cell.y == last.y && cell.x <= last.x);
}

void main() {
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
  if (cell.x >= hybridGridSize(c.width, c.cell) || cell.y >= hybridGridSize(c.height, c.cell)) return;
  // A cell across the crop's edge is classified; one wholly outside is not (its bin is 0 and never read).
  bool classified = cell.x >= hybridGridCropBegin(c.cropBegin, c.cell) && cell.x < hybridGridCropEnd(c.cropEnd, c.cell);
  bool left = classified && masked(cell, imageLoad(leftBins, cell).r, 0);
  bool right = classified && masked(cell, imageLoad(rightBins, cell).r, 1);
  ivec2 first = cell * c.cell, end = min(first + c.cell, ivec2(c.width, c.height));
  for (int y = first.y; y < end.y; ++y)
    for (int x = first.x; x < end.x; ++x) {
      bool inside = x >= c.cropBegin && x < c.cropEnd;
      imageStore(leftMask, ivec2(x, y), uvec4(inside && left ? 1u : 0u));
      imageStore(rightMask, ivec2(x, y), uvec4(inside && right ? 1u : 0u));
    }
}
