// Hybrid stereo, the stereo side: the classification finds the pixels a depth step disoccludes and ranks them
// first, the budget picks whole bins from the top, and the GPU passes match the C++ reference.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

class HybridPassTest : public test::VulkanTest {};

StereoParameters parametersFor(float maxSeparation) {
  StereoParameters parameters;
  parameters.maxSeparation = maxSeparation;
  parameters.zeroParallaxDistance = 1.0f;
  parameters.edgeCrop = 0.0f;
  return parameters;
}

// Sky everywhere (parallax m W = 20 px at 200 columns and m = 0.1) but a block at depth 2 (parallax 10 px) on
// columns [80, 120).
DepthImage stepDepth() {
  DepthImage depth(200, 2, INFINITY);
  for (std::uint32_t y = 0; y < depth.height; ++y)
    for (std::uint32_t x = 80; x < 120; ++x) *depth.at(x, y) = 2.0f;
  return depth;
}

TEST(HybridClassification, RanksTheDisoccludedPixelsOfADepthStepHighestAndFlatFarPixelsZero) {
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.1f), 200, 2);
  const HybridClassification classes = classifyHybridReference(stepDepth(), c);
  // Left eye: the block lands 10 px left (70..109), the sky 20 px left; behind the block's right edge the sky
  // from column 120 lands at 100, so eye columns 100..109 are where the block's right edge disoccludes sky.
  const std::uint32_t top = *std::max_element(classes.leftBins.begin(), classes.leftBins.end());
  EXPECT_EQ(top, gpu::hybridScoreBin(10.0f));
  for (int x = 100; x <= 109; ++x) EXPECT_EQ(classes.leftBins[std::size_t(x)], top) << "column " << x;
  // Far from both steps (more than the 21 px window) nothing can go wrong.
  for (int x : {0, 10, 160, 199}) EXPECT_EQ(classes.leftBins[std::size_t(x)], 0u) << "column " << x;
  // The right eye mirrors it: the left edge (column 80) disoccludes eye columns 90..99.
  for (int x = 90; x <= 99; ++x) EXPECT_EQ(classes.rightBins[std::size_t(x)], top) << "column " << x;
}

TEST(HybridClassification, LeavesTheCroppedColumnsOutOfBinsAndHistogram) {
  StereoParameters parameters = parametersFor(0.1f);
  parameters.edgeCrop = 0.05f;  // 10 columns each side
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 2);
  const HybridClassification classes = classifyHybridReference(stepDepth(), c);
  EXPECT_EQ(std::accumulate(classes.leftHistogram.begin(), classes.leftHistogram.end(), std::uint64_t(0)), 180u * 2u);
  EXPECT_EQ(std::accumulate(classes.rightHistogram.begin(), classes.rightHistogram.end(), std::uint64_t(0)), 180u * 2u);
}

TEST(HybridBudget, ZeroMasksNothingAndOneMasksEveryPixel) {
  HybridHistogram histogram{};
  histogram[0] = 500;
  histogram[3] = 40;
  histogram[200] = 10;
  EXPECT_EQ(hybridThreshold(histogram, 0.0f).maskedPixels, 0u);
  EXPECT_EQ(hybridThreshold(histogram, 0.0f).bin, 201);  // above every occupied bin: masks nothing
  EXPECT_EQ(hybridThreshold(histogram, 1.0f).maskedPixels, 550u);
  EXPECT_EQ(hybridThreshold(histogram, 1.0f).bin, 0);
}

TEST(HybridBudget, TakesTheHighestScoresFirstAndNeverMoreThanTheBudget) {
  HybridHistogram histogram{};
  histogram[0] = 500;
  histogram[3] = 40;
  histogram[200] = 10;
  // 2 % of 550 = 11: only the top bin fits; 10 % = 55: both scored bins (50).
  EXPECT_EQ(hybridThreshold(histogram, 0.02f).maskedPixels, 10u);
  EXPECT_GT(hybridThreshold(histogram, 0.02f).bin, 3);  // any bin in (3, 200] masks the same pixels
  EXPECT_LE(hybridThreshold(histogram, 0.02f).bin, 200);
  EXPECT_EQ(hybridThreshold(histogram, 0.1f).maskedPixels, 50u);
  EXPECT_EQ(hybridThreshold(histogram, 0.1f).bin, 1);
  EXPECT_EQ(hybridThreshold(histogram, 0.01f).maskedPixels, 0u);  // 5.5 pixels: the top bin does not fit
  EXPECT_THROW((void)hybridThreshold(histogram, 1.5f), std::invalid_argument);
}

// Tolerance: the GPU may round the parallax division differently in the last bit (Vulkan allows 2.5 ulp), which
// can move a score across a 1/8 px bin boundary; measured: identical on lavapipe.
TEST_F(HybridPassTest, ClassificationMatchesTheCppReferenceBinForBin) {
  const test::SyntheticView view = test::makeBlockView(160, 24, 7, 1.0f, 9, 4, true);
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.05f), 160, 24);
  const HybridClassification expected = classifyHybridReference(view.depth, c);
  const HybridClassification gpu = classifyHybridOnGpu(context(), view.depth, c);
  std::size_t offByOne = 0;
  for (std::size_t i = 0; i < expected.leftBins.size(); ++i)
    for (auto [a, b] : {std::pair{expected.leftBins[i], gpu.leftBins[i]}, std::pair{expected.rightBins[i], gpu.rightBins[i]}}) {
      ASSERT_LE(std::abs(int(a) - int(b)), 1) << "pixel " << i;
      offByOne += a != b;
    }
  EXPECT_LE(offByOne, expected.leftBins.size() / 1000);
  if (offByOne == 0) {
    EXPECT_EQ(gpu.leftHistogram, expected.leftHistogram);
    EXPECT_EQ(gpu.rightHistogram, expected.rightHistogram);
  }
}

TEST_F(HybridPassTest, CompositeMatchesTheCppReferenceExactly) {
  const test::SyntheticView displaced = test::makeBlockView(64, 16, 1, 1.0f, 8, 4, false);
  const test::SyntheticView rendered = test::makeBlockView(64, 16, 2, 1.0f, 8, 4, false);
  StereoParameters parameters = parametersFor(0.05f);
  parameters.edgeCrop = 0.05f;
  gpu::HybridConstants c = makeHybridConstants(parameters, 64, 16);
  c.thresholdBin = 5;
  std::vector<std::uint32_t> bins(64 * 16);
  for (std::size_t i = 0; i < bins.size(); ++i) bins[i] = std::uint32_t((i * 7) % 11);
  ImageRGBA8 expected = displaced.color;
  compositeHybridReference(expected, rendered.color, bins, c);
  EXPECT_EQ(compositeHybridOnGpu(context(), displaced.color, rendered.color, bins, c).pixels, expected.pixels);
  EXPECT_NE(expected.pixels, displaced.color.pixels);  // some pixels did change
}

}  // namespace
}  // namespace s3d::stereo
