// Hybrid stereo, the stereo side: the classification finds the pixels a depth step disoccludes and ranks them
// first, the budget picks whole bins from the top, and the GPU passes match the C++ reference.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

class HybridPassTest : public test::VulkanTest {};

// The GPUs' row group with a chunk every test device holds (lavapipe has 32 KiB of shared memory, the GPUs' chunk
// needs 48): the same code, its scans of the runs in parallel, only the chunk's length differs.
constexpr HybridRowShape kGpuGroupSmallChunk{S3D_HYBRID_GPU_ROW_GROUP, 512};

// Every row shape gives the same bins and masks: the CPU devices' (each invocation classifies its run alone, one
// chunk for a short row), the fallback (a few invocations share the slots and walk the runs), the GPUs' (many
// invocations scan them in parallel, one chunk for a short row; where the device holds it) or its group with a
// smaller chunk, a large group with small chunks (the parallel scan across several chunks of a row) and mask runs of
// three cells (a run cut by the row's end), and independent runs in many small chunks (each run's window reaching
// across its neighbours'). The mask pass runs one cell per invocation, or the CPU devices' run of cells.
std::vector<HybridRowShape> rowShapesToCheck(const vk::Context& context) {
  std::vector<HybridRowShape> shapes;
  for (HybridRowShape shape : {kHybridCpuRowShape, kHybridFallbackRowShape, kHybridGpuRowShape, kGpuGroupSmallChunk,
                               HybridRowShape{64, 128, false, 3}, HybridRowShape{8, 64, true}})
    if (hybridRowShapeFits(context, shape)) shapes.push_back(shape);
  EXPECT_GE(shapes.size(), 1u);
  return shapes;
}

std::string shapeName(HybridRowShape shape) {
  return "row group " + std::to_string(shape.rowGroup) + ", chunk " + std::to_string(shape.chunk) + ", mask run " +
         std::to_string(shape.maskRun);
}

