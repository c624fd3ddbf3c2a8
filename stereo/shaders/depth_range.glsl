// The depth-range reduction's body (depth_range.comp, depth_range_host.comp). Each invocation reduces a run of
// S3D_DEPTH_RUN pixels of one row in registers (a histogram bin is added once per run of equal bins: neighbouring
// depths mostly share one), then the workgroup in shared memory, then once per group into the result buffer: few
// atomics, which a CPU device (lavapipe) serializes. Positive floats order as their bits: min/max are exact. The
// includer declares the depth it reads: S3D_DEPTH_AT(texel), the linear depth there, and S3D_DEPTH_SIZE().
#include "s3d/stereo/depth_range_shared.h"

layout(local_size_x = S3D_DEPTH_GROUP_SIZE, local_size_y = S3D_DEPTH_GROUP_SIZE) in;
layout(std430, binding = 1) buffer Result { DepthRangeBuffer result; };

shared uint groupBins[S3D_DEPTH_HISTOGRAM_BINS];
shared uint groupNearest, groupFarthest, groupSky, groupInvalid;

const uint kGroupInvocations = S3D_DEPTH_GROUP_SIZE * S3D_DEPTH_GROUP_SIZE;

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
  const int x0 = int(gl_GlobalInvocationID.x) * S3D_DEPTH_RUN;
  uint nearest = 0x7f800000u, farthest = 0u, sky = 0u, invalid = 0u;
  uint runBin = 0u, runCount = 0u;
  if (y < size.y) {
    for (int x = x0; x < min(x0 + S3D_DEPTH_RUN, size.x); ++x) {
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
    if (groupBins[i] != 0u) atomicAdd(result.bins[i], groupBins[i]);
  if (local == 0u) {
    if (groupNearest != 0x7f800000u) {
      atomicMin(result.nearestBits, groupNearest);
      atomicMax(result.farthestBits, groupFarthest);
    }
    if (groupSky != 0u) atomicAdd(result.skyPixels, groupSky);
    if (groupInvalid != 0u) atomicAdd(result.invalidPixels, groupInvalid);
  }
}
