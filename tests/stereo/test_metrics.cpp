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


ImageRGBA8 grayImage(std::uint32_t width, std::uint32_t height, std::uint8_t level) {
  ImageRGBA8 image(width, height, level);
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  return image;
}

TEST(Ssim, IdenticalImagesGiveExactlyOne) {
  // x = y makes the two factors of SSIM equal numerator and denominator term by term: exactly 1, even with
  // rounding in the moments. Gradient display image, cropped and not, and an HDR image with highlights.
  const ImageRGBA8 image = gradientImage(13, 9);
  for (std::uint32_t crop : {0u, 3u}) {
    EXPECT_EQ(compareDisplayImages(image, image, crop).ssim, 1.0) << crop;
    for (float value : ssimMap(image, image, crop)) EXPECT_TRUE(value == 1.0f || value == 0.0f);
  }
  ImageRGBA32F hdr(7, 5);
  for (std::size_t i = 0; i < hdr.pixels.size(); ++i) hdr.pixels[i] = float(i % 11) * 0.7f;
  EXPECT_EQ(compareHdrImages(hdr, hdr, 1).ssim, 1.0);
}

TEST(Ssim, UniformOffsetMatchesTheLuminanceTerm) {
  // Gray 100 against gray 110: no variance, so SSIM = (2 * 100 * 110 + C1) / (100^2 + 110^2 + C1) with
  // C1 = (0.01 * 255)^2 = 6.5025: 22006.5025 / 22106.5025 = 0.995476444. Tolerance 1e-7: the SSIM map is
  // stored as float (6e-8 relative); the moments themselves are double.
  const ErrorStats stats = compareDisplayImages(grayImage(6, 4, 110), grayImage(6, 4, 100), 0);
  EXPECT_NEAR(stats.ssim, 22006.5025 / 22106.5025, 1e-7);
}

TEST(Ssim, SwappedPairMatchesTheHandComputedWindowMoments) {
  // A 2x1 image [a, b] against [b, a] (a = 50, b = 200): the window is cut to the two pixels, weights 1
  // (self) and w = exp(-1 / (2 * 1.5^2)) (neighbour), renormalized to p = 1 / (1 + w), q = w / (1 + w).
  // Then mu_x = p a + q b, mu_y = p b + q a, sigma_x^2 = sigma_y^2 = p q (a - b)^2 = -sigma_xy, and
  // SSIM = (2 mu_x mu_y + C1)(C2 - 2 p q (a - b)^2) / ((mu_x^2 + mu_y^2 + C1)(C2 + 2 p q (a - b)^2))
  // = -0.98083843 at both pixels (perfect anti-correlation). Tolerance 1e-7: the map is stored as float.
  const double a = 50.0, b = 200.0, w = std::exp(-1.0 / 4.5), p = 1.0 / (1.0 + w), q = w / (1.0 + w);
  const double c1 = 6.5025, c2 = 58.5225, variance = p * q * (a - b) * (a - b);
  const double muX = p * a + q * b, muY = p * b + q * a;
  const double expected = (2.0 * muX * muY + c1) * (c2 - 2.0 * variance) / ((muX * muX + muY * muY + c1) * (c2 + 2.0 * variance));
  ImageRGBA8 x = grayImage(2, 1, 50), y = grayImage(2, 1, 200);
  for (int c = 0; c < 3; ++c) x.at(1, 0)[c] = 200, y.at(1, 0)[c] = 50;
  EXPECT_NEAR(compareDisplayImages(x, y, 0).ssim, expected, 1e-7);
  EXPECT_NEAR(expected, -0.98083843, 1e-8);  // the value written above, from the formula
}

TEST(Ssim, WorksOnAOneByOneImage) {
  // The window cut to one pixel: the luminance term alone, as for the uniform offset.
  EXPECT_NEAR(compareDisplayImages(grayImage(1, 1, 110), grayImage(1, 1, 100), 0).ssim, 22006.5025 / 22106.5025, 1e-7);
}