// Every pixel its own cell: the row classification's definitions, pixel for pixel (the tests of cells say so).
StereoParameters parametersFor(float maxSeparation, int cell = 1) {
  StereoParameters parameters;
  parameters.maxSeparation = maxSeparation;
  parameters.zeroParallaxDistance = 1.0f;
  parameters.edgeCrop = 0.0f;
  parameters.hybridCell = cell;
  parameters.hybridScoreFloor = 0.0f;
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

// The definition (hybrid_shared.h) pixel by pixel: every pair of the edge-extended row tested against the pixel.
gpu::HybridCoverage directCoverage(const DepthImage& depth, int x, int y, Eye eye, const gpu::HybridConstants& c) {
  auto depthAt = [&](int column) {
    return gpu::sanitizedDepth(*depth.at(std::uint32_t(std::clamp(column, 0, c.width - 1)), std::uint32_t(y)),
                               c.zeroParallaxDistance);
  };
  const float direction = eye == Eye::Left ? 1.0f : -1.0f;
  const float eyeX = float(x);
  gpu::HybridCoverage coverage{false, INFINITY, 0.0f, 0.0f, INFINITY};
  for (int i = -c.windowPx; i <= c.width + c.windowPx - 2; ++i) {
    const float dA = depthAt(i), dB = depthAt(i + 1);
    const float pA = gpu::hybridParallaxPx(dA, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const float pB = gpu::hybridParallaxPx(dB, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const float landA = float(i) - direction * pA, landB = float(i + 1) - direction * pB;
    const gpu::HybridPairTerms terms = gpu::hybridPairTerms(gpu::hybridPair(landA, pA, dA, landB, pB, dB), eyeX);
    coverage.visibleParallaxPx = std::min(coverage.visibleParallaxPx, terms.coverParallaxPx);
    coverage.holeJumpPx = std::max(coverage.holeJumpPx, terms.holeJumpPx);
    coverage.edgeScore = std::max(coverage.edgeScore, terms.edgeScore);
    if (gpu::hybridSurfaceChange(dA, dB)) {
      const float lo = std::min(landA, landB), hi = std::max(landA, landB);
      coverage.nearestChangePx = std::min(coverage.nearestChangePx, std::max(std::max(lo - eyeX, eyeX - hi), 0.0f));
    }
  }
  coverage.covered = coverage.visibleParallaxPx < INFINITY;
  return coverage;
}

// Tolerance: none. The row scatter (each pair into the pixels it reaches, the nearest boundary from a prefix maximum
// and a suffix minimum) is the same float operations as testing every pair at every pixel, so it matches exactly;
// surfaces nearer than the zero-parallax plane (depth 0.3: parallax -2.3 times the sky's) land beyond the
// separation window, and variable block widths make holes, occlusions and spans of every size.
TEST(HybridClassification, TheRowScatterEqualsTestingEveryColumnPairAtEveryPixel) {
  const test::SyntheticView view = test::makeBlockView(150, 6, 11, 0.3f, 9, 1, true);
  for (float separation : {0.02f, 0.06f}) {
    const gpu::HybridConstants c = makeHybridConstants(parametersFor(separation), 150, 6);
    for (int y = 0; y < 6; ++y)
      for (const Eye eye : {Eye::Left, Eye::Right}) {
        const std::vector<gpu::HybridCoverage> row = hybridRowCoverageReference(view.depth, y, eye, c);
        for (int x = 0; x < 150; ++x) {
          const gpu::HybridCoverage expected = directCoverage(view.depth, x, y, eye, c);
          const gpu::HybridCoverage& got = row[std::size_t(x)];
          const std::string where = "separation " + std::to_string(separation) + " row " + std::to_string(y) +
                                    (eye == Eye::Left ? " left" : " right") + " pixel " + std::to_string(x);
          ASSERT_EQ(got.covered, expected.covered) << where;
          ASSERT_EQ(got.visibleParallaxPx, expected.visibleParallaxPx) << where;
          ASSERT_EQ(got.holeJumpPx, expected.holeJumpPx) << where;
          ASSERT_EQ(got.edgeScore, expected.edgeScore) << where;
          ASSERT_EQ(got.nearestChangePx, expected.nearestChangePx) << where;
        }
      }
  }
}

// Tolerance: none. The scatter writes a depth step's interior pixels (hybridPairInterior) without evaluating their
// terms, so every pixel there must get exactly the terms hybridPairTerms gives it: no cover, the step, the edge
// band's base. Checked for landings on, just off and between integers, both orders, far from zero and for a
// step within one surface (no edge band).
TEST(HybridClassification, AStepsInteriorPixelsHaveTheStepsTermsExactly) {
  const float fractions[] = {0.0f, 1e-6f, 0.25f, 0.5f, 0.5f - 1e-6f, 0.5f + 1e-6f, 0.999999f};
  int checkedPixels = 0;
  for (float origin : {-3.0f, 0.0f, 1917.0f, 70000.0f})
    for (float fractionA : fractions)
      for (float fractionB : fractions)
        for (float width : {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 37.0f})
          for (bool aFirst : {true, false})
            for (float depthB : {2.0f, 2.001f}) {  // another surface, or the same one (steps by the parallax alone)
              const float lo = origin + fractionA, hi = origin + width + fractionB;
              const float landA = aFirst ? lo : hi, landB = aFirst ? hi : lo;
              const gpu::HybridPair pair = gpu::hybridPair(landA, 3.0f, 2.0f, landB, 3.0f + width + 1.5f, depthB);
              const glm::vec2 interior = gpu::hybridPairInterior(pair);
              if (pair.span) {
                EXPECT_GT(interior.x, interior.y);
              }
              for (float x = interior.x; x <= interior.y; x += 1.0f, ++checkedPixels) {
                const gpu::HybridPairTerms terms = gpu::hybridPairTerms(pair, x);
                ASSERT_EQ(terms.coverParallaxPx, INFINITY) << "lo " << pair.lo << " hi " << pair.hi << " x " << x;
                ASSERT_EQ(terms.holeJumpPx, pair.jumpPx) << "x " << x;
                ASSERT_EQ(terms.edgeScore, pair.edgeBase) << "x " << x;
              }
            }
  EXPECT_GT(checkedPixels, 1000);
}

// A surface nearer than the zero-parallax plane lands on the far side of its columns, farther than the separation
// window (which bounds only the parallax behind the screen): the pixels it lands on still see it.
TEST(HybridClassification, ASurfaceInFrontOfTheScreenCoversWhereItLandsBeyondTheWindow) {
  DepthImage depth(200, 1, INFINITY);
  for (std::uint32_t x = 80; x < 100; ++x) *depth.at(x, 0) = 0.25f;  // parallax 0.05 x 200 x (1 - 4) = -30 px
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.05f), 200, 1);
  ASSERT_EQ(c.windowPx, 11);
  // Left eye: the block's columns land 30 px to their right, on eye pixels 110..129 (the sky there lands 10 px left).
  const std::vector<gpu::HybridCoverage> left = hybridRowCoverageReference(depth, 0, Eye::Left, c);
  for (int x : {112, 120, 128}) {
    EXPECT_TRUE(left[std::size_t(x)].covered) << "pixel " << x;
    EXPECT_FLOAT_EQ(left[std::size_t(x)].visibleParallaxPx, -30.0f) << "pixel " << x;
  }
  // Where the block's columns were, the sky from columns 30 px to the right shows through: no surface covers
  // pixels 70..89 (the sky's columns 80..99 were the block's, and the block left for 110..129).
  EXPECT_FALSE(left[85].covered);
  EXPECT_GT(hybridPixelScoreReference(depth, 85, 0, Eye::Left, c), 1.0f);
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

TEST(HybridBudget, TakesTheHighestScoresFirstAndMeetsTheBudgetBySplittingTheTiesOfOneBin) {
  HybridHistogram histogram{};
  histogram[0] = 500;
  histogram[3] = 40;
  histogram[200] = 10;
  // 2 % of 550 = 11: the top bin whole and one of bin 3's 40 pixels; 10 % = 55: both scored bins (50), and bin 0
  // (nothing expected wrong) is never split.
  const HybridThreshold two = hybridThreshold(histogram, 11);
  EXPECT_EQ(two.maskedPixels, 11u);
  EXPECT_GT(two.bin, 3);  // any bin in (3, 200] masks the same whole bins
  EXPECT_LE(two.bin, 200);
  EXPECT_EQ(two.splitBin, 3);
  EXPECT_EQ(two.splitPixels, 1u);
  const HybridThreshold ten = hybridThreshold(histogram, 55);
  EXPECT_EQ(ten.maskedPixels, 50u);
  EXPECT_EQ(ten.bin, 1);
  EXPECT_EQ(ten.splitBin, S3D_HYBRID_NO_PIXEL);
  EXPECT_EQ(ten.splitPixels, 0u);
  // The top bin does not fit whole: 5 of its 10 pixels.
  const HybridThreshold five = hybridThreshold(histogram, 5);
  EXPECT_EQ(five.maskedPixels, 5u);
  EXPECT_EQ(five.bin, 201);
  EXPECT_EQ(five.splitBin, 200);
  EXPECT_EQ(five.splitPixels, 5u);
  // A cap that ends exactly at a bin's edge splits nothing.
  const HybridThreshold exact = hybridThreshold(histogram, 10);
  EXPECT_EQ(exact.maskedPixels, 10u);
  EXPECT_EQ(exact.splitBin, S3D_HYBRID_NO_PIXEL);
}

TEST(HybridBudget, TheScoreFloorKeepsLowerBinsUnmaskedBelowBudgetOne) {
  HybridHistogram histogram{};
  histogram[0] = 500;
  histogram[3] = 40;
  histogram[200] = 10;
  // A floor at bin 4: bin 3 is never masked, however much of the cap is left; below the floor nothing splits.
  const HybridThreshold floored = hybridThreshold(histogram, 55, 4);
  EXPECT_EQ(floored.maskedPixels, 10u);
  EXPECT_GE(floored.bin, 4);
  EXPECT_LE(floored.bin, 200);
  EXPECT_EQ(floored.splitBin, S3D_HYBRID_NO_PIXEL);
  // Above the floor the cap splits as without one.
  const HybridThreshold five = hybridThreshold(histogram, 5, 4);
  EXPECT_EQ(five.splitBin, 200);
  EXPECT_EQ(five.splitPixels, 5u);
  // Budget 1 takes every pixel whatever the floor.
  EXPECT_EQ(hybridThreshold(histogram, 550, 4).bin, 0);
  EXPECT_EQ(hybridThreshold(histogram, 550, 4).maskedPixels, 550u);
  // Floors of 0 and 1 are no floor (bin 0 is never masked below budget 1 anyway).
  for (int minimumBin : {0, 1}) EXPECT_EQ(hybridThreshold(histogram, 55, minimumBin).maskedPixels, 50u);
}

TEST(HybridParameters, TheScoreFloorIsABinOfTheScoreAndRefusedOutsideItsRange) {
  StereoParameters p = parametersFor(0.05f);
  p.method = StereoMethod::Hybrid;
  p.hybridScoreFloor = 0.15f;
  EXPECT_EQ(makeHybridConstants(p, 64, 8).minimumBin, int(gpu::hybridScoreBin(0.15f)));
  p.hybridScoreFloor = 0.0f;
  EXPECT_EQ(makeHybridConstants(p, 64, 8).minimumBin, 0);
  for (float floor : {-0.1f, 40.0f, float(NAN)}) {
    p.hybridScoreFloor = floor;
    EXPECT_THROW(validate(p), std::invalid_argument) << floor;
  }
}

TEST(HybridMask, MarksTheBinsAtOrAboveTheThresholdInsideTheCropOnly) {
  StereoParameters parameters = parametersFor(0.1f);
  parameters.edgeCrop = 0.05f;  // 10 columns each side
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 2);
  std::vector<std::uint32_t> bins(400, 7);
  bins[50] = 3;
  HybridThreshold threshold;
  threshold.bin = 5;
  const std::vector<std::uint8_t> mask = hybridMaskReference(bins, threshold, c);
  EXPECT_EQ(mask[50], 0);
  EXPECT_EQ(mask[51], 1);
  EXPECT_EQ(mask[5], 0);    // cropped
  EXPECT_EQ(mask[195], 0);  // cropped
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 2 * 180 - 1);
}

