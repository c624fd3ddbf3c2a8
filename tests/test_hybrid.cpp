// Hybrid stereo, the stereo side: the classification finds the pixels a depth step disoccludes and ranks them
// first, the budget picks whole bins from the top, and the GPU passes match the C++ reference.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <numeric>
#include <tuple>

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

TEST(HybridParameters, RefuseTheNonlinearMapping) {
  // The masked pixels are rendered from one pair of eye cameras; a nonlinear map's parallax needs one per segment.
  StereoParameters p;
  p.method = StereoMethod::Hybrid;
  EXPECT_NO_THROW(validate(p));
  p.disparityMapping = DisparityMapping::Nonlinear;
  EXPECT_THROW(validate(p), std::invalid_argument);
  p.method = p.hybridBase;  // the hybrid's base alone takes the mapped depth like any displacement
  EXPECT_NO_THROW(validate(p));
}

TEST(HybridClassification, RanksTheDisoccludedPixelsOfADepthStepByTheirHoleAndFlatFarPixelsZero) {
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.1f), 200, 2);
  const HybridClassification classes = classifyHybridReference(stepDepth(), c);
  // Left eye: column i lands at i - P (sky P = 20, block P = 10). The sky's column 79 lands at 59 and the block's
  // column 80 at 70: eye columns 60..69 see around the block's left edge, where the center saw nothing.
  for (int x = 60; x <= 69; ++x) EXPECT_EQ(classes.leftBins[std::size_t(x)], gpu::hybridScoreBin(10.0f)) << "column " << x;
  // The sky beside the hole is seen, but the boundary between the surfaces lies next to it: the edge band
  // (0.25 + 0.125 * min(10, 2) px), below any hole.
  EXPECT_EQ(classes.leftBins[59], gpu::hybridScoreBin(0.5f));
  // On the block, farther from the boundary: only the nearness tier, below the edge band and falling with the
  // distance (5 and 10 px from the hole).
  EXPECT_GT(classes.leftBins[80], 0u);
  EXPECT_LT(classes.leftBins[75], classes.leftBins[59]);
  EXPECT_LT(classes.leftBins[80], classes.leftBins[75]);
  // The right eye mirrors it behind the block's right edge: 119 lands at 129, 120 at 140.
  for (int x = 130; x <= 139; ++x) EXPECT_EQ(classes.rightBins[std::size_t(x)], gpu::hybridScoreBin(10.0f)) << "column " << x;
  // Far from both edges (more than the 21 px window) the sky lands where the gather reads it: nothing to render.
  for (int x : {0, 10, 160, 199}) EXPECT_EQ(classes.leftBins[std::size_t(x)], 0u) << "column " << x;
}

// A 4-tap search (taps 5, 10, 15, 20 px) past the block's right edge in the left eye: a tap still on the block
// makes the gather read the sky 10 px too far, where the block's own columns do not land.
TEST(HybridClassification, MarksTheHaloWhereTheGathersTapsPickTheWrongSurface) {
  StereoParameters parameters = parametersFor(0.1f);
  parameters.method = StereoMethod::Search;
  parameters.searchTaps = 4;
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 2);
  ASSERT_EQ(c.baseTapCount, 4);
  EXPECT_GT(hybridPixelScoreReference(stepDepth(), 112, 0, Eye::Left, c), 9.0f);  // tap 117 on the block
  // The block, read where it lands: only the edge band of its boundary with the sky (0.5 px).
  EXPECT_EQ(hybridPixelScoreReference(stepDepth(), 100, 0, Eye::Left, c), 0.5f);
  EXPECT_EQ(hybridPixelScoreReference(stepDepth(), 140, 0, Eye::Left, c), 0.0f);  // every tap on the sky, far away
  // A base that lands on the visible surface by design is only wrong in the holes.
  parameters.hybridBase = StereoMethod::Iterative;
  parameters.method = StereoMethod::Hybrid;
  const gpu::HybridConstants iterative = makeHybridConstants(parameters, 200, 2);
  EXPECT_EQ(iterative.baseTapCount, 0);
  EXPECT_LT(hybridPixelScoreReference(stepDepth(), 112, 0, Eye::Left, iterative), 0.25f);  // the nearness tier only
  EXPECT_GT(hybridPixelScoreReference(stepDepth(), 65, 0, Eye::Left, iterative), 9.0f);
}

TEST(HybridClassification, LeavesTheCroppedColumnsOutOfBinsAndHistogram) {
  StereoParameters parameters = parametersFor(0.1f);
  parameters.edgeCrop = 0.05f;  // 10 columns each side
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 2);
  const HybridClassification classes = classifyHybridReference(stepDepth(), c);
  EXPECT_EQ(std::accumulate(classes.leftHistogram.begin(), classes.leftHistogram.end(), std::uint64_t(0)), 180u * 2u);
  EXPECT_EQ(std::accumulate(classes.rightHistogram.begin(), classes.rightHistogram.end(), std::uint64_t(0)), 180u * 2u);
}

TEST(HybridBudget, TheCapIsTheBudgetsShareRoundedDownAndEveryPixelAtOne) {
  EXPECT_EQ(hybridPixelCap(0.0f, 550), 0u);
  EXPECT_EQ(hybridPixelCap(0.02f, 550), 11u);
  EXPECT_EQ(hybridPixelCap(0.01f, 550), 5u);  // 5.5 rounds down: never more than the budget
  EXPECT_EQ(hybridPixelCap(1.0f, 550), 550u);
  EXPECT_EQ(hybridPixelCap(1.0f, 16777217u), 16777217u);  // not float-rounded to 2^24
  EXPECT_THROW((void)hybridPixelCap(1.5f, 550), std::invalid_argument);
  EXPECT_THROW((void)hybridPixelCap(NAN, 550), std::invalid_argument);
}