TEST(CompareHdrImages, KnownOffsetGivesItsPsnrAndMeanAbsoluteError) {
  // Every R, G, B 0.01 above the reference: MSE = 1e-4, PSNR = 10 log10(1 / 1e-4) = 40 dB against the peak
  // 1.0; MAE 0.01. Tolerance 1e-4 dB / 1e-7: 0.51f - 0.5f is 0.01 only to float precision.
  ImageRGBA32F reference(5, 3, 0.5f), synthesized(5, 3, 0.51f);
  for (std::size_t i = 3; i < reference.pixels.size(); i += 4) reference.pixels[i] = 1.0f, synthesized.pixels[i] = 7.0f;
  const HdrErrorStats stats = compareHdrImages(synthesized, reference, 1);
  EXPECT_NEAR(stats.psnrDb, 40.0, 1e-4);
  EXPECT_NEAR(stats.meanAbsoluteError, 0.01, 1e-7);
  EXPECT_EQ(stats.pixelCount, 9u);  // 3 of 5 columns after cropping 1 each side, alpha ignored
  EXPECT_EQ(compareHdrImages(reference, reference, 0).psnrDb, kMaxPsnrDb);
}

TEST(CompareByRegion, RestIsThePixelsInNoRegionAndAnEmptyMaskIsAnEmptyRegion) {
  // 4x1: pixel 0 halo, pixel 1 disocclusion and transparent, pixels 2 and 3 the rest.
  const ImageRGBA8 reference = gradientImage(4, 1);
  const RegionMasks masks{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 1, 0, 0}};
  const ErrorsByRegion<ErrorStats> display = compareDisplayByRegion(reference, reference, 0, masks);
  EXPECT_EQ(display.all.pixelCount, 4u);
  EXPECT_EQ(display.halo.pixelCount, 1u);
  EXPECT_EQ(display.disocclusion.pixelCount, 1u);
  EXPECT_EQ(display.transparent.pixelCount, 1u);
  EXPECT_EQ(display.rest.pixelCount, 2u);
  const ErrorsByRegion<ErrorStats> noTransparent =
      compareDisplayByRegion(reference, reference, 0, RegionMasks{masks.halo, masks.disocclusion, {}});
  EXPECT_EQ(noTransparent.transparent.pixelCount, 0u);
  EXPECT_EQ(noTransparent.rest.pixelCount, 2u);
  ImageRGBA32F hdr(4, 1, 0.25f), brighter(4, 1, 0.25f);
  brighter.at(3, 0)[0] = 1.25f;  // one rest pixel off by 1 in red
  const ErrorsByRegion<HdrErrorStats> hdrErrors = compareHdrByRegion(brighter, hdr, 0, masks);
  EXPECT_EQ(hdrErrors.halo.psnrDb, kMaxPsnrDb);
  EXPECT_NEAR(hdrErrors.rest.meanAbsoluteError, 1.0 / 6.0, 1e-12);  // 1 of 6 samples
  EXPECT_LT(hdrErrors.rest.ssim, 1.0);
}

TEST(CompareByRegion, TheFoliageRegionIsCountedAndLeftOutOfTheRest) {
  // 4x1: pixel 0 halo, pixel 2 foliage (an alpha cut-out's pixel), pixels 1 and 3 the rest; without a foliage
  // mask the region is empty and pixel 2 is rest again.
  const ImageRGBA8 reference = gradientImage(4, 1);
  RegionMasks masks{{1, 0, 0, 0}, {}, {}, {0, 0, 1, 0}};
  const ErrorsByRegion<ErrorStats> display = compareDisplayByRegion(reference, reference, 0, masks);
  EXPECT_EQ(display.foliage.pixelCount, 1u);
  EXPECT_EQ(display.rest.pixelCount, 2u);
  EXPECT_EQ(compareHdrByRegion(ImageRGBA32F(4, 1, 0.5f), ImageRGBA32F(4, 1, 0.5f), 0, masks).foliage.pixelCount, 1u);
  masks.foliage.clear();
  const ErrorsByRegion<ErrorStats> none = compareDisplayByRegion(reference, reference, 0, masks);
  EXPECT_EQ(none.foliage.pixelCount, 0u);
  EXPECT_EQ(none.rest.pixelCount, 3u);
}

}  // namespace
}  // namespace s3d::stereo
