// The HUD crosshair: drawn where asked, clipped at the borders, displaced per eye by its parallax.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>

#include "s3d/hud/crosshair.h"

namespace s3d::hud {
namespace {

bool touched(const ImageRGBA8& image, std::uint32_t x, std::uint32_t y) {
  const std::uint8_t* p = image.at(x, y);
  return p[0] || p[1] || p[2] || p[3];
}

bool hasColor(const ImageRGBA8& image, std::uint32_t x, std::uint32_t y, const std::array<std::uint8_t, 4>& color) {
  const std::uint8_t* p = image.at(x, y);
  return p[0] == color[0] && p[1] == color[1] && p[2] == color[2] && p[3] == color[3];
}

std::size_t touchedCount(const ImageRGBA8& image) {
  std::size_t count = 0;
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) count += touched(image, x, y);
  return count;
}

TEST(Crosshair, ArmsCarryTheColorAroundTheCenter) {
  ImageRGBA8 image(64, 64);
  const CrosshairStyle style;
  drawCrosshair(image, 32.0f, 32.0f, style);
  const std::uint32_t firstArmPixel = 32 + std::uint32_t(style.gapPx) + 1;
  EXPECT_TRUE(hasColor(image, firstArmPixel, 32, style.color));       // right arm
  EXPECT_TRUE(hasColor(image, 32, firstArmPixel, style.color));       // lower arm
  EXPECT_TRUE(hasColor(image, 64 - firstArmPixel, 32, style.color));  // left arm
  EXPECT_TRUE(hasColor(image, 32, 64 - firstArmPixel, style.color));  // upper arm
  EXPECT_FALSE(touched(image, 32, 32));                               // the center pixel stays clear
}

TEST(Crosshair, DrawsNothingFarFromTheCenter) {
  ImageRGBA8 image(64, 64);
  const CrosshairStyle style;
  drawCrosshair(image, 32.0f, 32.0f, style);
  // Everything drawn lies within gap + arm + 1 px of outline of the center, in a plus shape.
  const int reach = style.gapPx + style.armLengthPx + 1;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) {
      const int dx = int(x) - 32, dy = int(y) - 32;
      const bool inPlus = (std::abs(dx) <= reach && std::abs(dy) <= 2) || (std::abs(dy) <= reach && std::abs(dx) <= 2);
      if (!inPlus) {
        EXPECT_FALSE(touched(image, x, y)) << "at " << x << ", " << y;
      }
    }
}

TEST(Crosshair, FractionalCenterIsRoundedToTheNearestPixel) {
  ImageRGBA8 rounded(64, 64), exact(64, 64);
  drawCrosshair(rounded, 31.6f, 32.4f, CrosshairStyle{});
  drawCrosshair(exact, 32.0f, 32.0f, CrosshairStyle{});
  EXPECT_EQ(rounded.pixels, exact.pixels);
}

TEST(Crosshair, IsClippedAtTheImageCorner) {
  ImageRGBA8 image(16, 16);
  const CrosshairStyle style;
  drawCrosshair(image, 0.0f, 0.0f, style);  // three quarters of it lie outside
  EXPECT_TRUE(hasColor(image, std::uint32_t(style.gapPx) + 2, 0, style.color));
  EXPECT_TRUE(hasColor(image, 0, std::uint32_t(style.gapPx) + 2, style.color));
}

TEST(Crosshair, EntirelyOutsideDrawsNothing) {
  ImageRGBA8 image(16, 16);
  drawCrosshair(image, -50.0f, -50.0f, CrosshairStyle{});
  drawCrosshair(image, 1.0e30f, -1.0e30f, CrosshairStyle{});
  EXPECT_EQ(touchedCount(image), 0u);
}

TEST(Crosshair, StyleScalesWithTheImageHeight) {
  const CrosshairStyle at720 = crosshairStyleForHeight(720), at1440 = crosshairStyleForHeight(1440);
  EXPECT_EQ(at720.armLengthPx, CrosshairStyle{}.armLengthPx);
  EXPECT_EQ(at1440.armLengthPx, 2 * at720.armLengthPx);
  EXPECT_EQ(at1440.thicknessPx, 2 * at720.thicknessPx);
  const CrosshairStyle tiny = crosshairStyleForHeight(16);
  EXPECT_GE(tiny.armLengthPx, 2);
  EXPECT_GE(tiny.thicknessPx, 1);
}

TEST(CrosshairEyeOffset, IsZeroAtTheZeroParallaxDistance) {
  const stereo::StereoParameters parameters{0.02f, 3.0f};
  EXPECT_EQ(crosshairEyeOffsetPx(parameters, 3.0f, 1280, stereo::Eye::Left), 0.0f);
  EXPECT_EQ(crosshairEyeOffsetPx(parameters, 3.0f, 1280, stereo::Eye::Right), 0.0f);
}

TEST(CrosshairEyeOffset, EyesHaveOppositeSigns) {
  // Behind the screen plane the left eye's image moves left; in front of it, right (crossed disparity).
  const stereo::StereoParameters parameters{0.02f, 1.0f};
  EXPECT_LT(crosshairEyeOffsetPx(parameters, 8.0f, 1280, stereo::Eye::Left), 0.0f);
  EXPECT_GT(crosshairEyeOffsetPx(parameters, 8.0f, 1280, stereo::Eye::Right), 0.0f);
  EXPECT_GT(crosshairEyeOffsetPx(parameters, 0.5f, 1280, stereo::Eye::Left), 0.0f);
  EXPECT_LT(crosshairEyeOffsetPx(parameters, 0.5f, 1280, stereo::Eye::Right), 0.0f);
}

TEST(CrosshairEyeOffset, EqualsTheHandValue) {
  // Depth 8 m, ZPP 1 m, maxSeparation 0.02 at 1280 px: 0.02 * (1 - 1/8) * 1280 = 22.4 px.
  // Tolerance 1e-4 px: a few float roundings of numbers around 20.
  const stereo::StereoParameters parameters{0.02f, 1.0f};
  EXPECT_NEAR(crosshairEyeOffsetPx(parameters, 8.0f, 1280, stereo::Eye::Left), -22.4f, 1e-4f);
  EXPECT_NEAR(crosshairEyeOffsetPx(parameters, 8.0f, 1280, stereo::Eye::Right), 22.4f, 1e-4f);
}

}  // namespace
}  // namespace s3d::hud