TEST(HybridMask, TakesTheSplitBinsFirstPixelsInRasterOrderInsideTheCrop) {
  StereoParameters parameters = parametersFor(0.1f);
  parameters.edgeCrop = 0.05f;  // 10 columns each side
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 2);
  std::vector<std::uint32_t> bins(400, 1);
  for (std::size_t i : {5u, 20u, 30u, 205u, 220u}) bins[i] = 4;  // 5 and 205 are cropped
  bins[100] = 9;
  HybridThreshold threshold;
  threshold.bin = 5;
  threshold.splitBin = 4;
  threshold.splitPixels = 2;
  const std::vector<std::uint8_t> mask = hybridMaskReference(bins, threshold, c);
  EXPECT_EQ(mask[100], 1);  // above the threshold
  EXPECT_EQ(mask[20], 1);   // the split bin's first two inside the crop
  EXPECT_EQ(mask[30], 1);
  EXPECT_EQ(mask[220], 0);  // the third
  EXPECT_EQ(mask[5], 0);    // cropped
  EXPECT_EQ(mask[205], 0);
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 3);
}

TEST(HybridParameters, TheCellIsTwoPixelsFrom1280ColumnsUnlessGivenAndRefusedOutsideZeroToTwo) {
  StereoParameters p;
  p.method = StereoMethod::Hybrid;
  EXPECT_EQ(hybridCellFor(p, kHybridCellWidth - 1), 1);
  EXPECT_EQ(hybridCellFor(p, kHybridCellWidth), 2);
  EXPECT_EQ(makeHybridConstants(p, 1920, 8).cell, 2);
  for (int cell : {0, 1, 2}) {
    p.hybridCell = cell;
    EXPECT_NO_THROW(validate(p)) << cell;
  }
  p.hybridCell = 1;
  EXPECT_EQ(hybridCellFor(p, 1920), 1);
  for (int cell : {3, -2}) {
    p.hybridCell = cell;
    EXPECT_THROW(validate(p), std::invalid_argument) << cell;
  }
}

