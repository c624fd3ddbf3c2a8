// Row tiles (docs/DESIGN.md "Row tiles"): the tiled shaders read the run of a row and its margin from shared
// memory, and must return what the per-pixel shaders and the C++ references return, whatever the image width,
// separation or depth.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "s3d/stereo/iterative.h"
#include "s3d/stereo/iterative_pass.h"
#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/stereo.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

using test::largestChannelDifference;
using test::SyntheticView;

// Random color; depth in blocks of 1-9 columns, a quarter sky, some in front of the zero-parallax plane (whose
// seed parallax points beyond the margin, so the tiles' fallback color fetches run too).
SyntheticView makeView(std::uint32_t width, std::uint32_t height, unsigned seed) {
  return test::makeBlockView(width, height, seed, 0.6f, 9, 1, true);
}

// Widths around the tile (256): not a multiple of it, narrower than it, one pixel; the last separation's margin
// (0.25 * 1100 = 275 px, 277 with the filter) is wider than the tile, and the last one (527) does not fit the
// shared arrays, so RowTiles runs per pixel there.
const std::tuple<std::uint32_t, std::uint32_t, float> kCases[] = {
    {300, 3, 0.05f}, {37, 2, 0.1f}, {1, 1, 0.02f}, {513, 2, 0.02f}, {1100, 2, 0.25f}, {2100, 1, 0.25f}};

TEST(StereoRowTiles, TheMarginCoversTheTapsAndTheSkysDisplacementWithTheFilterTexel) {
  StereoParameters parameters{0.02f, 1.0f, -1.0f};  // 38.4 px at 1920
  EXPECT_EQ(rowTileMargin(makeSeedConstants(parameters, 1920, 1080)), 41);  // ceil(38.4) + 2
  EXPECT_EQ(rowTileMargin(makeIterativeConstants(parameters, 2, 1920, 1080)), 41);
  gpu::StereoConstants c = makeSeedConstants(parameters, 1920, 1080);
  c.tapOffsetPx[1] = 60;  // a tap beyond the sky's displacement widens it
  EXPECT_EQ(rowTileMargin(c), 60);
}

TEST(StereoRowTiles, RowTilesAreOptInAndOnlyWhereTheMarginFitsTheSharedArrays) {
  // Auto is per pixel: row tiles were slower on lavapipe and on an H100 (stereo.h).
  EXPECT_FALSE(usesRowTiles(StereoKernel::Auto, S3D_STEREO_ROW_TILE_MARGIN, false));
  EXPECT_FALSE(usesRowTiles(StereoKernel::Auto, S3D_STEREO_ROW_TILE_MARGIN, true));
  EXPECT_TRUE(usesRowTiles(StereoKernel::RowTiles, S3D_STEREO_ROW_TILE_MARGIN, true));
  EXPECT_FALSE(usesRowTiles(StereoKernel::RowTiles, S3D_STEREO_ROW_TILE_MARGIN + 1, false));
  EXPECT_FALSE(usesRowTiles(StereoKernel::PerPixel, 1, false));
  EXPECT_EQ(parseStereoKernel("tiles"), StereoKernel::RowTiles);
  EXPECT_THROW(parseStereoKernel("blocks"), std::invalid_argument);
}

class StereoRowTilesGpu : public test::VulkanTest {};

TEST_F(StereoRowTilesGpu, SeedAndSearchMatchTheCppReferenceWithinOneLevelOnBothKernels) {
  // Tolerance 1 level of 8 bits, as for the per-pixel pass: the filter's multiply-add and the unorm store may
  // round differently from std::lround; taps, minimum and crop are integer-exact on both kernels.
  for (auto [width, height, separation] : kCases)
    for (StereoKernel kernel : {StereoKernel::PerPixel, StereoKernel::RowTiles})
      for (int taps : {0, S3D_STEREO_MAX_TAPS}) {  // 0: the seed
        SyntheticView view = makeView(width, height, width + unsigned(taps));
        StereoParameters parameters{separation, 2.0f, -1.0f};
        if (taps > 0) {
          parameters.method = StereoMethod::Search;
          parameters.searchTaps = taps;
        }
        gpu::StereoConstants c = makeStereoConstants(parameters, width, height);
        StereoPair expected = synthesizeStereoReference(view.color, view.depth, c);
        StereoPair actual = synthesizeStereoOnGpu(context(), view.color, view.depth, c, kernel);
        EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1) << width << " " << separation << " " << kernelName(kernel) << " " << taps;
        EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1) << width << " " << separation << " " << kernelName(kernel) << " " << taps;
      }
}

