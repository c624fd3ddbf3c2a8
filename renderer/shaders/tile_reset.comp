#version 450
// The tile buffer's reset before a frame's tile passes: the shaded-pixel counters and the indirect dispatch counts
// to zero (each dispatch's y and z to 1) and, in a masked render, the ambient-region flags mask_tiles.comp sets.
// In compute, not as transfer fills: a transfer between compute passes costs more than this dispatch (RESULTS.md).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_TILE_RESET_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
#define S3D_TILES_BINDING 1
#include "tiles.glsl"

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index == 0u) {
    tileHeader.lightingDispatch = uvec4(0u, 1u, 1u, 0u);
    tileHeader.ambientDispatch = uvec4(0u, 1u, 1u, 0u);
    for (int k = 0; k < S3D_TILE_CLASSES; ++k) tileHeader.tileClassDispatch[k] = uvec4(0u, 1u, 1u, 0u);
  }
  if (index < uint(S3D_COUNT_SLOTS)) tileHeader.shadedPixels[index] = 0u;
  if (!maskedRender()) return;
  for (uint word = index; word < tileCount(); word += gl_NumWorkGroups.x * gl_WorkGroupSize.x) tileEntries[word] = 0u;
}