TEST(HybridGrid, ACellsDepthIsTheNearestOfItsPixelsAndTheLastRowAndColumnOfCellsArePartial) {
  DepthImage depth(5, 3, 4.0f);
  *depth.at(1, 1) = 2.0f;       // cell (0, 0)'s nearest
  *depth.at(2, 0) = NAN;        // no information: the zero-parallax distance (1), nearer than the rest
  *depth.at(4, 2) = INFINITY;   // the sky, alone in its partial cell (2, 1)
  *depth.at(4, 0) = 3.0f;       // cell (2, 0) holds column 4 of rows 0 and 1 only
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.05f, 2), 5, 3);
  const DepthImage grid = hybridGridDepthReference(depth, c);
  ASSERT_EQ(grid.width, 3u);
  ASSERT_EQ(grid.height, 2u);
  EXPECT_EQ(*grid.at(0, 0), 2.0f);
  EXPECT_EQ(*grid.at(1, 0), 1.0f);
  EXPECT_EQ(*grid.at(2, 0), 3.0f);
  EXPECT_EQ(*grid.at(0, 1), 4.0f);
  EXPECT_EQ(*grid.at(2, 1), INFINITY);
}

TEST(HybridGrid, TheGridsConstantsScaleTheSizeCropTapsAndCapAndTakeEveryCellAtBudgetOne) {
  StereoParameters parameters = parametersFor(0.1f, 2);
  parameters.edgeCrop = 0.055f;  // 11 columns each side: the crop [11, 189) touches cells 5 to 94
  parameters.method = StereoMethod::Hybrid;
  parameters.hybridBase = StereoMethod::Search;
  parameters.hybridBudget = 0.1f;
  const gpu::HybridConstants image = makeHybridConstants(parameters, 201, 7);
  const gpu::HybridConstants grid = hybridGridConstants(image);
  EXPECT_EQ(grid.cell, 1);
  EXPECT_EQ(grid.width, 101);
  EXPECT_EQ(grid.height, 4);
  EXPECT_EQ(grid.cropBegin, image.cropBegin / 2);
  EXPECT_EQ(grid.cropEnd, (image.cropEnd + 1) / 2);
  EXPECT_EQ(grid.windowPx, int(std::ceil(0.1f * 101.0f)) + 1);
  ASSERT_EQ(grid.baseTapCount, image.baseTapCount);
  for (int i = 0; i < grid.baseTapCount; ++i) EXPECT_EQ(grid.baseTapOffsetPx[i], (image.baseTapOffsetPx[i] + 1) / 2);
  const std::uint64_t cells = std::uint64_t(grid.cropEnd - grid.cropBegin) * 4;
  const std::uint64_t pixels = std::uint64_t(image.cropEnd - image.cropBegin) * 7;
  EXPECT_EQ(grid.maskedPixelCap, std::uint64_t(image.maskedPixelCap) * cells / pixels);
  parameters.hybridBudget = 1.0f;
  EXPECT_EQ(hybridGridConstants(makeHybridConstants(parameters, 201, 7)).maskedPixelCap, cells);
  EXPECT_EQ(hybridGridConstants(makeHybridConstants(parametersFor(0.1f, 1), 201, 7)).width, 201);  // cell 1: as is
}

