// The HUD overlay: panels with text drawn into each eye at the parallax of their depth, faded out where the
// weapon mask (carried in the eyes' alpha) covers an element behind the weapon, and its depth-conflict count.
#include <gtest/gtest.h>

#include <cmath>

#include "s3d/hud/overlay.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/synthesis.h"
#include "vulkan_test.h"

namespace s3d::hud {
namespace {

// A 4x1 eye: gray world with alpha 255 (pixels 0-1), weapon with alpha 0 (pixel 2), a weapon edge at 50 % (pixel 3).
ImageRGBA8 eyeWithWeaponMask() {
  ImageRGBA8 eye(4, 1, 100);
  eye.at(0, 0)[3] = eye.at(1, 0)[3] = 255;
  eye.at(2, 0)[3] = 0;
  eye.at(3, 0)[3] = 128;
  return eye;
}

ImageRGBA8 whiteLayer(std::uint32_t width, std::uint32_t height) { return ImageRGBA8(width, height, 255); }

TEST(HudBlend, AnElementBehindTheWeaponFadesOutWhereTheMaskCoversIt) {
  ImageRGBA8 eye = eyeWithWeaponMask();
  const BlendCounts counts = blendLayer(eye, whiteLayer(4, 1), true);
  EXPECT_EQ(eye.at(0, 0)[0], 255);  // world: drawn
  EXPECT_EQ(eye.at(2, 0)[0], 100);  // weapon: the element is occluded
  // Half-covered edge: half the element's opacity, 100 + (255 - 100) * 128 / 255 = 177.8 -> 178.
  EXPECT_EQ(eye.at(3, 0)[0], 178);
  EXPECT_EQ(counts.fadedPixels, 2u);
  EXPECT_EQ(counts.drawnPixels, 3u);
}

TEST(HudBlend, AnElementInFrontOfTheWeaponIsDrawnOverIt) {
  ImageRGBA8 eye = eyeWithWeaponMask();
  const BlendCounts counts = blendLayer(eye, whiteLayer(4, 1), false);
  for (std::uint32_t x = 0; x < 4; ++x) EXPECT_EQ(eye.at(x, 0)[0], 255) << x;
  EXPECT_EQ(counts.fadedPixels, 0u);
  EXPECT_EQ(eye.at(2, 0)[3], 0);  // the mask stays for later elements
}

TEST(HudPanel, ShiftsByItsRoundedEyeOffsetAndCarriesText) {
  Panel panel;
  panel.x = 10;
  panel.y = 5;
  panel.width = 60;
  panel.height = 16;
  panel.text = "AMMO 30";
  panel.textColor = {255, 0, 0, 255};  // red: apart from the fill and the border
  const ImageRGBA8 still = panelLayer(100, 30, panel, 0.0f);
  const ImageRGBA8 shifted = panelLayer(100, 30, panel, 2.5f);  // rounded half up: 3 px
  EXPECT_EQ(still.at(9, 10)[3], 0);  // outside the panel: transparent
  EXPECT_GT(still.at(10, 10)[3], 0);
  EXPECT_EQ(shifted.at(12, 10)[3], 0);
  EXPECT_GT(shifted.at(13, 10)[3], 0);
  std::size_t textPixels = 0;
  for (std::uint32_t y = 0; y < 30; ++y)
    for (std::uint32_t x = 0; x < 100; ++x) {
      const bool red = still.at(x, y)[0] == 255 && still.at(x, y)[1] == 0;
      if (!red) continue;
      ++textPixels;
      EXPECT_TRUE(x > 10 && x < 69 && y > 5 && y < 20) << "text outside its panel at " << x << "," << y;
    }
  EXPECT_GT(textPixels, 20u);  // seven glyphs of stb_easy_font segments
}

TEST(HudDepthConflicts, CountVisiblePixelsDeeperThanTheSurfaceTheyCover) {
  // 4 layer pixels at 2 m over depth 1.5 (wall, nearer), 3.0, 1.5 (weapon) and 1.0 (weapon).
  const ImageRGBA8 layer = whiteLayer(4, 1);
  DepthImage depth(4, 1);
  depth.pixels = {1.5f, 3.0f, 1.5f, 1.0f};
  const std::vector<std::uint8_t> weapon = {0, 0, 1, 1};
  // Behind the weapon the element fades out over it: only the wall pixel conflicts.
  EXPECT_EQ(countDepthConflicts(layer, 2.0f, depth, weapon, true), 1u);
  // Drawn over the weapon (not behind it by its nearest point), the weapon pixels nearer than 2 m conflict too.
  EXPECT_EQ(countDepthConflicts(layer, 2.0f, depth, weapon, false), 3u);
}

class WeaponMaskInAlpha : public test::VulkanTest {};

TEST_F(WeaponMaskInAlpha, TheRendererWritesItAndTheStereoPassCarriesItIntoBothEyes) {
  constexpr std::uint32_t kWidth = 96, kHeight = 54;
  renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  renderer::DeferredRenderer deferred(context(), kWidth, kHeight);
  deferred.setScene(scene);
  deferred.render(renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight), {1.0f, 1.0f}));
  const ImageRGBA8 center = deferred.readDisplayColor();
  const std::vector<std::uint8_t> mask = deferred.readFirstPersonMask();
  std::size_t weaponPixels = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    EXPECT_EQ(center.pixels[4 * i + 3], mask[i] ? 0 : 255) << "pixel " << i;
    weaponPixels += mask[i];
  }
  ASSERT_GT(weaponPixels, 0u);
  const stereo::SynthesisResult eyes =
      stereo::synthesizeTimed(context(), deferred.displayColor(), deferred.linearDepth(), stereo::StereoParameters{});
  for (const ImageRGBA8* eye : {&eyes.eyes.left, &eyes.eyes.right}) {
    std::size_t masked = 0;
    for (std::size_t i = 0; i < eye->pixelCount(); ++i) masked += eye->pixels[4 * i + 3] == 0;
    // The weapon moves by its parallax but keeps its size: its mask covers about as many pixels (within 20 %:
    // columns at its edges are interpolated, and the crop blacks out a border).
    EXPECT_NEAR(double(masked), double(weaponPixels), 0.2 * double(weaponPixels));
  }
}

}  // namespace
}  // namespace s3d::hud
