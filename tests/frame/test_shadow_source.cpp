// Shadow maps shared between the views of a stereo frame: an eye view plans its shadow maps for the center
// camera (ViewMatrices::shadowFit), so a renderer can light it with the center frame's maps instead of rendering
// its own, and refuses a source whose maps were made for another camera, scene or size.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "s3d/frame/layered_reference.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/stereo.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

class ShadowSource : public test::VulkanTest {};

constexpr std::uint32_t kWidth = 96, kHeight = 54;

Scene builtIn(const std::string& name) {
  Scene scene = makeBuiltInScene(name);
  scene.camera = cameraForFrame(scene, 0);
  return scene;
}

bool anyShadowPass(const FrameTimings& frame) {
  return std::any_of(frame.passes.begin(), frame.passes.end(),
                     [](const PassTiming& pass) { return pass.name.rfind("shadow-", 0) == 0; });
}

// Tolerance: none. The borrowed maps are the ones the eye renderer would render itself (same casters, matrices,
// sizes and pipelines), so the lit image is the same bit for bit. Courtyard: sun cascades and a point light;
// cover: sun cascades and a spot light.
TEST_F(ShadowSource, AnEyeLitWithTheCenterFramesShadowMapsIsTheSameAsWithItsOwn) {
  for (const std::string name : {"courtyard", "cover"}) {
    const Scene scene = builtIn(name);
    DeferredRenderer center(context(), kWidth, kHeight), eye(context(), kWidth, kHeight);
    center.setScene(scene);
    eye.setScene(scene);
    const ViewMatrices centerView = centerViewMatrices(scene, float(kWidth) / float(kHeight));
    const ViewMatrices eyeView = frame::referenceEyeView(scene, centerView, stereo::Eye::Left, stereo::StereoParameters{});
    ASSERT_TRUE(eyeView.shadowFit.has_value());
    const FrameTimings own = eye.render(eyeView);
    ASSERT_TRUE(anyShadowPass(own)) << name;
    const ImageRGBA8 ownImage = eye.readDisplayColor();
    (void)center.render(centerView);
    const FrameTimings lent = eye.render(eyeView, {}, center);
    EXPECT_FALSE(anyShadowPass(lent)) << name;
    EXPECT_EQ(eye.readDisplayColor().pixels, ownImage.pixels) << name;
  }
}

TEST_F(ShadowSource, ASourceWhoseLastFramePlannedForAnotherCameraIsRefused) {
  const Scene scene = builtIn("courtyard");
  DeferredRenderer center(context(), kWidth, kHeight), eye(context(), kWidth, kHeight);
  center.setScene(scene);
  eye.setScene(scene);
  const ViewMatrices centerView = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  const ViewMatrices eyeView = frame::referenceEyeView(scene, centerView, stereo::Eye::Right, stereo::StereoParameters{});
  EXPECT_THROW((void)eye.render(eyeView, {}, center), std::invalid_argument);  // no frame yet
  ViewMatrices ownFit = eyeView;
  ownFit.shadowFit.reset();  // planned for the eye camera itself
  (void)center.render(ownFit);
  EXPECT_THROW((void)eye.render(eyeView, {}, center), std::invalid_argument);
  (void)center.render(centerView);
  EXPECT_NO_THROW((void)eye.render(eyeView, {}, center));
}

TEST_F(ShadowSource, ASourceOfAnotherSceneOrSizeIsRefused) {
  const Scene courtyard = builtIn("courtyard"), cover = builtIn("cover");
  DeferredRenderer eye(context(), kWidth, kHeight), otherScene(context(), kWidth, kHeight),
      otherSize(context(), kWidth + 16, kHeight);
  eye.setScene(courtyard);
  otherScene.setScene(cover);
  otherSize.setScene(courtyard);
  const ViewMatrices centerView = centerViewMatrices(courtyard, float(kWidth) / float(kHeight));
  const ViewMatrices eyeView = frame::referenceEyeView(courtyard, centerView, stereo::Eye::Left, stereo::StereoParameters{});
  (void)otherScene.render(centerView);
  (void)otherSize.render(centerView);
  EXPECT_THROW((void)eye.render(eyeView, {}, otherScene), std::invalid_argument);
  EXPECT_THROW((void)eye.render(eyeView, {}, otherSize), std::invalid_argument);
  EXPECT_THROW((void)eye.render(eyeView, {}, eye), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::renderer
