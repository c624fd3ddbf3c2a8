// frame::StereoSynthesis, the one entry point for the eyes from s3d's renderer: the previous-frame fill keeps its
// history and follows the eye cameras between frames, the hybrid's eye renderer follows the scene, and frames the
// synthesis was not made for are refused. (The hybrid's own behaviour: test_hybrid_render.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "s3d/frame/layered_reference.h"
#include "s3d/frame/stereo_synthesis.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/previous_fill.h"
#include "s3d/stereo/reprojection.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::frame {
namespace {

using test::largestChannelDifference;

constexpr std::uint32_t kWidth = 96, kHeight = 54;

class StereoSynthesisTest : public test::VulkanTest {};

struct CenterFrame {
  renderer::Scene scene;
  renderer::ViewMatrices center;
};

// Frame `index` of a built-in scene's camera path, rendered into `renderer` (its scene set when `setScene`).
CenterFrame renderCenter(renderer::DeferredRenderer& renderer, const std::string& name, std::size_t index,
                         const stereo::StereoParameters& parameters, bool setScene) {
  CenterFrame frame{renderer::makeBuiltInScene(name), {}};
  frame.scene.camera = renderer::cameraForFrame(frame.scene, index);
  if (setScene) renderer.setScene(frame.scene);
  frame.center = renderer::centerViewMatrices(frame.scene, float(kWidth) / float(kHeight),
                                              {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  (void)renderer.render(frame.center);
  return frame;
}

// Tolerance: one 8-bit level, as the fill pass against its C++ twin (test_previous_fill.cpp): the GPU's unorm
// conversion of a filtered value may round the other way. The motion is the two-pass reference's eye cameras'.
TEST_F(StereoSynthesisTest, TheFillOverFramesOfACameraPathIsItsCppTwinWithTheEyeCamerasMotion) {
  stereo::StereoParameters parameters;
  parameters.method = stereo::StereoMethod::Forward;
  parameters.previousFrameFill = true;
  parameters.edgeCrop = parameters.maxSeparation;
  renderer::DeferredRenderer centerRenderer(context(), kWidth, kHeight);
  StereoSynthesis synthesis(context(), {.width = kWidth, .height = kHeight, .previousFrameFill = true});
  std::optional<stereo::ForwardWithHistory> cpu;
  std::array<renderer::ViewMatrices, 2> previousEyes;
  for (std::size_t index = 0; index < 3; ++index) {
    const CenterFrame frame = renderCenter(centerRenderer, "courtyard", index, parameters, index == 0);
    const SynthesizedEyes eyes = synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters});
    std::array<gpu::EyeMotion, 2> motion{};
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      const std::size_t e = eye == stereo::Eye::Left ? 0 : 1;
      const renderer::ViewMatrices view = referenceEyeView(frame.scene, frame.center, eye, parameters);
      if (cpu)
        motion[e] = stereo::eyeMotion(view.worldView, view.worldProjection, previousEyes[e].worldView,
                                      previousEyes[e].worldProjection);
      previousEyes[e] = view;
    }
    cpu = stereo::synthesizeForwardWithPreviousFrameReference(
        centerRenderer.readDisplayColor(), centerRenderer.readLinearDepth(),
        stereo::makeForwardConstants(parameters, kWidth, kHeight), motion, cpu ? &cpu->history : nullptr);
    EXPECT_LE(largestChannelDifference(eyes.eyes.left, cpu->eyes.left), 1) << "frame " << index;
    EXPECT_LE(largestChannelDifference(eyes.eyes.right, cpu->eyes.right), 1) << "frame " << index;
  }
  EXPECT_GT(cpu->counts[0].filledFromPrevious + cpu->counts[1].filledFromPrevious, 0u);  // the history was used
}

