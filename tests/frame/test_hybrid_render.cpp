// The hybrid method with s3d's renderer: budget 0 is the base displacement bit for bit, budget 1 the two-pass
// reference, the default budget masks the pixels the displacement cannot know (the disocclusions) first, and
// render reports what it masked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "s3d/frame/hybrid_stereo.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/synthesis.h"
#include "vulkan_test.h"

namespace s3d::frame {
namespace {

class HybridRender : public test::VulkanTest {};

// One built-in scene's center view at a small size, with a second renderer for the eyes.
struct HybridScene {
  renderer::Scene scene;
  renderer::ViewMatrices center;
  std::unique_ptr<renderer::DeferredRenderer> centerRenderer, eyeRenderer;
};

HybridScene renderCenter(vk::Context& context, const std::string& name, std::uint32_t width, std::uint32_t height,
                         const stereo::StereoParameters& parameters) {
  HybridScene s;
  s.scene = renderer::makeBuiltInScene(name);
  s.scene.camera = renderer::cameraForFrame(s.scene, 0);
  s.centerRenderer = std::make_unique<renderer::DeferredRenderer>(context, width, height);
  s.eyeRenderer = std::make_unique<renderer::DeferredRenderer>(context, width, height);
  s.centerRenderer->setScene(s.scene);
  s.eyeRenderer->setScene(s.scene);
  s.center = renderer::centerViewMatrices(s.scene, float(width) / float(height),
                                          {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  (void)s.centerRenderer->render(s.center);
  return s;
}

stereo::StereoParameters hybridParameters(float budget) {
  stereo::StereoParameters parameters;
  parameters.method = stereo::StereoMethod::Hybrid;
  parameters.hybridBudget = budget;
  return parameters;
}

int largestDifference(const ImageRGBA8& a, const ImageRGBA8& b, std::uint32_t firstColumn, std::uint32_t endColumn) {
  int largest = 0;
  for (std::uint32_t y = 0; y < a.height; ++y)
    for (std::uint32_t x = firstColumn; x < endColumn; ++x)
      for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
  return largest;
}

TEST_F(HybridRender, BudgetZeroIsTheBaseDisplacementBitForBit) {
  for (const stereo::StereoMethod base : {stereo::StereoMethod::Search, stereo::StereoMethod::Iterative}) {
    stereo::StereoParameters parameters = hybridParameters(0.0f);
    parameters.hybridBase = base;
    HybridScene s = renderCenter(context(), "courtyard", 96, 54, parameters);
    const stereo::SynthesisResult displaced = stereo::synthesizeTimed(
        context(), s.centerRenderer->displayColor(), s.centerRenderer->linearDepth(), stereo::displacementParameters(parameters));
    const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    EXPECT_EQ(hybrid.thresholds[0].maskedPixels, 0u);
    EXPECT_EQ(hybrid.thresholds[1].maskedPixels, 0u);
    EXPECT_EQ(hybrid.eyes.left.pixels, displaced.eyes.left.pixels) << stereo::methodName(base);
    EXPECT_EQ(hybrid.eyes.right.pixels, displaced.eyes.right.pixels) << stereo::methodName(base);
  }
}

// A synthesizer kept between frames (its pipelines and images reused) gives each frame what a fresh one gives:
// through a classified budget, the budget-1 end (masks uploaded, not classified) and back, then a new size and
// another scene, whose images it makes again.
TEST_F(HybridRender, AKeptSynthesizerGivesEachFrameWhatAFreshOneGives) {
  HybridSynthesizer kept(context());
  struct Frame {
    const char* scene;
    std::uint32_t width, height;
    float budget;
  };
  // Budget 1 twice, and again after a classifying frame: what the kept images held before changes nothing.
  for (const Frame frame : {Frame{"courtyard", 96, 54, 0.2f}, Frame{"courtyard", 96, 54, 1.0f},
                            Frame{"courtyard", 96, 54, 1.0f}, Frame{"courtyard", 96, 54, 0.2f},
                            Frame{"courtyard", 96, 54, 1.0f}, Frame{"cover", 128, 72, 0.6f},
                            Frame{"cover", 128, 72, 1.0f}}) {
    const stereo::StereoParameters parameters = hybridParameters(frame.budget);
    HybridScene s = renderCenter(context(), frame.scene, frame.width, frame.height, parameters);
    const HybridSynthesis reused = kept.synthesize(*s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    const HybridSynthesis fresh =
        synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    const std::string what = std::string(frame.scene) + " at " + std::to_string(frame.budget);
    EXPECT_EQ(reused.masks, fresh.masks) << what;
    EXPECT_EQ(reused.eyes.left.pixels, fresh.eyes.left.pixels) << what;
    EXPECT_EQ(reused.eyes.right.pixels, fresh.eyes.right.pixels) << what;
  }
}

// A budget whose share of the pixels rounds down to none (0.0001 of 96 x 54): the eyes are the base displacement
// bit for bit, and neither eye is rendered (no pass ran, no time spent).
TEST_F(HybridRender, AnEyeWithNothingMaskedIsNotRendered) {
  const stereo::StereoParameters parameters = hybridParameters(0.0001f);
  HybridScene s = renderCenter(context(), "courtyard", 96, 54, parameters);
  const stereo::SynthesisResult displaced = stereo::synthesizeTimed(
      context(), s.centerRenderer->displayColor(), s.centerRenderer->linearDepth(), stereo::displacementParameters(parameters));
  const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
  EXPECT_EQ(hybrid.thresholds[0].maskedPixels, 0u);
  EXPECT_EQ(hybrid.thresholds[1].maskedPixels, 0u);
  EXPECT_TRUE(hybrid.timings.leftEyePasses.empty());
  EXPECT_TRUE(hybrid.timings.rightEyePasses.empty());
  if (hybrid.timings.eyeGeometry) {
    EXPECT_EQ(*hybrid.timings.eyeGeometry, 0.0);
  }
  if (hybrid.timings.maskedShading) {
    EXPECT_EQ(*hybrid.timings.maskedShading, 0.0);
  }
  if (hybrid.timings.eyeRenders) {
    EXPECT_EQ(*hybrid.timings.eyeRenders, 0.0);
  }
  EXPECT_EQ(hybrid.eyes.left.pixels, displaced.eyes.left.pixels);
  EXPECT_EQ(hybrid.eyes.right.pixels, displaced.eyes.right.pixels);
}

// Depth-range at a small budget: the bin the cap falls in holds many cells of one score (one eye masked none of
// them when whole bins were taken), so its ties are split and each eye masks exactly the budget's share of its
// cells; a pixel's cell masks all its pixels (at most 4, 2 where the crop cuts it: the image is 180 rows high).
TEST_F(HybridRender, EachEyeMasksTheBudgetsShareWhenItsThresholdBinIsTied) {
  for (const int cell : {1, 2}) {
    stereo::StereoParameters parameters = hybridParameters(0.02f);
    parameters.hybridCell = cell;
    HybridScene s = renderCenter(context(), "depth-range", 320, 180, parameters);
    const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    const std::uint32_t cap = stereo::hybridGridConstants(stereo::makeHybridConstants(parameters, 320, 180)).maskedPixelCap;
    ASSERT_GT(cap, 0u);
    for (std::size_t eye = 0; eye < 2; ++eye) {
      EXPECT_EQ(hybrid.thresholds[eye].maskedPixels, cap) << "eye " << eye << ", cell " << cell;
      const auto maskedPixels = std::uint64_t(std::count(hybrid.masks[eye].begin(), hybrid.masks[eye].end(), 1));
      EXPECT_LE(maskedPixels, std::uint64_t(cap) * std::uint64_t(cell * cell)) << "eye " << eye << ", cell " << cell;
      EXPECT_GE(maskedPixels, std::uint64_t(cap) * std::uint64_t(cell)) << "eye " << eye << ", cell " << cell;
    }
  }
}

// The budget's ends are the base displacement and the two-pass reference whatever the scores, so nothing is
// classified there (no classification time), and at budget 1 the eyes are rendered whole (no masked-render pass).
TEST_F(HybridRender, TheBudgetsEndsSkipTheClassification) {
  for (const float budget : {0.0f, 1.0f}) {
    const stereo::StereoParameters parameters = hybridParameters(budget);
    HybridScene s = renderCenter(context(), "courtyard", 96, 54, parameters);
    const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    ASSERT_TRUE(hybrid.timings.classification.has_value()) << budget;
    EXPECT_EQ(*hybrid.timings.classification, 0.0) << budget;
    for (const auto* passes : {&hybrid.timings.leftEyePasses, &hybrid.timings.rightEyePasses}) {
      EXPECT_EQ(passes->empty(), budget == 0.0f) << budget;
      for (const renderer::PassTiming& pass : *passes) EXPECT_NE(pass.name, "mask-tiles") << budget;
    }
  }
  const frame::HybridSynthesis between = [&] {
    const stereo::StereoParameters parameters = hybridParameters(0.5f);
    HybridScene s = renderCenter(context(), "courtyard", 96, 54, parameters);
    return frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
  }();
  if (between.timings.classification) {  // a device with timestamps times what did run
    EXPECT_GT(*between.timings.classification, 0.0);
  }
}

// Tolerance: one 8-bit level. At budget 1 every compared pixel is the eye camera's render, the same renderer,
// camera and rasterized surfaces as the reference eye, rendered into the eye (measured: identical on lavapipe and
// on an H200); the cropped columns are black, as the displacement leaves them. Rasterized on every device: a GPU
// would otherwise cast the eyes' rays, which the next test holds to the reference off triangle edges.
TEST_F(HybridRender, BudgetOneIsTheTwoPassReferenceOnEveryBuiltInScene) {
  for (const std::string& name : renderer::builtInSceneNames()) {
    const stereo::StereoParameters parameters = hybridParameters(1.0f);
    HybridScene s = renderCenter(context(), name, 96, 54, parameters);
    const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene,
                                                                  s.center, parameters, 1, HybridSurfaces::Raster);
    const gpu::StereoConstants crop = stereo::makeStereoConstants(parameters, 96, 54);
    EXPECT_EQ(hybrid.thresholds[0].maskedPixels, hybrid.classifiedCells) << name;
    EXPECT_EQ(hybrid.maskedPixels[0], hybrid.classifiedPixels) << name;
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      (void)s.centerRenderer->render(frame::referenceEyeView(s.scene, s.center, eye, parameters));
      const ImageRGBA8 reference = s.centerRenderer->readDisplayColor();
      const ImageRGBA8& synthesized = eye == stereo::Eye::Left ? hybrid.eyes.left : hybrid.eyes.right;
      EXPECT_LE(largestDifference(synthesized, reference, std::uint32_t(crop.cropBegin), std::uint32_t(crop.cropEnd)), 1)
          << name << (eye == stereo::Eye::Left ? " left" : " right");
      ASSERT_GT(crop.cropBegin, 0) << "the test needs cropped columns";
      for (std::uint32_t y = 0; y < 54; ++y)
        for (std::uint32_t x = 0; x < 96; ++x)
          if (int(x) < crop.cropBegin || int(x) >= crop.cropEnd) {
            ASSERT_EQ(std::vector<std::uint8_t>(synthesized.at(x, y), synthesized.at(x, y) + 4),
                      (std::vector<std::uint8_t>{0, 0, 0, 255}))
                << name << " (" << x << ", " << y << ")";
          }
    }
  }
}

// With ray-cast surfaces (the eye renderer a GPU's: visibility shading, the compute transparent pass) budget 1 is
// still the two-pass reference: within one 8-bit level on all but 0.5 % of the compared pixels (measured: at most
// 16 of 4968, the courtyard's right eye), as the rays decide triangle edges by the rasterizer's rule.
TEST_F(HybridRender, WithRayCastSurfacesBudgetOneIsTheTwoPassReferenceOffTriangleEdges) {
  renderer::RendererOptions eyeOptions;
  eyeOptions.gbufferShading = renderer::RendererOptions::GBufferShading::Visibility;
  eyeOptions.transparentCompositing = renderer::RendererOptions::TransparentCompositing::Compute;
  for (const std::string& name : renderer::builtInSceneNames()) {
    const stereo::StereoParameters parameters = hybridParameters(1.0f);
    HybridScene s = renderCenter(context(), name, 96, 54, parameters);
    s.eyeRenderer = std::make_unique<renderer::DeferredRenderer>(context(), 96, 54, eyeOptions);
    s.eyeRenderer->setScene(s.scene);
    const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    ASSERT_EQ(hybrid.surfaces[0], renderer::ShadeMask::Surfaces::RayCast) << name;
    ASSERT_EQ(hybrid.surfaces[1], renderer::ShadeMask::Surfaces::RayCast) << name;
    const gpu::StereoConstants crop = stereo::makeStereoConstants(parameters, 96, 54);
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      (void)s.centerRenderer->render(frame::referenceEyeView(s.scene, s.center, eye, parameters));
      const ImageRGBA8 reference = s.centerRenderer->readDisplayColor();
      const ImageRGBA8& synthesized = eye == stereo::Eye::Left ? hybrid.eyes.left : hybrid.eyes.right;
      std::size_t compared = 0, beyondOneLevel = 0;
      for (std::uint32_t y = 0; y < 54; ++y)
        for (int x = crop.cropBegin; x < crop.cropEnd; ++x, ++compared) {
          int largest = 0;
          for (int c = 0; c < 3; ++c)
            largest = std::max(largest, std::abs(int(synthesized.at(std::uint32_t(x), y)[c]) - int(reference.at(std::uint32_t(x), y)[c])));
          beyondOneLevel += largest > 1 ? 1 : 0;
        }
      EXPECT_LE(beyondOneLevel, compared / 200) << name << (eye == stereo::Eye::Left ? " left" : " right");
    }
  }
}

// Ray-cast eyes with ambient occlusion cast only their masked pixels (the eye render's other pixels keep id 0; with
// RayCastRegion the occlusion's whole region is cast); the region around them takes the center's depth where the
// base samples, which is the eye's surface wherever the base is right, so the occlusion shades the masked pixels
// as the eye camera's full render by rays does (the same surfaces, so only the base depth differs): within one
// 8-bit level on all but 2 % of them (measured at 160x90, budget 0.2: at most 25 of 2736 on lavapipe, depth-range's
// right eye, and 18 on an H200, the courtyard's right eye, where an unmasked neighbour's base depth is another
// surface's). The masks are the same either way.
TEST_F(HybridRender, WithRayCastSurfacesOnlyTheMaskedPixelsAreCastAndTheBaseDepthShadesThemAsTheEyeRender) {
  const renderer::RendererOptions eyeOptions = eyeRendererOptions({}, HybridSurfaces::RayCast);
  std::size_t scenes = 0;
  for (const std::string& name : renderer::builtInSceneNames()) {
    const stereo::StereoParameters parameters = hybridParameters(0.2f);
    HybridScene s = renderCenter(context(), name, 160, 90, parameters);
    if (!s.scene.ambientOcclusion) continue;
    ++scenes;
    s.eyeRenderer = std::make_unique<renderer::DeferredRenderer>(context(), 160, 90, eyeOptions);
    s.eyeRenderer->setScene(s.scene);
    const HybridSynthesis region = synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center,
                                                    parameters, 1, HybridSurfaces::RayCastRegion);
    const std::vector<std::uint32_t> regionIds = s.eyeRenderer->readVisibilityIds();  // the right eye's
    const HybridSynthesis given = synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center,
                                                   parameters, 1, HybridSurfaces::RayCast);
    const std::vector<std::uint32_t> givenIds = s.eyeRenderer->readVisibilityIds();
    ASSERT_EQ(given.surfaces[1], renderer::ShadeMask::Surfaces::RayCast) << name;
    std::size_t castUnmasked = 0, regionCastUnmasked = 0;
    for (std::size_t i = 0; i < givenIds.size(); ++i)
      if (!given.masks[1][i]) {
        castUnmasked += givenIds[i] != 0;
        regionCastUnmasked += regionIds[i] != 0;
      }
    EXPECT_EQ(castUnmasked, 0u) << name;
    EXPECT_GT(regionCastUnmasked, 0u) << name;
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      const std::size_t index = eye == stereo::Eye::Left ? 0 : 1;
      EXPECT_EQ(given.masks[index], region.masks[index]) << name;
      // The eye camera's full render by rays (its surfaces the masked pixels' own), lit with the center's maps.
      (void)s.eyeRenderer->render(referenceEyeView(s.scene, s.center, eye, parameters),
                                  {nullptr, 1, renderer::ShadeMask::Surfaces::RayCast}, *s.centerRenderer);
      const ImageRGBA8 reference = s.eyeRenderer->readDisplayColor();
      const ImageRGBA8& synthesized = index == 0 ? given.eyes.left : given.eyes.right;
      std::size_t masked = 0, beyondOneLevel = 0;
      for (std::size_t i = 0; i < given.masks[index].size(); ++i) {
        if (!given.masks[index][i]) continue;
        ++masked;
        const std::uint32_t x = std::uint32_t(i % 160), y = std::uint32_t(i / 160);
        int largest = 0;
        for (int c = 0; c < 3; ++c)
          largest = std::max(largest, std::abs(int(synthesized.at(x, y)[c]) - int(reference.at(x, y)[c])));
        beyondOneLevel += largest > 1 ? 1 : 0;
      }
      EXPECT_GT(masked, 0u) << name;
      EXPECT_LE(beyondOneLevel, masked / 50) << name << (index == 0 ? " left" : " right");
    }
  }
  EXPECT_GT(scenes, 0u);
}

