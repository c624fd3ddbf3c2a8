// Error statistics between a synthesized eye view and its reference rendering.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "s3d/stereo/metrics.h"

namespace s3d::stereo {
namespace {

ImageRGBA8 gradientImage(std::uint32_t width, std::uint32_t height) {
  ImageRGBA8 image(width, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = static_cast<std::uint8_t>(40 * x);
      p[1] = static_cast<std::uint8_t>(30 * y);
      p[2] = 100;
      p[3] = 255;
    }
  return image;
}

TEST(CompareDisplayImages, IdenticalImagesGiveCappedPsnrAndNoError) {
  const ImageRGBA8 image = gradientImage(4, 4);
  const ErrorStats stats = compareDisplayImages(image, image, 0);
  EXPECT_EQ(stats.psnrDb, kMaxPsnrDb);
  EXPECT_EQ(stats.meanAbsoluteError, 0.0);
  EXPECT_EQ(stats.shareAbove8, 0.0);
  EXPECT_EQ(stats.pixelCount, 16u);
}

TEST(CompareDisplayImages, SinglePixelErrorMatchesHandComputation) {
  // 4x4 image, one red channel off by 20 levels: 48 samples.
  // MSE = 400/48 = 8.3333; PSNR = 10*log10(65025 / 8.3333) = 10*log10(7803) = 38.9226 dB.
  // MAE = 20/48 = 0.416667; share = 1/16 = 0.0625 (20 > 8). Tolerance 1e-4: hand values are rounded.
  const ImageRGBA8 reference = gradientImage(4, 4);
  ImageRGBA8 synthesized = reference;
  synthesized.at(2, 1)[0] = static_cast<std::uint8_t>(synthesized.at(2, 1)[0] + 20);
  const ErrorStats stats = compareDisplayImages(synthesized, reference, 0);
  EXPECT_NEAR(stats.psnrDb, 38.9226, 1e-4);
  EXPECT_NEAR(stats.meanAbsoluteError, 0.416667, 1e-4);
  EXPECT_DOUBLE_EQ(stats.shareAbove8, 0.0625);
  EXPECT_EQ(stats.pixelCount, 16u);
}

TEST(CompareDisplayImages, DifferenceOfExactlyEightLevelsIsNotCountedAbove8) {
  const ImageRGBA8 reference = gradientImage(2, 1);
  ImageRGBA8 synthesized = reference;
  synthesized.at(0, 0)[2] = static_cast<std::uint8_t>(synthesized.at(0, 0)[2] + 8);
  synthesized.at(1, 0)[2] = static_cast<std::uint8_t>(synthesized.at(1, 0)[2] + 9);
  EXPECT_DOUBLE_EQ(compareDisplayImages(synthesized, reference, 0).shareAbove8, 0.5);
}

TEST(CompareDisplayImages, AlphaDifferencesAreIgnored) {
  const ImageRGBA8 reference = gradientImage(3, 3);
  ImageRGBA8 synthesized = reference;
  synthesized.at(1, 1)[3] = 0;
  EXPECT_EQ(compareDisplayImages(synthesized, reference, 0).psnrDb, kMaxPsnrDb);
}

TEST(CompareDisplayImages, CropExcludesEdgeColumns) {
  // Errors only in the first and last column: cropping one column on each side hides them.
  const ImageRGBA8 reference = gradientImage(5, 3);
  ImageRGBA8 synthesized = reference;
  for (std::uint32_t y = 0; y < 3; ++y) {
    synthesized.at(0, y)[1] = 255;
    synthesized.at(4, y)[1] = 255;
  }
  EXPECT_LT(compareDisplayImages(synthesized, reference, 0).psnrDb, kMaxPsnrDb);
  const ErrorStats cropped = compareDisplayImages(synthesized, reference, 1);
  EXPECT_EQ(cropped.psnrDb, kMaxPsnrDb);
  EXPECT_EQ(cropped.meanAbsoluteError, 0.0);
  EXPECT_EQ(cropped.pixelCount, 9u);  // columns 1..3 of 3 rows
}

TEST(CompareDisplayImages, CropLeavingNoColumnsThrows) {
  const ImageRGBA8 image = gradientImage(4, 2);
  EXPECT_THROW(compareDisplayImages(image, image, 2), std::invalid_argument);
  EXPECT_THROW(compareDisplayImages(image, image, 0xFFFFFFFFu), std::invalid_argument);  // no wrap-around
}

TEST(CompareDisplayImages, DifferentSizesThrow) {
  EXPECT_THROW(compareDisplayImages(gradientImage(4, 2), gradientImage(4, 3), 0), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::stereo

namespace s3d::stereo {
namespace {

TEST(HaloMask, MarksColumnsWithinTheRadiusOfADepthEdge) {
  DepthImage depth(20, 1, 10.0f);
  for (std::uint32_t x = 10; x < 20; ++x) *depth.at(x, 0) = 2.0f;  // edge between columns 9 and 10
  std::vector<std::uint8_t> mask = haloMask(depth, 3);
  for (std::uint32_t x = 0; x < 20; ++x) EXPECT_EQ(mask[x], (x >= 7 && x < 13) ? 1 : 0) << x;
}

TEST(HaloMask, SkyAgainstASurfaceIsAnEdgeAndSkyAgainstSkyIsNot) {
  DepthImage depth(10, 1, INFINITY);
  *depth.at(9, 0) = 5.0f;
  std::vector<std::uint8_t> mask = haloMask(depth, 1);
  EXPECT_EQ(mask[0], 0);
  EXPECT_EQ(mask[8], 1);
  EXPECT_EQ(mask[9], 1);
}

TEST(RegionErrors, SplitTheErrorBetweenHaloAndRest) {
  ImageRGBA8 reference(4, 1, 100), synthesized(4, 1, 100);
  synthesized.at(1, 0)[0] = 120;  // one error, inside the halo
  std::vector<std::uint8_t> halo = {0, 1, 1, 0};
  RegionErrors errors = compareByRegion(synthesized, reference, 0, halo);
  EXPECT_EQ(errors.halo.pixelCount, 2u);
  EXPECT_EQ(errors.rest.pixelCount, 2u);
  EXPECT_DOUBLE_EQ(errors.rest.psnrDb, kMaxPsnrDb);
  EXPECT_LT(errors.halo.psnrDb, errors.all.psnrDb);  // the same error over fewer pixels
}

TEST(RegionErrors, AnEmptyRegionReportsNoPixelsAndNoError) {
  ImageRGBA8 image(4, 1, 100);
  RegionErrors errors = compareByRegion(image, image, 0, std::vector<std::uint8_t>(4, 0));
  EXPECT_EQ(errors.halo.pixelCount, 0u);
  EXPECT_DOUBLE_EQ(errors.halo.meanAbsoluteError, 0.0);
}

}  // namespace
}  // namespace s3d::stereo

namespace s3d::stereo {
namespace {

TEST(ErrorHeatMap, IdenticalImagesAreBlackAndFullScaleIsWhite) {
  ImageRGBA8 reference(6, 1, 100), synthesized(6, 1, 100);
  synthesized.at(2, 0)[1] = 100 + 32;  // full scale: 32 levels
  synthesized.at(3, 0)[0] = 100 + 16;  // half scale: red (the ramp's midpoint)
  ImageRGBA8 heat = makeErrorHeatMap(synthesized, reference, 1);
  EXPECT_EQ(heat.at(1, 0)[0] + heat.at(1, 0)[1] + heat.at(1, 0)[2], 0);
  EXPECT_EQ(heat.at(2, 0)[0], 255);
  EXPECT_EQ(heat.at(2, 0)[1], 255);
  EXPECT_EQ(heat.at(2, 0)[2], 255);
  EXPECT_EQ(heat.at(3, 0)[0], 255);
  EXPECT_EQ(heat.at(3, 0)[1], 0);
  EXPECT_EQ(heat.at(3, 0)[2], 0);
}

TEST(ErrorHeatMap, CroppedColumnsStayBlack) {
  ImageRGBA8 reference(6, 1, 0), synthesized(6, 1, 255);
  ImageRGBA8 heat = makeErrorHeatMap(synthesized, reference, 2);
  EXPECT_EQ(heat.at(0, 0)[0], 0);
  EXPECT_EQ(heat.at(5, 0)[0], 0);
  EXPECT_EQ(heat.at(2, 0)[0], 255);
}

}  // namespace
}  // namespace s3d::stereo

namespace s3d::stereo {
namespace {

TEST(DisocclusionMask, BackgroundHiddenBehindABoxInTheCenterViewIsUnseen) {
  // Center: a box at the zero-parallax plane (parallax 0) over sky; sky moves by 0.1 * 20 = 2 px.
  // The left eye's sky pixel x shows center content from x + 2: at x = 6, 7 that is the box, so the
  // center never saw that background; x = 18, 19 reproject outside the image.
  DepthImage center(20, 1, INFINITY);
  for (std::uint32_t x = 8; x < 12; ++x) *center.at(x, 0) = 1.0f;
  DepthImage leftReference = center;  // the box stays put (zero parallax); the sky is sky
  std::vector<std::uint8_t> mask = disocclusionMask(leftReference, center, 0.1f, 1.0f, Eye::Left);
  for (std::uint32_t x = 0; x < 20; ++x) {
    const bool unseen = x == 6 || x == 7 || x >= 18;
    EXPECT_EQ(mask[x], unseen ? 1 : 0) << x;
  }
}

TEST(DisocclusionMask, EverythingOnTheZeroParallaxPlaneIsSeen) {
  DepthImage depth(10, 2, 2.0f);
  std::vector<std::uint8_t> mask = disocclusionMask(depth, depth, 0.05f, 2.0f, Eye::Right);
  for (std::uint8_t value : mask) EXPECT_EQ(value, 0);
}

}  // namespace
}  // namespace s3d::stereo
