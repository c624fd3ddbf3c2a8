// frame::ComfortedStereoFrame, a frame's comfort rules around the stereo synthesis: the disparity budget keeps the
// eyes within the display's limit and widens the guard band with its separation, the zero-parallax control carries
// its state between frames until a cut, and the HUD off draws nothing.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "s3d/frame/comforted_stereo_frame.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_animation.h"
#include "vulkan_test.h"

namespace s3d::frame {
namespace {

constexpr std::uint32_t kWidth = 96, kHeight = 54;

class ComfortedStereoFrameTest : public test::VulkanTest {
 protected:
  // The cover scene from its path's first frame: walls near and far, a weapon in view.
  static renderer::Scene coverScene() {
    renderer::Scene scene = renderer::makeBuiltInScene("cover");
    scene.camera = renderer::cameraForFrame(scene, 0);
    return scene;
  }
  static ComfortedStereoFrameDescription description(comfort::DisparityBudgetRule budget) {
    ComfortedStereoFrameDescription d;
    d.width = kWidth;
    d.height = kHeight;
    d.comfort.budget = budget;
    return d;
  }
};

// The controller's choice on the 1-degree rule: no pixel of the eyes beyond 60 arcminutes on the display (the rule
// is exact on the frame it reduced; the parallax statistics read the same mapped depth).
TEST_F(ComfortedStereoFrameTest, TheBudgetKeepsEveryPixelWithinTheDisplaysOneDegree) {
  const renderer::Scene scene = coverScene();
  ComfortedStereoFrame stereoFrame(context(), description(comfort::DisparityBudgetRule::OneDegree));
  const ComfortedFrame frame = stereoFrame.render(scene, 1.0f / 30.0f);
  EXPECT_EQ(frame.comfort.parallax.shareBeyondOneDegree, 0.0);
}

// A separation below what the display allows: the budget picks a wider one, and the center view is rendered again
// at the wider band that separation needs, so the eyes stay full frame.
TEST_F(ComfortedStereoFrameTest, TheBandWidensWhenTheBudgetPicksAWiderSeparation) {
  const renderer::Scene scene = coverScene();
  ComfortedStereoFrameDescription narrow = description(comfort::DisparityBudgetRule::Off);
  narrow.stereo.maxSeparation = 0.002f;
  ComfortedStereoFrame unbudgeted(context(), narrow);
  const ComfortedFrame asGiven = unbudgeted.render(scene, 1.0f / 30.0f);
  narrow.comfort.budget = comfort::DisparityBudgetRule::OneDegree;
  ComfortedStereoFrame budgeted(context(), narrow);
  const ComfortedFrame chosen = budgeted.render(scene, 1.0f / 30.0f);
  ASSERT_GT(chosen.parameters.maxSeparation, narrow.stereo.maxSeparation);
  EXPECT_GT(chosen.band.columns, asGiven.band.columns);
  EXPECT_EQ(chosen.renderedDepth.width, kWidth + 2 * chosen.band.columns);
  EXPECT_EQ(chosen.eyes.left.width, kWidth);
}

// The zero-parallax control eases toward the nearest surface over frames: with a surface in reach (an engage
// distance beyond the scene) each frame of the same view moves the plane further from its rest value, and a cut
// starts it from rest again, exactly as the first frame (the same inputs). Negative parallax allowed: only the
// control moves the plane.
TEST_F(ComfortedStereoFrameTest, TheControlCarriesItsStateBetweenFramesAndACutResetsIt) {
  const renderer::Scene scene = coverScene();
  ComfortedStereoFrameDescription d = description(comfort::DisparityBudgetRule::Off);
  d.guardBand = false;
  d.comfort.allowNegativeParallax = true;
  d.comfort.zeroParallaxControl = comfort::ZeroParallaxControlSettings{.engageDistance = 1000.0f};
  ComfortedStereoFrame stereoFrame(context(), d);
  const float first = stereoFrame.render(scene, 1.0f / 30.0f).parameters.zeroParallaxDistance;
  const float second = stereoFrame.render(scene, 1.0f / 30.0f).parameters.zeroParallaxDistance;
  const float afterCut = stereoFrame.render(scene, 1.0f / 30.0f, true).parameters.zeroParallaxDistance;
  EXPECT_LT(first, d.stereo.zeroParallaxDistance);
  EXPECT_LT(second, first);
  EXPECT_EQ(afterCut, first);
}

// HUD off: no element is drawn or reported; the eyes are only made opaque (color as synthesized).
TEST_F(ComfortedStereoFrameTest, TheHudOffDrawsNothing) {
  const renderer::Scene scene = coverScene();
  ComfortedStereoFrameDescription d = description(comfort::DisparityBudgetRule::Off);
  d.hud = false;
  ComfortedStereoFrame stereoFrame(context(), d);
  const ComfortedFrame frame = stereoFrame.render(scene, 1.0f / 30.0f);
  EXPECT_TRUE(frame.hud.elements.empty());
  std::size_t changed = 0;
  for (std::size_t i = 0; i < frame.eyes.left.pixels.size(); ++i)
    changed += (i % 4 != 3 && frame.eyesWithHud.left.pixels[i] != frame.eyes.left.pixels[i]) ? 1 : 0;
  EXPECT_EQ(changed, 0u);
}

}  // namespace
}  // namespace s3d::frame