TEST(HybridMask, ACellMasksItsPixelsInsideTheCropOnly) {
  StereoParameters parameters = parametersFor(0.1f, 2);
  parameters.edgeCrop = 0.055f;  // the crop [11, 189) of 200 columns: cells 5 and 94 are half inside
  const gpu::HybridConstants c = makeHybridConstants(parameters, 200, 3);
  ASSERT_EQ(c.cropBegin, 11);
  ASSERT_EQ(c.cropEnd, 189);
  const gpu::HybridConstants grid = hybridGridConstants(c);
  std::vector<std::uint32_t> bins(std::size_t(grid.width * grid.height), 0);
  bins[5] = bins[20] = bins[94] = 9;  // row 0 of cells: pixels rows 0 and 1
  bins[100 + 30] = 9;                 // row 1 of cells: pixel row 2 only
  HybridThreshold threshold;
  threshold.bin = 5;
  const std::vector<std::uint8_t> mask = hybridMaskReference(bins, threshold, c);
  auto at = [&](int x, int y) { return int(mask[std::size_t(y) * 200 + std::size_t(x)]); };
  EXPECT_EQ(at(10, 0), 0);  // cell 5's cropped column
  EXPECT_EQ(at(11, 0), 1);
  EXPECT_EQ(at(11, 1), 1);
  EXPECT_EQ(at(40, 0) + at(41, 0) + at(40, 1) + at(41, 1), 4);
  EXPECT_EQ(at(188, 1), 1);
  EXPECT_EQ(at(189, 1), 0);  // cell 94's cropped column
  EXPECT_EQ(at(60, 2) + at(61, 2), 2);
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 2 + 4 + 2 + 2);
}

