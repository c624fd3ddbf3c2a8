// The frame's depth reduction: nearest, farthest, sky and invalid counts and the log-depth histogram (C++
// reference; the GPU pass is held to it bin by bin).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <stdexcept>
#include <string>

#include "s3d/stereo/depth_range.h"
#include "s3d/stereo/depth_range_pass.h"
#include "vulkan_test.h"

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

class DepthRangeGpu : public test::VulkanTest {};

// Every device's shape gives the same result (each device runs its own; both fit every test device).
constexpr DepthReductionShape kShapes[] = {kDepthReductionCpuShape, kDepthReductionGpuShape};

std::string shapeName(DepthReductionShape shape) {
  return std::to_string(shape.groupSide) + "x" + std::to_string(shape.groupSide) + " groups, runs of " +
         std::to_string(shape.run);
}

TEST_F(DepthRangeGpu, MatchesTheReferenceBinForBin) {
  // 67x41 (not a multiple of the 16x16 groups): log-uniform depths from 1 cm to 1000 km (both clamped bins
  // hit), plus sky, NaN, zero and negative pixels. Integer binning of the float bits: exact, no tolerance.
  DepthImage depth(67, 41);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> exponent(-2.0f, 6.0f);
  std::uniform_int_distribution<int> kind(0, 19);
  for (float& value : depth.pixels) {
    const int k = kind(random);
    value = k == 0   ? std::numeric_limits<float>::infinity()
            : k == 1 ? std::numeric_limits<float>::quiet_NaN()
            : k == 2 ? (random() % 2 ? 0.0f : -3.0f)
                     : std::pow(10.0f, exponent(random));
  }
  const DepthRange expected = reduceDepthRangeReference(depth);
  for (const DepthReductionShape shape : kShapes) {
    SCOPED_TRACE(shapeName(shape));
    const DepthRange gpu = reduceDepthRangeOnGpu(context(), depth, shape);
    EXPECT_EQ(gpu.nearest, expected.nearest);
    EXPECT_EQ(gpu.farthest, expected.farthest);
    EXPECT_EQ(gpu.skyPixels, expected.skyPixels);
    EXPECT_EQ(gpu.invalidPixels, expected.invalidPixels);
    EXPECT_EQ(gpu.bins, expected.bins);
  }
  EXPECT_GT(expected.skyPixels, 0u);
  EXPECT_GT(expected.bins.front(), 0u);
  EXPECT_GT(expected.bins.back(), 0u);
}

// A depth image of `width` x `height` at `depth` everywhere, in the compute-read state the pass reads.
vk::Image uploadedDepth(vk::Context& context, std::uint32_t width, std::uint32_t height, float depth) {
  const DepthImage pixels(width, height, depth);
  vk::Image image = vk::createImage(context, VK_FORMAT_R32_SFLOAT, width, height,
                                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context, image, std::as_bytes(std::span(pixels.pixels)), vk::kComputeRead);
  return image;
}

// Each reduction starts from fresh counters (the last workgroup of the one before reset them): a large image (many
// workgroups), then a small one at another depth, in one submission and in the next two.
TEST_F(DepthRangeGpu, EachReductionCountsOnlyItsOwnImage) {
  const vk::Image large = uploadedDepth(context(), 300, 70, 40.0f), small = uploadedDepth(context(), 9, 5, 2.0f);
  for (const DepthReductionShape shape : kShapes) {
    SCOPED_TRACE(shapeName(shape));
    const DepthRangePass pass(context(), shape);
    auto expectSmall = [&] {
      const DepthRange range = pass.result();
      EXPECT_EQ(range.nearest, 2.0f);
      EXPECT_EQ(range.farthest, 2.0f);
      std::uint64_t counted = 0;
      for (std::uint32_t bin : range.bins) counted += bin;
      EXPECT_EQ(counted, 45u);
    };
    context().submitAndWait([&](VkCommandBuffer cmd) {
      pass.record(cmd, large);
      pass.record(cmd, small);
    });
    expectSmall();
    context().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, large); });
    EXPECT_EQ(pass.result().nearest, 40.0f);
    context().submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, small); });
    expectSmall();
  }
}

TEST_F(DepthRangeGpu, AShapeBeyondTheDeviceIsRefused) {
  EXPECT_THROW(DepthRangePass(context(), DepthReductionShape{4096, 8}), std::invalid_argument);
  EXPECT_THROW(DepthRangePass(context(), DepthReductionShape{8, 0}), std::invalid_argument);
}

// Two passes on one queue, one after the other in a submission: each has its own counters and result.
TEST_F(DepthRangeGpu, TwoPassesKeepTheirOwnResults) {
  const vk::Image near = uploadedDepth(context(), 64, 16, 1.5f), far = uploadedDepth(context(), 64, 16, 30.0f);
  const DepthRangePass first(context()), second(context());
  context().submitAndWait([&](VkCommandBuffer cmd) {
    first.record(cmd, near);
    second.record(cmd, far);
  });
  EXPECT_EQ(first.result().nearest, 1.5f);
  EXPECT_EQ(second.result().farthest, 30.0f);
}

TEST_F(DepthRangeGpu, AnImageOfSkyHasNoFiniteRange) {
  const DepthRange gpu = reduceDepthRangeOnGpu(context(), DepthImage(5, 3, std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(gpu.hasFinite());
  EXPECT_EQ(gpu.skyPixels, 15u);
}

}  // namespace
}  // namespace s3d::stereo