// Tolerance: one 8-bit level, as HybridRender's budget-1 test: at budget 1 every compared pixel is the eye
// camera's render, rasterized (exact on any device; a GPU's rays may part from the raster on triangle edges). An
// eye renderer left on the first scene would render the wrong one (or refuse the center renderer's shadow maps).
TEST_F(StereoSynthesisTest, TheHybridsEyeRendererFollowsTheScene) {
  stereo::StereoParameters parameters;
  parameters.method = stereo::StereoMethod::Hybrid;
  parameters.hybridBudget = 1.0f;
  renderer::DeferredRenderer centerRenderer(context(), kWidth, kHeight);
  StereoSynthesis synthesis(context(),
                            {.width = kWidth, .height = kHeight, .hybrid = true, .hybridSurfaces = HybridSurfaces::Raster});
  const gpu::StereoConstants crop = stereo::makeStereoConstants(parameters, kWidth, kHeight);
  for (const std::string name : {"courtyard", "fence"}) {
    const CenterFrame frame = renderCenter(centerRenderer, name, 0, parameters, true);
    synthesis.setScene(frame.scene);
    const SynthesizedEyes eyes = synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters});
    ASSERT_TRUE(eyes.hybrid.has_value());
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      (void)centerRenderer.render(referenceEyeView(frame.scene, frame.center, eye, parameters));
      const ImageRGBA8 reference = stereo::cropColumns(centerRenderer.readDisplayColor(), std::uint32_t(crop.cropBegin),
                                                       std::uint32_t(crop.cropEnd - crop.cropBegin));
      const ImageRGBA8 synthesized =
          stereo::cropColumns(eye == stereo::Eye::Left ? eyes.eyes.left : eyes.eyes.right,
                              std::uint32_t(crop.cropBegin), std::uint32_t(crop.cropEnd - crop.cropBegin));
      EXPECT_LE(largestChannelDifference(synthesized, reference), 1) << name;
    }
  }
}

