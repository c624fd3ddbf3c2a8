// The temporal flicker metric: zero without change in the error, the error's change where it comes and goes.
#include <gtest/gtest.h>

#include "s3d/stereo/temporal.h"

namespace s3d::stereo {
namespace {

ImageRGBA8 ramp(std::uint32_t width, std::uint32_t height, int offset) {
  ImageRGBA8 image(width, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y)[c] = std::uint8_t(10 + 5 * x + 7 * y + 3 * c + offset);
  return image;
}

TEST(TemporalFlicker, IsZeroForIdenticalFrames) {
  const ImageRGBA8 eye = ramp(12, 5, 0), reference = ramp(12, 5, 40);  // a large but static error
  const FlickerStats stats = temporalFlicker(eye, eye, reference, reference, 0, std::vector<std::uint8_t>(60, 1), {});
  EXPECT_EQ(stats.all.meanLevels, 0.0);
  EXPECT_EQ(stats.all.pixelCount, 60u);
  EXPECT_EQ(stats.halo.meanLevels, 0.0);
  EXPECT_EQ(stats.disocclusion.pixelCount, 0u);
}

TEST(TemporalFlicker, IsZeroForAnExactMethodUnderMotion) {
  // The reference changes (the camera moved); an eye equal to it changes alike.
  const ImageRGBA8 before = ramp(12, 5, 0), after = ramp(12, 5, 9);
  EXPECT_EQ(temporalFlicker(after, before, after, before, 0, {}, {}).all.meanLevels, 0.0);
}

TEST(TemporalFlicker, MeasuresAnErrorThatComesAndGoesPerRegion) {
  // A static reference; the eye gains +12 levels on every channel in the left half of the frame only.
  const ImageRGBA8 reference = ramp(12, 5, 0);
  ImageRGBA8 flickering = reference;
  std::vector<std::uint8_t> halo(60, 0), disocclusion(60, 0);
  for (std::uint32_t y = 0; y < 5; ++y)
    for (std::uint32_t x = 0; x < 6; ++x) {
      for (int c = 0; c < 3; ++c) flickering.at(x, y)[c] = std::uint8_t(flickering.at(x, y)[c] + 12);
      halo[y * 12 + x] = 1;
    }
  for (std::uint32_t y = 0; y < 5; ++y) disocclusion[y * 12 + 9] = 1;  // a column that did not flicker
  const FlickerStats stats = temporalFlicker(flickering, reference, reference, reference, 0, halo, disocclusion);
  EXPECT_DOUBLE_EQ(stats.all.meanLevels, 6.0);  // half the pixels by 12
  EXPECT_DOUBLE_EQ(stats.halo.meanLevels, 12.0);
  EXPECT_EQ(stats.halo.pixelCount, 30u);
  EXPECT_EQ(stats.disocclusion.meanLevels, 0.0);
  // The crop leaves columns 2..9: 4 of their 8 columns flicker.
  EXPECT_DOUBLE_EQ(temporalFlicker(flickering, reference, reference, reference, 2, {}, {}).all.meanLevels, 6.0);
  EXPECT_EQ(temporalFlicker(flickering, reference, reference, reference, 2, {}, {}).all.pixelCount, 40u);
}

TEST(TemporalFlicker, RejectsImagesOfDifferentSizes) {
  const ImageRGBA8 a = ramp(4, 4, 0), b = ramp(5, 4, 0);
  EXPECT_THROW((void)temporalFlicker(a, a, b, b, 0, {}, {}), std::invalid_argument);
  EXPECT_THROW((void)temporalFlicker(a, a, a, a, 0, std::vector<std::uint8_t>(3), {}), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::stereo