// An iterative base lands on the visible surface by construction and has no source texel per eye pixel: its
// ray-cast eyes cast the occlusion's whole region, with no base depth pass.
TEST_F(HybridRender, WithAnIterativeBaseTheRayCastEyesCastTheWholeRegion) {
  stereo::StereoParameters parameters = hybridParameters(0.2f);
  parameters.hybridBase = stereo::StereoMethod::Iterative;
  HybridScene s = renderCenter(context(), "courtyard", 160, 90, parameters);
  ASSERT_TRUE(s.scene.ambientOcclusion);
  s.eyeRenderer =
      std::make_unique<renderer::DeferredRenderer>(context(), 160, 90, eyeRendererOptions({}, HybridSurfaces::RayCast));
  s.eyeRenderer->setScene(s.scene);
  const HybridSynthesis hybrid = synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center,
                                                  parameters, 1, HybridSurfaces::RayCast);
  const std::vector<std::uint32_t> ids = s.eyeRenderer->readVisibilityIds();  // the right eye's
  std::size_t castUnmasked = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) castUnmasked += !hybrid.masks[1][i] && ids[i] != 0;
  EXPECT_GT(castUnmasked, 0u);
  EXPECT_EQ(hybrid.timings.baseDepth, 0.0);
}

// The surfaces can be chosen: Raster keeps an eye renderer that could cast rays rasterizing; RayCast refuses one
// that cannot (raster shading), naming why, and eyeRendererOptions makes one that can.
TEST_F(HybridRender, TheSurfacesCanBeChosen) {
  const stereo::StereoParameters parameters = hybridParameters(0.2f);
  HybridScene s = renderCenter(context(), "cover", 96, 54, parameters);
  renderer::RendererOptions raster;
  raster.gbufferShading = renderer::RendererOptions::GBufferShading::Raster;
  s.eyeRenderer = std::make_unique<renderer::DeferredRenderer>(context(), 96, 54, raster);
  s.eyeRenderer->setScene(s.scene);
  try {
    frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters, 1,
                            frame::HybridSurfaces::RayCast);
    ADD_FAILURE() << "a raster-shading eye renderer was asked to cast rays";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("visibility"), std::string::npos) << error.what();
  }
  s.eyeRenderer = std::make_unique<renderer::DeferredRenderer>(
      context(), 96, 54, frame::eyeRendererOptions(raster, frame::HybridSurfaces::RayCast));
  s.eyeRenderer->setScene(s.scene);
  using Surfaces = renderer::ShadeMask::Surfaces;
  using EyeSurfaces = std::array<Surfaces, 2>;
  EXPECT_EQ(frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters, 1,
                                    frame::HybridSurfaces::Raster).surfaces,
            (EyeSurfaces{Surfaces::Raster, Surfaces::Raster}));
  EXPECT_EQ(frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters).surfaces,
            (EyeSurfaces{Surfaces::RayCast, Surfaces::RayCast}));
  EXPECT_EQ(frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters, 1,
                                    frame::HybridSurfaces::Mixed).surfaces,
            (EyeSurfaces{Surfaces::Raster, Surfaces::RayCast}));
  for (frame::HybridSurfaces surfaces :
       {frame::HybridSurfaces::Automatic, frame::HybridSurfaces::Raster, frame::HybridSurfaces::RayCast,
        frame::HybridSurfaces::RayCastRegion, frame::HybridSurfaces::Mixed})
    EXPECT_EQ(frame::hybridSurfacesFromName(frame::hybridSurfacesName(surfaces)), surfaces);
  EXPECT_FALSE(frame::hybridSurfacesFromName("rays").has_value());
}