TEST_F(StereoRowTilesGpu, IterativeMatchesTheCppReferenceWithinOneLevelAndFillsTheSamePixels) {
  // Color within 1 level (the filter's rounding, as above); the fill mark (alpha 0) is a decision on identical
  // floats on both sides, so it matches exactly.
  for (auto [width, height, separation] : kCases)
    for (StereoKernel kernel : {StereoKernel::PerPixel, StereoKernel::RowTiles}) {
      SyntheticView view = makeView(width, height, width + 1);
      for (std::size_t i = 3; i < view.color.pixels.size(); i += 4) view.color.pixels[i] = 255;
      gpu::IterativeConstants c = makeIterativeConstants(StereoParameters{separation, 2.0f, -1.0f}, 3, width, height);
      StereoPair expected = synthesizeIterativeReference(view.color, view.depth, c);
      StereoPair actual = synthesizeIterativeOnGpu(context(), view.color, view.depth, c, kernel);
      EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1) << width << " " << separation << " " << kernelName(kernel);
      EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1) << width << " " << separation << " " << kernelName(kernel);
      for (std::size_t i = 3; i < expected.left.pixels.size(); i += 4) {
        ASSERT_EQ(actual.left.pixels[i] == 0, expected.left.pixels[i] == 0) << width << " " << separation << " " << i / 4;
        ASSERT_EQ(actual.right.pixels[i] == 0, expected.right.pixels[i] == 0) << width << " " << separation << " " << i / 4;
      }
    }
}

TEST_F(StereoRowTilesGpu, ZeroSeparationReproducesTheCenterViewBitForBitForEveryMethod) {
  SyntheticView view = makeView(300, 3, 5);
  const StereoParameters parameters{0.0f, 2.0f, 0.0f};
  StereoParameters search = parameters;
  search.method = StereoMethod::Search;
  search.searchTaps = 8;
  for (const StereoPair& pair :
       {synthesizeStereoOnGpu(context(), view.color, view.depth, makeStereoConstants(parameters, 300, 3), StereoKernel::RowTiles),
        synthesizeStereoOnGpu(context(), view.color, view.depth, makeStereoConstants(search, 300, 3), StereoKernel::RowTiles),
        synthesizeIterativeOnGpu(context(), view.color, view.depth,
                                 makeIterativeConstants(parameters, kDefaultIterations, 300, 3), StereoKernel::RowTiles)}) {
    EXPECT_EQ(pair.left.pixels, view.color.pixels);
    EXPECT_EQ(pair.right.pixels, view.color.pixels);
  }
}

TEST_F(StereoRowTilesGpu, FlatDepthTilesTakeTheShortcutToTheReferencesResult) {
  // A flat tile (its min depth equals its max) skips the taps and the iterations: the result must still be the
  // reference's. Row 0 is sky, row 1 a flat wall in front of the screen; row 2 is flat except one near texel,
  // which makes its tiles search normally. Tolerance 1 level (the filter's rounding); no pixel is filled.
  const std::uint32_t width = 600, height = 3;
  SyntheticView view = makeView(width, height, 9);
  for (std::size_t i = 3; i < view.color.pixels.size(); i += 4) view.color.pixels[i] = 255;
  for (std::uint32_t x = 0; x < width; ++x) {
    *view.depth.at(x, 0) = INFINITY;
    *view.depth.at(x, 1) = 1.5f;
    *view.depth.at(x, 2) = x == 300 ? 0.8f : 3.0f;
  }
  const StereoParameters parameters{0.04f, 2.0f, -1.0f};
  gpu::StereoConstants seed = makeStereoConstants(parameters, width, height);
  StereoPair seedExpected = synthesizeStereoReference(view.color, view.depth, seed);
  StereoPair seedActual = synthesizeStereoOnGpu(context(), view.color, view.depth, seed, StereoKernel::RowTiles);
  EXPECT_LE(largestChannelDifference(seedActual.left, seedExpected.left), 1);
  EXPECT_LE(largestChannelDifference(seedActual.right, seedExpected.right), 1);
  gpu::IterativeConstants iterative = makeIterativeConstants(parameters, 2, width, height);
  StereoPair expected = synthesizeIterativeReference(view.color, view.depth, iterative);
  StereoPair actual = synthesizeIterativeOnGpu(context(), view.color, view.depth, iterative, StereoKernel::RowTiles);
  EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1);
  EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1);
  for (std::uint32_t x = std::uint32_t(iterative.cropBegin); x < std::uint32_t(iterative.cropEnd); ++x) {
    EXPECT_EQ(actual.left.at(x, 0)[3], 255) << x;
    EXPECT_EQ(actual.left.at(x, 1)[3], 255) << x;
  }
}

}  // namespace
}  // namespace s3d::stereo
