// The depth-range reduction's body (depth_range.comp, depth_range_host.comp). Each invocation reduces a run of
// kRun pixels of one row in registers (a histogram bin is added once per run of equal bins: neighbouring
// depths mostly share one), then the workgroup in shared memory, then once per group into the device counters: few
// atomics, which a CPU device (lavapipe) serializes. The last group to finish hands the counters to the result and
// resets them (a clear and a copy around the dispatch were measured slower on a GPU). Positive floats order as
// their bits: min/max are exact. The includer declares the depth it reads: S3D_DEPTH_AT(texel), the linear depth
// there, and S3D_DEPTH_SIZE().
#include "s3d/stereo/depth_range_shared.h"

// The device's shape (stereo::DepthReductionShape): the workgroup's side (ids 0 and 1) and each invocation's run.
layout(local_size_x_id = 0, local_size_y_id = 1) in;
layout(constant_id = 0) const int kGroupSide = S3D_DEPTH_CPU_GROUP_SIDE;
layout(constant_id = 1) const int kGroupSideY = S3D_DEPTH_CPU_GROUP_SIDE;
layout(constant_id = 2) const int kRun = S3D_DEPTH_CPU_RUN;
layout(std430, binding = 1) coherent buffer Counters { DepthRangeCounters counters; };
layout(std430, binding = 2) writeonly buffer Result { DepthRangeBuffer result; };

shared uint groupBins[S3D_DEPTH_HISTOGRAM_BINS];
shared uint groupNearest, groupFarthest, groupSky, groupInvalid;
shared uint lastGroup;

const uint kGroupInvocations = uint(kGroupSide * kGroupSideY);

void main() {
  const uint local = gl_LocalInvocationIndex;
  for (uint i = local; i < S3D_DEPTH_HISTOGRAM_BINS; i += kGroupInvocations) groupBins[i] = 0u;
  if (local == 0u) {
    groupNearest = 0x7f800000u;
    groupFarthest = 0u;
    groupSky = 0u;
    groupInvalid = 0u;
  }
  barrier();
  const ivec2 size = S3D_DEPTH_SIZE();
  const int y = int(gl_GlobalInvocationID.y);
  const int x0 = int(gl_GlobalInvocationID.x) * kRun;
  uint nearest = 0x7f800000u, farthest = 0u, sky = 0u, invalid = 0u;
  uint runBin = 0u, runCount = 0u;
  if (y < size.y) {
    for (int x = x0; x < min(x0 + kRun, size.x); ++x) {
      const uint bits = floatBitsToUint(S3D_DEPTH_AT(ivec2(x, y)));
      const uint kind = depthKind(bits);
      if (kind == 0u) {
        nearest = min(nearest, bits);
        farthest = max(farthest, bits);
        const uint bin = depthHistogramBin(bits);
        if (bin != runBin && runCount != 0u) {
          atomicAdd(groupBins[runBin], runCount);
          runCount = 0u;
        }
        runBin = bin;
        ++runCount;
      } else if (kind == 1u) {
        ++sky;
      } else {
        ++invalid;
      }
    }
  }
  if (runCount != 0u) atomicAdd(groupBins[runBin], runCount);
  if (nearest != 0x7f800000u) {
    atomicMin(groupNearest, nearest);
    atomicMax(groupFarthest, farthest);
  }
  if (sky != 0u) atomicAdd(groupSky, sky);
  if (invalid != 0u) atomicAdd(groupInvalid, invalid);
  barrier();
  for (uint i = local; i < S3D_DEPTH_HISTOGRAM_BINS; i += kGroupInvocations)
    if (groupBins[i] != 0u) atomicAdd(counters.range.bins[i], groupBins[i]);
  if (local == 0u) {
    if (groupNearest != 0x7f800000u) {
      atomicMin(counters.range.nearestBits, groupNearest);
      atomicMax(counters.range.farthestBits, groupFarthest);
    }
    if (groupSky != 0u) atomicAdd(counters.range.skyPixels, groupSky);
    if (groupInvalid != 0u) atomicAdd(counters.range.invalidPixels, groupInvalid);
  }
  // The group's atomics are visible before it counts itself done, so the last one to finish reads every group's.
  memoryBarrierBuffer();
  barrier();
  if (local == 0u) lastGroup = atomicAdd(counters.groupsDone, 1u) == gl_NumWorkGroups.x * gl_NumWorkGroups.y - 1u ? 1u : 0u;
  barrier();
  if (lastGroup == 0u) return;
  memoryBarrierBuffer();
  // Each counter read and reset in one atomic: the next dispatch starts from nearest +inf and zeros.
  for (uint i = local; i < S3D_DEPTH_HISTOGRAM_BINS; i += kGroupInvocations)
    result.bins[i] = atomicExchange(counters.range.bins[i], 0u);
  if (local == 0u) {
    result.nearestBits = atomicExchange(counters.range.nearestBits, 0x7f800000u);
    result.farthestBits = atomicExchange(counters.range.farthestBits, 0u);
    result.skyPixels = atomicExchange(counters.range.skyPixels, 0u);
    result.invalidPixels = atomicExchange(counters.range.invalidPixels, 0u);
    atomicExchange(counters.groupsDone, 0u);
  }
}
