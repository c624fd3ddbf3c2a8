// HUD elements as layers (the C++ reference of the HUD pass): the built-in panels and crosshair, cropped and placed
// at their eye origins, draw exactly what the full-image overlay functions draw; placement, clipping and order.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "s3d/hud/hud_layers.h"
#include "stereo_test_views.h"

namespace s3d::hud {
namespace {

// Random colour with a weapon mask in the alpha: 0 on a block (the weapon), 255 elsewhere, a soft edge at 96.
ImageRGBA8 eyeWithMask(std::uint32_t width, std::uint32_t height, unsigned seed) {
  std::mt19937 random(seed);
  ImageRGBA8 eye(width, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      std::uint8_t* p = eye.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(random() & 255u);
      const bool weapon = x >= width / 2 && y >= height / 2;
      const bool edge = x + 1 == width / 2 && y >= height / 2;
      p[3] = weapon ? 0 : edge ? 96 : 255;
    }
  return eye;
}

const float kOffsets[] = {0.0f, 2.5f, -2.5f, 7.3f, -13.6f, 0.49f, -0.5f, 250.0f};

TEST(HudLayers, ABuiltInPanelAtItsEyeOriginDrawsWhatPanelLayerDraws) {
  for (const std::uint32_t width : {320u, 1280u}) {
    const std::uint32_t height = width * 9 / 16;
    for (const Panel& panel : defaultPanels(width, height)) {
      const HudLayer layer = panelHudLayer(panel);
      EXPECT_LT(layer.pixels.width, width / 2) << "cropped to the panel";
      for (const float offset : kOffsets)
        for (const bool behind : {false, true}) {
          ImageRGBA8 expected = eyeWithMask(width, height, 3), got = expected;
          const BlendCounts want = blendLayer(expected, panelLayer(width, height, panel, offset), behind);
          const LayerOrigin origin = layerOrigin(layer.placement, offset);
          const BlendCounts have = compositeLayer(got, layer.pixels, origin.x, origin.y, behind);
          // Exact: the same pixels blended by the same function.
          EXPECT_EQ(test::largestChannelDifference(got, expected), 0) << panel.name << " offset " << offset;
          EXPECT_EQ(have.drawnPixels, want.drawnPixels);
          EXPECT_EQ(have.fadedPixels, want.fadedPixels);
        }
    }
  }
}

TEST(HudLayers, TheBuiltInCrosshairAtItsEyeOriginDrawsWhatDrawCrosshairDraws) {
  for (const std::uint32_t width : {319u, 320u}) {  // odd and even: the center is a pixel or between two
    const std::uint32_t height = 181;
    const CrosshairStyle style = crosshairStyleForHeight(height);
    const HudLayer layer = crosshairHudLayer(width, height, style);
    for (const float offset : kOffsets) {
      ImageRGBA8 full(width, height);
      drawCrosshair(full, 0.5f * float(width - 1) + offset, 0.5f * float(height - 1), style);
      ImageRGBA8 expected = eyeWithMask(width, height, 4), got = expected;
      blendLayer(expected, full, true);
      const LayerOrigin origin = layerOrigin(layer.placement, offset);
      compositeLayer(got, layer.pixels, origin.x, origin.y, true);
      EXPECT_EQ(test::largestChannelDifference(got, expected), 0) << "width " << width << " offset " << offset;
    }
  }
}

TEST(HudLayers, ALayerPartlyOutsideTheEyeIsClippedLikeTheSameLayerPlacedInAFullImage) {
  HudLayer layer{"box", ImageRGBA8(10, 6), {}};
  for (std::size_t i = 0; i < layer.pixels.pixels.size(); ++i) layer.pixels.pixels[i] = std::uint8_t(37 * i + 11);
  for (const auto& [x, y] : {std::pair{-4, -2}, std::pair{27, 9}, std::pair{-20, 0}, std::pair{3, 3}}) {
    ImageRGBA8 expected = eyeWithMask(32, 12, 5), got = expected;
    blendLayer(expected, placedLayer(32, 12, layer.pixels, x, y), false);
    compositeLayer(got, layer.pixels, x, y, false);
    EXPECT_EQ(test::largestChannelDifference(got, expected), 0) << x << "," << y;
  }
}

TEST(HudLayers, EachEyeGetsTheElementShiftedByMinusAndPlusItsParallax) {
  const HudLayer layer{"dot", ImageRGBA8(1, 1, 255), {10.0f, 2.0f, 0, 0}};
  ImageRGBA8 left(24, 4), right(24, 4);
  const HudElementFrame frame{3.4f, false, false};
  compositeHud(left, stereo::Eye::Left, std::span(&layer, 1), std::span(&frame, 1));
  compositeHud(right, stereo::Eye::Right, std::span(&layer, 1), std::span(&frame, 1));
  EXPECT_EQ(left.at(7, 2)[0], 255);   // 10 - 3.4 = 6.6 -> 7
  EXPECT_EQ(right.at(13, 2)[0], 255);  // 10 + 3.4 = 13.4 -> 13
}

// An opaque single-colour layer w pixels wide, anchored at column x.
HudLayer solid(std::uint32_t width, float x, std::array<std::uint8_t, 4> color) {
  HudLayer layer{"solid", ImageRGBA8(width, 1), {x, 0.0f, 0, 0}};
  for (std::size_t i = 0; i < layer.pixels.pixels.size(); ++i) layer.pixels.pixels[i] = color[i % 4];
  return layer;
}

TEST(HudLayers, LaterElementsAreDrawnOnTopAndHiddenOnesNotAtAll) {
  const HudLayer layers[] = {solid(2, 0.0f, {255, 0, 0, 255}), solid(2, 1.0f, {0, 255, 0, 255}),
                             solid(1, 0.0f, {0, 0, 255, 255})};
  const HudElementFrame frames[] = {{}, {}, {0.0f, false, true}};
  ImageRGBA8 eye(3, 1);
  compositeHud(eye, stereo::Eye::Left, layers, frames);
  EXPECT_EQ(eye.at(0, 0)[0], 255);  // red alone (blue hidden)
  EXPECT_EQ(eye.at(1, 0)[1], 255);  // green over red
  EXPECT_EQ(eye.at(1, 0)[0], 0);
  EXPECT_THROW(compositeHud(eye, stereo::Eye::Left, layers, std::span(frames).first(2)), std::invalid_argument);
}

TEST(HudLayers, ANonFiniteParallaxIsRefused) {
  EXPECT_THROW(layerOrigin({}, NAN), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::hud
