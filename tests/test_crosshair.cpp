// The HUD crosshair: drawn where asked, clipped at the borders, displaced per eye by its parallax.
#include <gtest/gtest.h>

#include "s3d/hud/crosshair.h"

namespace s3d::hud {
namespace {

bool touched(const ImageRGBA8& image, std::uint32_t x, std::uint32_t y) {
  const std::uint8_t* p = image.at(x, y);
  return p[0] || p[1] || p[2] || p[3];
}

TEST(Crosshair, ArmsAreDrawnAroundTheCenterAndNothingFarAway) {
  ImageRGBA8 image(64, 64);
  CrosshairStyle style;
  drawCrosshair(image, 32.0f, 32.0f, style);
  EXPECT_EQ(image.at(32 + style.gapPx + 2, 32)[1], style.color[1]);  // on the right arm
  EXPECT_FALSE(touched(image, 32, 32));                                // the gap stays clear
  EXPECT_FALSE(touched(image, 2, 2));
  EXPECT_FALSE(touched(image, 60, 60));
}

TEST(Crosshair, IsClippedAtTheImageBorder) {
  ImageRGBA8 image(16, 16);
  drawCrosshair(image, 0.0f, 0.0f, CrosshairStyle{});
  drawCrosshair(image, -50.0f, -50.0f, CrosshairStyle{});  // entirely outside: draws nothing, no crash
  EXPECT_TRUE(touched(image, 6, 0));
}

TEST(Crosshair, EyeOffsetIsZeroAtTheZeroParallaxPlane) {
  stereo::StereoParameters parameters{0.02f, 3.0f, -1.0f};
  EXPECT_FLOAT_EQ(hudEyeOffsetPx(parameters, 3.0f, 1280, stereo::Eye::Left), 0.0f);
}

TEST(Crosshair, EyeOffsetsAreOppositeAndMatchTheParallaxFormula) {
  // Depth 8 m, ZPP 1 m, maxSeparation 0.02 at 1280 px: 0.02 * (1 - 1/8) * 1280 = 22.4 px.
  stereo::StereoParameters parameters{0.02f, 1.0f, -1.0f};
  EXPECT_NEAR(hudEyeOffsetPx(parameters, 8.0f, 1280, stereo::Eye::Left), -22.4f, 1e-4f);
  EXPECT_NEAR(hudEyeOffsetPx(parameters, 8.0f, 1280, stereo::Eye::Right), 22.4f, 1e-4f);
}

}  // namespace
}  // namespace s3d::hud