TEST(HybridBudget, ZeroMasksNothingAndOneMasksEveryPixel) {
  HybridHistogram histogram{};
  histogram[0] = 500;
  histogram[3] = 40;
  histogram[200] = 10;
  EXPECT_EQ(hybridThreshold(histogram, hybridPixelCap(0.0f, 550)).maskedPixels, 0u);
  EXPECT_EQ(hybridThreshold(histogram, hybridPixelCap(0.0f, 550)).bin, 201);  // above every occupied bin
  EXPECT_EQ(hybridThreshold(histogram, hybridPixelCap(1.0f, 550)).maskedPixels, 550u);
  EXPECT_EQ(hybridThreshold(histogram, hybridPixelCap(1.0f, 550)).bin, 0);
}

TEST(HybridBudget, TakesTheHighestScoresFirstAndNeverMoreThanTheBudget) {
  HybridHistogram histogram{};
  histogram[0] = 500;
  histogram[3] = 40;
  histogram[200] = 10;
  // 2 % of 550 = 11: only the top bin fits; 10 % = 55: both scored bins (50).
  EXPECT_EQ(hybridThreshold(histogram, 11).maskedPixels, 10u);
  EXPECT_GT(hybridThreshold(histogram, 11).bin, 3);  // any bin in (3, 200] masks the same pixels
  EXPECT_LE(hybridThreshold(histogram, 11).bin, 200);
  EXPECT_EQ(hybridThreshold(histogram, 55).maskedPixels, 50u);
  EXPECT_EQ(hybridThreshold(histogram, 55).bin, 1);
  EXPECT_EQ(hybridThreshold(histogram, 5).maskedPixels, 0u);  // the top bin does not fit whole
}

TEST(HybridMask, MarksTheBinsAtOrAboveTheThresholdInsideTheCropOnly) {
  StereoParameters parameters = parametersFor(0.1f);
  parameters.edgeCrop = 0.05f;  // 10 columns each side
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 2);
  std::vector<std::uint32_t> bins(400, 7);
  bins[50] = 3;
  const std::vector<std::uint8_t> mask = hybridMaskReference(bins, 5, c);
  EXPECT_EQ(mask[50], 0);
  EXPECT_EQ(mask[51], 1);
  EXPECT_EQ(mask[5], 0);    // cropped
  EXPECT_EQ(mask[195], 0);  // cropped
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 2 * 180 - 1);
}

// Tolerance: the GPU may round the parallax division differently in the last bit (Vulkan allows 2.5 ulp), which
// can move a score across a 1/8 px bin boundary; measured: identical on lavapipe.
TEST_F(HybridPassTest, ClassificationMatchesTheCppReferenceBinForBin) {
  const test::SyntheticView view = test::makeBlockView(160, 24, 7, 1.0f, 9, 4, true);
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.05f), 160, 24);
  const HybridClassification expected = classifyHybridReference(view.depth, c);
  const HybridClassification gpu = classifyHybridOnGpu(context(), view.depth, c).classification;
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

// The threshold and the masks follow from the GPU's own histogram exactly (integer math), at every budget.
TEST_F(HybridPassTest, ThresholdAndMasksMatchTheCppReferenceAtEveryBudget) {
  const test::SyntheticView view = test::makeBlockView(160, 24, 7, 1.0f, 9, 4, true);
  for (float budget : {0.0f, 0.01f, 0.05f, 0.2f, 0.5f, 0.99f, 1.0f}) {
    StereoParameters parameters = parametersFor(0.05f);
    parameters.hybridBudget = budget;
    const gpu::HybridConstants c = makeHybridConstants(parameters, 160, 24);
    const HybridGpuResult gpu = classifyHybridOnGpu(context(), view.depth, c);
    for (auto [histogram, threshold, bins, mask] :
         {std::tuple{&gpu.classification.leftHistogram, &gpu.leftThreshold, &gpu.classification.leftBins, &gpu.leftMask},
          std::tuple{&gpu.classification.rightHistogram, &gpu.rightThreshold, &gpu.classification.rightBins,
                     &gpu.rightMask}}) {
      const HybridThreshold expected = hybridThreshold(*histogram, c.maskedPixelCap);
      EXPECT_EQ(threshold->bin, expected.bin) << "budget " << budget;
      EXPECT_EQ(threshold->maskedPixels, expected.maskedPixels) << "budget " << budget;
      EXPECT_LE(threshold->maskedPixels, c.maskedPixelCap);
      EXPECT_EQ(*mask, hybridMaskReference(*bins, expected.bin, c)) << "budget " << budget;
      EXPECT_EQ(std::uint64_t(std::count(mask->begin(), mask->end(), 1)), expected.maskedPixels);
    }
  }
}

TEST_F(HybridPassTest, CompositeMatchesTheCppReferenceExactly) {
  const test::SyntheticView displaced = test::makeBlockView(64, 16, 1, 1.0f, 8, 4, false);
  const test::SyntheticView rendered = test::makeBlockView(64, 16, 2, 1.0f, 8, 4, false);
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.05f), 64, 16);
  std::vector<std::uint8_t> mask(64 * 16);
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = std::uint8_t((i * 7) % 11 >= 5);
  ImageRGBA8 expected = displaced.color;
  compositeHybridReference(expected, rendered.color, mask);
  EXPECT_EQ(compositeHybridOnGpu(context(), displaced.color, rendered.color, mask, c).pixels, expected.pixels);
  EXPECT_NE(expected.pixels, displaced.color.pixels);  // some pixels did change
}

}  // namespace
}  // namespace s3d::stereo