// Tolerance: none on cells of one pixel without a score floor; 3 pixels in 1000 on 2x2 cells with the default
// floor. The metrics' disocclusion region (reference pixels whose surface the center view does not show at the
// rounded parallax) is finer than the classification's holes (thin slats seen at another sub-pixel phase count
// there too), but the default budget reaches the edge band and nearness tiers around them: at 640x360 every such
// pixel inside the compared columns is masked on cells of one pixel (measured: 6907 of 6907 left, 5619 of 5619
// right; at 320x180, where edges take a larger share of the image, 65 %), and on 2x2 cells with the floor all but
// a few (6906 of 6907, 5608 of 5619), where a cell's nearest depth moves a step's far side by a pixel or the floor
// leaves a slat's nearness-tier pixels displaced.
TEST_F(HybridRender, TheDefaultBudgetMasksTheDisocclusionsOfTheCourtyard) {
  for (const bool cells : {false, true}) {
    stereo::StereoParameters parameters = hybridParameters(stereo::StereoParameters{}.hybridBudget);
    parameters.hybridCell = cells ? 2 : 1;
    if (!cells) parameters.hybridScoreFloor = 0.0f;
    HybridScene s = renderCenter(context(), "courtyard", 640, 360, parameters);
    const gpu::StereoConstants crop = stereo::makeStereoConstants(parameters, 640, 360);
    const DepthImage centerDepth = s.centerRenderer->readLinearDepth();
    const frame::HybridSynthesis hybrid = frame::synthesizeHybrid(context(), *s.centerRenderer, *s.eyeRenderer, s.scene, s.center, parameters);
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      (void)s.centerRenderer->render(frame::referenceEyeView(s.scene, s.center, eye, parameters));
      const std::vector<std::uint8_t> unseen =
          stereo::disocclusionMask(s.centerRenderer->readLinearDepth(), centerDepth, parameters.maxSeparation,
                                   parameters.zeroParallaxDistance, eye);
      const std::vector<std::uint8_t>& mask = hybrid.masks[eye == stereo::Eye::Left ? 0 : 1];
      std::uint64_t disoccluded = 0, covered = 0;
      for (std::size_t i = 0; i < unseen.size(); ++i)
        if (const int x = int(i % 640); unseen[i] && x >= crop.cropBegin && x < crop.cropEnd) {
          ++disoccluded;
          covered += mask[i] != 0;
        }
      ASSERT_GT(disoccluded, 0u);
      EXPECT_GE(covered, cells ? disoccluded - 3 * disoccluded / 1000 : disoccluded)
          << (eye == stereo::Eye::Left ? "left" : "right") << (cells ? ", 2x2 cells" : ", cells of one pixel");
    }
  }
}

}  // namespace
}  // namespace s3d::frame