// The GPU classification against the C++ reference in every row shape the device runs. Tolerance: a bin off by
// one in at most 1 pixel in 1000 (the GPU may round the parallax division differently in the last bit, which can
// move a score across a bin boundary); with no pixel off, the histograms are the same.
void expectClassificationMatchesTheReference(vk::Context& context, const DepthImage& depth, const gpu::HybridConstants& c) {
  const HybridClassification expected = classifyHybridReference(depth, c);
  for (HybridRowShape shape : rowShapesToCheck(context)) {
    SCOPED_TRACE(shapeName(shape));
    const HybridClassification gpu = classifyHybridOnGpu(context, depth, c, shape).classification;
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
}

// Tolerance: the GPU may round the parallax division differently in the last bit (Vulkan allows 2.5 ulp), which
// can move a score across a 1/8 px bin boundary; measured: identical on lavapipe.
TEST_F(HybridPassTest, ClassificationMatchesTheCppReferenceBinForBin) {
  const test::SyntheticView view = test::makeBlockView(160, 24, 7, 1.0f, 9, 4, true);
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.05f), 160, 24);
  expectClassificationMatchesTheReference(context(), view.depth, c);
}

// Tolerance: as above. On 2x2 cells of an image of odd size: the cells' depth on the GPU, then the same rows.
TEST_F(HybridPassTest, ClassificationOnCellsMatchesTheCppReference) {
  const test::SyntheticView view = test::makeBlockView(161, 25, 7, 1.0f, 9, 4, true);
  expectClassificationMatchesTheReference(context(), view.depth, makeHybridConstants(parametersFor(0.05f, 2), 161, 25));
}

// Tolerance: as above. A wider image classified in several chunks of a row, inside an edge crop, at a separation
// whose window and reach (surfaces at depth 0.35 land 1.9 windows away) exceed the chunk's shared span, so the
// shader reads part of its columns from the image.
TEST_F(HybridPassTest, ClassificationMatchesTheCppReferenceAcrossChunksCropAndFarReach) {
  const test::SyntheticView view = test::makeBlockView(700, 6, 5, 0.35f, 14, 1, true);
  StereoParameters parameters = parametersFor(0.08f);
  parameters.edgeCrop = 0.03f;
  parameters.method = StereoMethod::Search;
  parameters.searchTaps = 8;
  const gpu::HybridConstants c = makeHybridConstants(parameters, 700, 6);
  expectClassificationMatchesTheReference(context(), view.depth, c);
}

