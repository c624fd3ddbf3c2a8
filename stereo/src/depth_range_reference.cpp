#include "s3d/stereo/depth_range.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace s3d::stereo {

float depthBinLowerEdge(std::uint32_t bin) {
  const std::uint32_t key = (std::uint32_t(S3D_DEPTH_FIRST_OCTAVE) << S3D_DEPTH_MANTISSA_BITS) + bin;
  return std::bit_cast<float>(key << (23 - S3D_DEPTH_MANTISSA_BITS));
}

float DepthRange::farthestShown() const {
  if (skyPixels > 0) return std::numeric_limits<float>::infinity();
  return farthest;
}

std::uint64_t DepthRange::finitePixels() const {
  std::uint64_t total = 0;
  for (std::uint32_t count : bins) total += count;
  return total;
}

float DepthRange::percentile(double share) const {
  if (!(share >= 0.0 && share <= 1.0)) throw std::invalid_argument("DepthRange::percentile: share outside [0, 1]");
  const std::uint64_t shown = finitePixels() + skyPixels;
  if (shown == 0) return std::numeric_limits<float>::quiet_NaN();
  const double wanted = share * double(shown);
  double cumulative = 0.0;
  for (std::uint32_t bin = 0; bin < bins.size(); ++bin) {
    cumulative += bins[bin];
    if (bins[bin] > 0 && cumulative >= wanted) {
      const float upper = bin + 1 < bins.size() ? depthBinLowerEdge(bin + 1) : farthest;
      return std::clamp(upper, nearest, farthest);
    }
  }
  return skyPixels > 0 ? std::numeric_limits<float>::infinity() : farthest;
}

DepthRange depthRangeFromBuffer(const gpu::DepthRangeBuffer& buffer) {
  DepthRange range;
  range.nearest = std::bit_cast<float>(buffer.nearestBits);
  range.farthest = std::bit_cast<float>(buffer.farthestBits);
  range.skyPixels = buffer.skyPixels;
  range.invalidPixels = buffer.invalidPixels;
  range.bins.assign(std::begin(buffer.bins), std::end(buffer.bins));
  return range;
}

DepthRange reduceDepthRangeReference(const DepthImage& linearDepth) {
  gpu::DepthRangeBuffer buffer{};
  buffer.nearestBits = std::bit_cast<std::uint32_t>(std::numeric_limits<float>::infinity());
  for (float depth : linearDepth.pixels) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(depth);
    switch (gpu::depthKind(bits)) {
      case 0:
        buffer.nearestBits = std::min(buffer.nearestBits, bits);  // positive floats order as their bits
        buffer.farthestBits = std::max(buffer.farthestBits, bits);
        ++buffer.bins[gpu::depthHistogramBin(bits)];
        break;
      case 1: ++buffer.skyPixels; break;
      default: ++buffer.invalidPixels; break;
    }
  }
  return depthRangeFromBuffer(buffer);
}

}  // namespace s3d::stereo
