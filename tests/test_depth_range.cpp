// The frame's depth reduction: nearest, farthest, sky and invalid counts and the log-depth histogram (C++
// reference; the GPU pass is held to it bin by bin).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "s3d/stereo/depth_range.h"

namespace s3d::stereo {
namespace {

TEST(DepthRangeReference, CountsEveryKindOfPixel) {
  DepthImage depth(4, 2, 2.0f);
  *depth.at(0, 0) = 0.5f;
  *depth.at(1, 0) = 300.0f;
  *depth.at(2, 0) = std::numeric_limits<float>::infinity();
  *depth.at(3, 0) = std::numeric_limits<float>::quiet_NaN();
  *depth.at(0, 1) = -1.0f;
  const DepthRange range = reduceDepthRangeReference(depth);
  EXPECT_EQ(range.nearest, 0.5f);
  EXPECT_EQ(range.farthest, 300.0f);
  EXPECT_EQ(range.skyPixels, 1u);
  EXPECT_EQ(range.invalidPixels, 2u);
  EXPECT_EQ(range.finitePixels(), 5u);
  EXPECT_TRUE(std::isinf(range.farthestShown()));
}

TEST(DepthRangeReference, BinsSpanAnEighthOfAnOctave) {
  // 1.0 = 2^0 starts bin 6 * 8 = 48 (bin 0 starts at 2^-6); 1.1 is still in it, 1.1 * 1.0905 is not.
  EXPECT_EQ(gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(1.0f)), 48u);
  EXPECT_EQ(gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(1.09f)), 48u);
  EXPECT_EQ(gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(1.13f)), 49u);
  EXPECT_EQ(depthBinLowerEdge(48), 1.0f);
  EXPECT_EQ(depthBinLowerEdge(56), 2.0f);
  EXPECT_EQ(gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(1e-4f)), 0u);  // nearer: first bin
  EXPECT_EQ(gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(1e9f)), 191u);  // farther: last bin
}

TEST(DepthRangeReference, PercentilesAreTheUpperEdgeOfTheirBin) {
  DepthImage depth(10, 1, 1.0f);  // 9 pixels at 1 m, one at 8 m
  *depth.at(9, 0) = 8.0f;
  const DepthRange range = reduceDepthRangeReference(depth);
  EXPECT_EQ(range.percentile(0.5), depthBinLowerEdge(49));
  EXPECT_EQ(range.percentile(1.0), 8.0f);  // the last bin's edge clamped to the farthest depth
  EXPECT_EQ(range.percentile(0.0), depthBinLowerEdge(49));
}

TEST(DepthRangeReference, AnImageWithoutFiniteDepthHasNoRange) {
  DepthImage depth(3, 1, std::numeric_limits<float>::infinity());
  const DepthRange range = reduceDepthRangeReference(depth);
  EXPECT_FALSE(range.hasFinite());
  EXPECT_EQ(range.skyPixels, 3u);
  EXPECT_TRUE(std::isinf(range.percentile(0.5)));
}

}  // namespace
}  // namespace s3d::stereo