// The left eye's depth steps in row y whose interior the shader writes as a group (hybridPairInterior, at least
// S3D_HYBRID_SHARED_INTERIOR_PX pixels inside the image).
int queuedInteriors(const DepthImage& depth, int y, const gpu::HybridConstants& c) {
  int count = 0;
  for (int i = 0; i + 1 < c.width; ++i) {
    const float dA = gpu::sanitizedDepth(*depth.at(std::uint32_t(i), std::uint32_t(y)), c.zeroParallaxDistance);
    const float dB = gpu::sanitizedDepth(*depth.at(std::uint32_t(i + 1), std::uint32_t(y)), c.zeroParallaxDistance);
    const float pA = gpu::hybridParallaxPx(dA, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const float pB = gpu::hybridParallaxPx(dB, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const glm::vec2 interior =
        gpu::hybridPairInterior(gpu::hybridPair(float(i) - pA, pA, dA, float(i + 1) - pB, pB, dB));
    const float first = std::max(interior.x, 0.0f), last = std::min(interior.y, float(c.width - 1));
    count += last - first + 1.0f >= float(S3D_HYBRID_SHARED_INTERIOR_PX);
  }
  return count;
}

// Tolerance: as above. Posts 3 pixels wide at depth 1.5 (parallax 27 px) against the sky (82 px), their spacing
// varying by row, put more step interiors in one row than the row group queues to write together
// (S3D_HYBRID_INTERIOR_CAP): the rest are written by the invocation that found them, with the same bins.
TEST_F(HybridPassTest, ClassificationMatchesTheCppReferenceWhereARowHasMoreStepsThanTheGroupQueues) {
  DepthImage depth(1024, 3, INFINITY);
  for (std::uint32_t y = 0; y < depth.height; ++y)
    for (std::uint32_t x = 0; x < depth.width; ++x)
      if (x % (6 + y) < 3) *depth.at(x, y) = 1.5f;
  const gpu::HybridConstants c = makeHybridConstants(parametersFor(0.08f), 1024, 3);
  ASSERT_GT(queuedInteriors(depth, 0, c), S3D_HYBRID_INTERIOR_CAP);
  expectClassificationMatchesTheReference(context(), depth, c);
}

// The threshold and the masks follow from the GPU's own histogram exactly (integer math), at every budget, for
// cells of one pixel and of 2x2 with the score floor (an odd size, the crop across a cell).
TEST_F(HybridPassTest, ThresholdAndMasksMatchTheCppReferenceAtEveryBudget) {
  for (HybridRowShape shape : rowShapesToCheck(context())) {
    for (int cell : {1, 2}) {
      SCOPED_TRACE(shapeName(shape) + ", cell " + std::to_string(cell));
      const std::uint32_t width = 160 + std::uint32_t(cell) - 1, height = 24 + std::uint32_t(cell) - 1;
      const test::SyntheticView view = test::makeBlockView(width, height, 7, 1.0f, 9, 4, true);
      for (float budget : {0.0f, 0.01f, 0.05f, 0.2f, 0.5f, 0.99f, 1.0f}) {
        StereoParameters parameters = parametersFor(0.05f, cell);
        parameters.hybridBudget = budget;
        parameters.hybridScoreFloor = cell == 2 ? 0.15f : 0.0f;  // the defaults, floor included, on cells
        parameters.edgeCrop = cell == 2 ? 0.014f : 0.0f;  // an odd first column: a cell across the crop's edge
        const gpu::HybridConstants image = makeHybridConstants(parameters, width, height);
        const gpu::HybridConstants grid = hybridGridConstants(image);
        ASSERT_TRUE(cell == 1 || image.cropBegin % 2 == 1) << image.cropBegin;
        const HybridGpuResult gpu = classifyHybridOnGpu(context(), view.depth, image, shape);
        for (auto [histogram, threshold, bins, mask] :
             {std::tuple{&gpu.classification.leftHistogram, &gpu.leftThreshold, &gpu.classification.leftBins, &gpu.leftMask},
              std::tuple{&gpu.classification.rightHistogram, &gpu.rightThreshold, &gpu.classification.rightBins,
                         &gpu.rightMask}}) {
          const HybridThreshold expected = hybridThreshold(*histogram, grid.maskedPixelCap, grid.minimumBin);
          EXPECT_EQ(threshold->bin, expected.bin) << "budget " << budget;
          EXPECT_EQ(threshold->maskedPixels, expected.maskedPixels) << "budget " << budget;
          EXPECT_LE(threshold->maskedPixels, grid.maskedPixelCap);
          // The budget is met as closely as the cells scored at or above the floor allow (bin 0 and those below the
          // floor are rendered only at budget 1).
          const std::uint64_t classified = std::accumulate(histogram->begin(), histogram->end(), std::uint64_t(0));
          const std::uint64_t scored = std::accumulate(histogram->begin() + std::max(grid.minimumBin, 1),
                                                       histogram->end(), std::uint64_t(0));
          EXPECT_EQ(threshold->maskedPixels,
                    budget >= 1.0f ? classified : std::min<std::uint64_t>(grid.maskedPixelCap, scored))
              << "budget " << budget;
          EXPECT_EQ(threshold->splitBin, expected.splitBin) << "budget " << budget;
          EXPECT_EQ(threshold->splitPixels, expected.splitPixels) << "budget " << budget;
          EXPECT_EQ(*mask, hybridMaskReference(*bins, *threshold, image)) << "budget " << budget;
          if (cell == 1) {
            EXPECT_EQ(std::uint64_t(std::count(mask->begin(), mask->end(), 1)), expected.maskedPixels);
          }
        }
      }
    }
  }
}

// The split bin's share ends at one cell, which the threshold pass finds by scanning its row in runs of columns
// (one run per invocation): on a row of more cells than the pass has invocations each run holds several, and the
// masks still equal the reference's raster-order split.
TEST_F(HybridPassTest, TheSplitEndsAtTheReferencesCellOnARowWiderThanTheThresholdGroup) {
  const std::uint32_t width = 3 * S3D_HYBRID_THRESHOLD_GROUP + 37, height = 6;
  const test::SyntheticView view = test::makeBlockView(width, height, 5, 1.0f, 9, 3, true);
  int splits = 0;
  for (float budget : {0.03f, 0.1f, 0.3f, 0.6f}) {
    StereoParameters parameters = parametersFor(0.05f);
    parameters.hybridBudget = budget;
    const gpu::HybridConstants image = makeHybridConstants(parameters, width, height);
    const HybridGpuResult gpu = classifyHybridOnGpu(context(), view.depth, image, hybridRowShapeFor(context()));
    for (auto [threshold, bins, mask] : {std::tuple{&gpu.leftThreshold, &gpu.classification.leftBins, &gpu.leftMask},
                                         std::tuple{&gpu.rightThreshold, &gpu.classification.rightBins, &gpu.rightMask}}) {
      splits += threshold->splitPixels > 0 ? 1 : 0;
      EXPECT_EQ(*mask, hybridMaskReference(*bins, *threshold, image)) << "budget " << budget;
    }
  }
  EXPECT_GT(splits, 0) << "no budget split a bin: the row scan went untested";
}

TEST_F(HybridPassTest, ACpuDeviceGetsIndependentRunsAndAShapeBeyondTheDeviceIsRefused) {
  if (context().isCpuDevice()) {
    EXPECT_EQ(hybridRowShapeFor(context()), kHybridCpuRowShape);
    // lavapipe runs the fallback and the GPUs' row group too, so the tests above hold their code to the reference.
    EXPECT_TRUE(hybridRowShapeFits(context(), kHybridFallbackRowShape));
    EXPECT_TRUE(hybridRowShapeFits(context(), kGpuGroupSmallChunk));
  }
  EXPECT_TRUE(hybridRowShapeFits(context(), hybridRowShapeFor(context())));
  EXPECT_THROW(HybridPass(context(), HybridRowShape{1 << 20, 512}), std::invalid_argument);
  EXPECT_THROW(HybridPass(context(), HybridRowShape{16, 1 << 20}), std::invalid_argument);
  EXPECT_THROW(HybridPass(context(), HybridRowShape{16, 512, false, 0}), std::invalid_argument);
  // Independent runs split the chunk's private slots evenly: a chunk that is no multiple of the group is refused.
  EXPECT_THROW(HybridPass(context(), HybridRowShape{8, 100, true}), std::invalid_argument);
  // Shared slots give each eye half the group: an odd group is refused.
  EXPECT_THROW(HybridPass(context(), HybridRowShape{15, 256}), std::invalid_argument);
  EXPECT_NO_THROW(HybridPass(context(), HybridRowShape{14, 256}));
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
