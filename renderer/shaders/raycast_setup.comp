#version 450
// The ray-cast pass's per-view triangle setup: every triangle of the BVH projected with its layer's
// view-projection, clipped at the near plane and snapped as the rasterizer sets it up (raycast_shared.h's
// setupTriangle), once per view, so each ray's leaf test only evaluates edge functions (coverSample). It also
// empties the screen bins that raycast_bin.comp fills next.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "s3d/renderer/raycast_shared.h"

layout(local_size_x = 64) in;
layout(binding = 0) uniform Constants { RaycastConstants constants; };
layout(std430, binding = 1) readonly buffer Triangles { BvhTriangle triangles[]; };
layout(std430, binding = 2) writeonly buffer Snapped { SnappedTriangle snapped[]; };
layout(std430, binding = 3) writeonly buffer BinCounts { uint binCounts[]; };
layout(std430, binding = 4) writeonly buffer Large { RaycastBinLarge large; };
layout(push_constant) uniform Push {
  uint triangleCount;
  uint firstPersonFirst;  // triangles from here on are the first-person layer's
  uint binCount;          // both layers' bins (0: no bins)
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < binCount) binCounts[i] = 0u;
  if (i == 0u && binCount > 0u) large.dispatch = uvec4(0u, S3D_RAYCAST_BIN_SPLIT, 1u, 0u);
  if (i >= triangleCount) return;
  int layer = i >= firstPersonFirst ? S3D_LAYER_FIRST_PERSON : S3D_LAYER_WORLD;
  snapped[i] = setupTriangle(constants.viewProjection[layer], constants.screen, constants.clearedDepth.y,
                             triangles[i].v0, triangles[i].v1, triangles[i].v2, triangles[i].flags);
}
