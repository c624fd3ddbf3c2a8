#pragma once
// The frame's depth distribution for the disparity budget (comfort/disparity_budget_controller.h): the
// nearest and farthest linear depth, the sky and invalid pixel counts and a log-depth histogram (8 bins per
// octave). depth_range_pass.h computes it on the GPU without reading the image back; this is the C++
// reference of the same math.
#include <cstdint>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/depth_range_shared.h"

namespace s3d::stereo {

struct DepthRange {
  float nearest = 0.0f;   // nearest finite positive depth; +inf when there is none
  float farthest = 0.0f;  // farthest finite positive depth; 0 when there is none
  std::uint64_t skyPixels = 0;
  std::uint64_t invalidPixels = 0;
  std::vector<std::uint32_t> bins;  // S3D_DEPTH_HISTOGRAM_BINS counts of finite positive depths

  bool hasFinite() const { return nearest <= farthest; }
  // The farthest depth any pixel shows: +inf when there is sky.
  float farthestShown() const;
  std::uint64_t finitePixels() const;
  // Depth below which `share` of the finite and sky pixels lie, to the bin (the upper edge of the bin where
  // the count is reached, clamped to [nearest, farthest]; +inf when it falls into the sky). share in [0, 1].
  float percentile(double share) const;
};

// Lower edge of histogram bin `bin` (bin 0: 2^-6; each octave has 2^S3D_DEPTH_MANTISSA_BITS bins).
float depthBinLowerEdge(std::uint32_t bin);

DepthRange depthRangeFromBuffer(const gpu::DepthRangeBuffer& buffer);

// The reference: every pixel of `linearDepth` counted as the compute shader counts it.
DepthRange reduceDepthRangeReference(const DepthImage& linearDepth);

}  // namespace s3d::stereo