// Tolerance: none. Which path is faster is the device's to say (thin geometry makes a poor BVH; where little is
// masked, the classification can cost more than the rays it saves); the rule is that Automatic times rays, raster,
// the left eye rasterized beside the right eye's rays (where the eyes can render at once) and every pixel (by rays,
// and mixed where the eyes can render at once) on a scene's first hybrid frame at a budget, keeps the fastest for
// the scene's later frames at that budget, and times them again for a new scene.
TEST_F(StereoSynthesisTest, AutomaticSurfacesKeepThePathTimedFastestOnTheScenesFirstFrame) {
  stereo::StereoParameters parameters;
  parameters.method = stereo::StereoMethod::Hybrid;
  parameters.hybridBudget = 0.3f;
  const renderer::RendererOptions rays = eyeRendererOptions({}, HybridSurfaces::RayCast);
  renderer::DeferredRenderer centerRenderer(context(), kWidth, kHeight, rays);
  StereoSynthesis synthesis(context(), {.width = kWidth, .height = kHeight, .renderer = rays, .hybrid = true});
  const CenterFrame frame = renderCenter(centerRenderer, "cover", 0, parameters, true);
  synthesis.setScene(frame.scene);
  const SynthesizedEyes first = synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters});
  ASSERT_TRUE(first.hybrid && first.hybrid->surfaceChoice);
  const HybridSynthesis::SurfaceChoice& timed = *first.hybrid->surfaceChoice;
  ASSERT_TRUE(timed.raycastMs && timed.rasterMs && timed.everyPixelRaycastMs) << "the device gives no timestamps";
  const bool atOnce = context().hasConcurrentQueue();
  EXPECT_EQ(timed.mixedMs.has_value(), atOnce) << "mixed is timed where the eyes render at once";
  EXPECT_EQ(timed.everyPixelMixedMs.has_value(), atOnce) << "mixed is timed where the eyes render at once";
  using Surfaces = renderer::ShadeMask::Surfaces;
  using EyeSurfaces = std::array<Surfaces, 2>;
  constexpr EyeSurfaces kRays{Surfaces::RayCast, Surfaces::RayCast}, kRaster{Surfaces::Raster, Surfaces::Raster},
      kMixed{Surfaces::Raster, Surfaces::RayCast};
  // The fastest in the order Automatic compares them (a tie keeps the earlier).
  double fastestMs = *timed.raycastMs;
  EyeSurfaces fastest = kRays;
  bool everyPixel = false;
  auto consider = [&](const std::optional<double>& ms, EyeSurfaces surfaces, bool all) {
    if (ms && *ms < fastestMs) fastestMs = *ms, fastest = surfaces, everyPixel = all;
  };
  consider(timed.rasterMs, kRaster, false);
  consider(timed.mixedMs, kMixed, false);
  consider(timed.everyPixelRaycastMs, kRays, true);
  consider(timed.everyPixelMixedMs, kMixed, true);
  // Every pixel shows as a masked share above the budget's (the budget caps it otherwise).
  const auto castEveryPixel = [&](const HybridSynthesis& hybrid) {
    const std::vector<std::uint8_t>& mask = hybrid.masks[0];
    const auto masked = double(std::count(mask.begin(), mask.end(), std::uint8_t{1}));
    return masked > parameters.hybridBudget * double(mask.size());
  };
  EXPECT_EQ(first.hybrid->surfaces, fastest);
  EXPECT_EQ(castEveryPixel(*first.hybrid), everyPixel);
  const SynthesizedEyes second = synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters});
  EXPECT_FALSE(second.hybrid->surfaceChoice.has_value()) << "the scene's choice is timed once";
  EXPECT_EQ(second.hybrid->surfaces, fastest);
  EXPECT_EQ(castEveryPixel(*second.hybrid), everyPixel);
  parameters.hybridBudget = 0.1f;
  EXPECT_TRUE(synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters}).hybrid->surfaceChoice)
      << "another budget is timed on its first frame";
  parameters.hybridBudget = 0.3f;
  EXPECT_FALSE(synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters}).hybrid->surfaceChoice)
      << "a budget timed before keeps its choice";
  synthesis.setScene(frame.scene);
  EXPECT_TRUE(synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters}).hybrid->surfaceChoice)
      << "a new scene is timed again";
}

TEST_F(StereoSynthesisTest, ACenterViewOfAnotherSizeIsRefusedNamingBothSizes) {
  const stereo::StereoParameters parameters;
  renderer::DeferredRenderer centerRenderer(context(), 64, 36);
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  centerRenderer.setScene(scene);
  const renderer::ViewMatrices center = renderer::centerViewMatrices(scene, 64.0f / 36.0f, {1.0f, 1.0f});
  (void)centerRenderer.render(center);
  StereoSynthesis synthesis(context(), {.width = kWidth, .height = kHeight});
  try {
    (void)synthesis.synthesize({centerRenderer, scene, center, parameters});
    FAIL() << "a 64x36 center view was taken by a 96x54 synthesis";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("64x36"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("96x54"), std::string::npos) << error.what();
  }
}

// The fill's history lives in the synthesis: frames asking for it from one made without it (or the reverse) would
// silently get the other method.
TEST_F(StereoSynthesisTest, AFrameAndASynthesisThatDisagreeOnTheFillAreRefused) {
  stereo::StereoParameters parameters;
  parameters.method = stereo::StereoMethod::Forward;
  renderer::DeferredRenderer centerRenderer(context(), kWidth, kHeight);
  const CenterFrame frame = renderCenter(centerRenderer, "courtyard", 0, parameters, true);
  for (const bool fill : {false, true}) {
    StereoSynthesis synthesis(context(), {.width = kWidth, .height = kHeight, .previousFrameFill = fill});
    parameters.previousFrameFill = !fill;
    EXPECT_THROW((void)synthesis.synthesize({centerRenderer, frame.scene, frame.center, parameters}),
                 std::invalid_argument)
        << fill;
  }
}

}  // namespace
}  // namespace s3d::frame
