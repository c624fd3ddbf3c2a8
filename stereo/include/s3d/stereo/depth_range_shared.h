// The frame's depth reduction (depth_range.h): layout and binning shared by the compute shader and the C++
// reference. Bins come from the float's bits (exponent and top mantissa bits), so both sides agree exactly.
#ifndef S3D_DEPTH_RANGE_SHARED_H
#define S3D_DEPTH_RANGE_SHARED_H

#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

// Square workgroups whose invocations each reduce a run of pixels of one row in registers, shaped per device
// (stereo::DepthReductionShape): a CPU device serializes atomics and switches invocations at barriers, so it takes
// few long runs; a GPU takes short runs to keep many invocations in flight (RESULTS.md "Cost of the depth reduction").
#define S3D_DEPTH_CPU_GROUP_SIDE 8
#define S3D_DEPTH_CPU_RUN 32
#define S3D_DEPTH_GPU_GROUP_SIDE 16
#define S3D_DEPTH_GPU_RUN 8
#define S3D_DEPTH_MANTISSA_BITS 3  // 8 bins per octave: each bin spans a factor of at most 2^(1/8) = 1.09
#define S3D_DEPTH_HISTOGRAM_BINS 192  // 24 octaves
#define S3D_DEPTH_FIRST_OCTAVE 121    // float exponent of 2^-6 m: bin 0 starts at 1/64 world unit
// Bins [0, 192) cover [2^-6, 2^18); nearer finite depths count in bin 0, farther ones in the last bin.

// The reduction's output buffer (std430: uints only, so C++ and GLSL agree).
struct DepthRangeBuffer {
  uint nearestBits;   // float bits of the nearest finite positive depth (+inf's bits when none)
  uint farthestBits;  // float bits of the farthest finite positive depth (0 when none)
  uint skyPixels;     // +inf depth
  uint invalidPixels; // NaN, zero or negative (the stereo pass reads them as the zero-parallax plane)
  uint bins[S3D_DEPTH_HISTOGRAM_BINS];
};

// The reduction's device counters: the frame's buffer as the workgroups add into it, and how many have finished.
// Between dispatches they hold their starting values (nearest +inf's bits, everything else 0): the last workgroup
// of each dispatch hands the buffer on and resets them.
struct DepthRangeCounters {
  DepthRangeBuffer range;
  uint groupsDone;
};

S3D_INLINE uint depthHistogramBin(uint depthBits) {
  const int key = int(depthBits >> (23 - S3D_DEPTH_MANTISSA_BITS)) - (S3D_DEPTH_FIRST_OCTAVE << S3D_DEPTH_MANTISSA_BITS);
  return uint(min(max(key, 0), S3D_DEPTH_HISTOGRAM_BINS - 1));
}

// Which of the buffer's counters a depth (as float bits) goes to: 0 finite positive, 1 sky, 2 invalid.
S3D_INLINE uint depthKind(uint depthBits) {
  if (depthBits == 0x7f800000u) return 1u;                                    // +inf
  if (depthBits == 0u || depthBits >= 0x7f800000u) return 2u;                 // zero, NaN or negative
  return 0u;
}

S3D_GPU_END

#endif  // S3D_DEPTH_RANGE_SHARED_H
