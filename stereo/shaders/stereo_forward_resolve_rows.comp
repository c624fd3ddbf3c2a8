#version 450
// Forward method, key-image kernel, last dispatch: each eye pixel shows its winning source at the sub-pixel
// position, or fills a disocclusion from the background side. Workgroups are row segments, so a subgroup holds
// consecutive pixels of one row and its hole pixels share their work (the same eyes as stereo_forward_resolve.comp
// bit for bit): the edges inside the subgroup come from one ballot of the keys every pixel reads anyway, only the
// first and last pixel scan beyond it, and one pixel per run of pixels with the same edges computes the fill
// (forward_shared.h: it depends on the edges alone). The hole fill's image loads bound this pass on a GPU.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"
#include "stereo_forward_resolve.glsl"
#include "stereo_forward_resolve_images.glsl"

layout(local_size_x = S3D_FORWARD_RESOLVE_ROW_GROUP_SIZE) in;

// One eye of the subgroup's pixels; every invocation calls it (subgroup operations), `inside` or not.
vec4 resolveEyeInSubgroup(ivec2 pixel, bool inside, float direction) {
  bool leftEyeKeys = direction > 0.0;
  uint key = inside ? keyAt(leftEyeKeys, pixel.x, pixel.y) : S3D_FORWARD_EMPTY;
  bool hole = inside && key == S3D_FORWARD_EMPTY;
  uint lane = gl_SubgroupInvocationID;
  uint firstLane = subgroupMin(lane), lastLane = subgroupMax(lane);
  int x0 = subgroupBroadcastFirst(pixel.x);  // the first active invocation's: firstLane's
  // Lanes in invocation order on consecutive columns of one row (the usual mapping, not one Vulkan promises):
  // otherwise each hole pixel searches alone.
  bool ordered = subgroupAll(pixel.y == subgroupBroadcastFirst(pixel.y) && pixel.x - x0 == int(lane - firstLane));
  if (!ordered) {
    if (!inside) return vec4(0);
    return hole ? fillHole(leftEyeKeys, pixel.x, pixel.y) : resolveCovered(pixel, direction, key);
  }
  // Barriers end a run of hole pixels: covered pixels, or pixels past the row's end (only after the inside ones).
  uvec4 barriers = subgroupBallot(!hole);
  uvec4 below = barriers & gl_SubgroupLtMask, above = barriers & gl_SubgroupGtMask;
  bool edgeBelow = any(notEqual(below, uvec4(0))), edgeAbove = any(notEqual(above, uvec4(0)));
  // A run that reaches the subgroup's first (last) pixel: that pixel scans for the nearest covered pixel beyond,
  // within its reach, which is the farthest any pixel of the run has.
  int beyondLeft = -1, beyondRight = -1;
  if (hole && lane == firstLane) beyondLeft = nearestCovered(leftEyeKeys, pixel.x, pixel.y, -1);
  if (hole && lane == lastLane) beyondRight = nearestCovered(leftEyeKeys, pixel.x, pixel.y, 1);
  beyondLeft = subgroupMax(beyondLeft);
  beyondRight = subgroupMax(beyondRight);
  int left = -2, right = -2;  // -2: not a hole pixel, so no hole pixel shares its pair
  if (hole) {
    int leftEdge = edgeBelow ? x0 + int(subgroupBallotFindMSB(below) - firstLane) : beyondLeft;
    int rightEdge = beyondRight;
    if (edgeAbove) {
      rightEdge = x0 + int(subgroupBallotFindLSB(above) - firstLane);
      if (rightEdge >= c.width) rightEdge = -1;  // the row ends before any covered pixel
    }
    // As nearestCovered from this pixel: the nearest covered pixel if within c.fillSearchPx.
    left = leftEdge >= 0 && pixel.x - leftEdge <= c.fillSearchPx ? leftEdge : -1;
    right = rightEdge >= 0 && rightEdge - pixel.x <= c.fillSearchPx ? rightEdge : -1;
  }
  // Inside a run the pixels with the same edges are consecutive: the first of them computes the fill for all.
  uint previous = lane == firstLane ? lane : lane - 1u;
  int previousLeft = subgroupShuffle(left, previous), previousRight = subgroupShuffle(right, previous);
  bool edged = hole && (left >= 0 || right >= 0);
  bool computes = edged && (lane == firstLane || previousLeft != left || previousRight != right);
  vec4 fill = vec4(0);
  if (computes) fill = fillBetween(leftEyeKeys, pixel.x, pixel.y, left, right);
  int computer = subgroupInclusiveMax(computes ? int(lane) : -1);  // the last one at or before this pixel
  fill = subgroupShuffle(fill, uint(max(computer, 0)));
  if (!inside) return vec4(0);
  if (!hole) return resolveCovered(pixel, direction, key);
  return edged ? fill : imageLoad(centerColor, pixel);  // no edge within reach: the pixel itself (fillBetween)
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  bool inside = pixel.x < c.width && pixel.y < c.height;
  if (inside) emptyNextKeys(pixel);
  vec4 left = resolveEyeInSubgroup(pixel, inside, 1.0);
  vec4 right = resolveEyeInSubgroup(pixel, inside, -1.0);
  if (inside) storeEyes(pixel, left, right);
}
