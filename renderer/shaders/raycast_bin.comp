#version 450
// The ray-cast pass's screen bins (raycast_shared.h): every set-up triangle appended to the list of each bin of
// its layer that its pixel bounds (snappedPixelBounds) touch. A triangle spanning at most S3D_RAYCAST_BIN_DIRECT
// bins is appended by its own thread; a larger one is queued, and the indirect pass (kLargeTriangles) spreads its
// bins over S3D_RAYCAST_BIN_SPLIT workgroups, so one floor triangle does not serialize thousands of appends.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "s3d/renderer/raycast_shared.h"

layout(local_size_x = S3D_RAYCAST_BIN_GROUP) in;
layout(constant_id = 0) const bool kLargeTriangles = false;
layout(binding = 0) uniform Constants { RaycastConstants constants; };
layout(std430, binding = 1) readonly buffer Snapped { SnappedTriangle snapped[]; };
layout(std430, binding = 2) buffer BinCounts { uint binCounts[]; };
layout(std430, binding = 3) writeonly buffer BinEntries { uint binEntries[]; };
layout(std430, binding = 4) buffer Large {
  RaycastBinLarge large;
  uint largeTriangles[];
};
layout(push_constant) uniform Push {
  uint triangleCount;
  uint firstPersonFirst;  // triangles from here on are the first-person layer's
};

// The bins a triangle's pixel bounds touch: xy the first, zw the last (inclusive).
ivec4 binBounds(uint i) {
  ivec4 pixels = snappedPixelBounds(snapped[i], constants.screen);
  return pixels.z < pixels.x || pixels.w < pixels.y ? ivec4(0, 0, -1, -1) : pixels / S3D_RAYCAST_BIN_SIZE;
}

void append(uint i, ivec4 bins, uint k) {
  uint columns = uint(bins.z - bins.x + 1);
  uint x = uint(bins.x) + k % columns, y = uint(bins.y) + k / columns;
  uint bin = (i >= firstPersonFirst ? constants.bins.y : 0u) + y * constants.bins.x + x;
  uint slot = atomicAdd(binCounts[bin], 1u);
  if (slot < S3D_RAYCAST_BIN_CAPACITY) binEntries[bin * S3D_RAYCAST_BIN_CAPACITY + slot] = i;
}

void main() {
  if (kLargeTriangles) {  // workgroup x takes queued triangles x, x + the dispatch's width, ...
    for (uint queued = gl_WorkGroupID.x; queued < large.dispatch.w; queued += gl_NumWorkGroups.x) {
      uint i = largeTriangles[queued];
      ivec4 bins = binBounds(i);
      uint count = uint(bins.z - bins.x + 1) * uint(bins.w - bins.y + 1);
      uint stride = S3D_RAYCAST_BIN_GROUP * gl_NumWorkGroups.y;
      for (uint k = gl_WorkGroupID.y * S3D_RAYCAST_BIN_GROUP + gl_LocalInvocationID.x; k < count; k += stride)
        append(i, bins, k);
    }
    return;
  }
  uint i = gl_GlobalInvocationID.x;
  if (i >= triangleCount) return;
  ivec4 bins = binBounds(i);
  if (bins.z < bins.x || bins.w < bins.y) return;
  uint count = uint(bins.z - bins.x + 1) * uint(bins.w - bins.y + 1);
  if (count <= S3D_RAYCAST_BIN_DIRECT) {
    for (uint k = 0u; k < count; ++k) append(i, bins, k);
  } else {
    uint queued = atomicAdd(large.dispatch.w, 1u);
    largeTriangles[queued] = i;
    // The dispatch's width, at most the 65535 workgroups every Vulkan device can dispatch.
    atomicMax(large.dispatch.x, min(queued + 1u, 65535u));
  }
}
