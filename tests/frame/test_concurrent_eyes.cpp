// Both eyes rendered at once (DeferredRenderer::renderConcurrently, and the hybrid with an eye renderer per eye):
// each view comes out as its renderer's render() alone would make it, and a call that would read a renderer while
// it renders is refused. On a device without a compute queue (lavapipe) the views' command buffers run one after
// the other; the equality is what a GPU's compute queue must keep too (these tests run there as well).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "s3d/frame/hybrid_stereo.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_bvh.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/resources.h"
#include "vulkan_test.h"

namespace s3d::frame {
namespace {

class ConcurrentEyes : public test::VulkanTest {};

constexpr std::uint32_t kWidth = 96, kHeight = 54;

renderer::Scene builtIn(const std::string& name) {
  renderer::Scene scene = renderer::makeBuiltInScene(name);
  scene.camera = renderer::cameraForFrame(scene, 0);
  return scene;
}

// Every other pixel of every other row: tiles partly covered, the casts beside unmasked pixels.
vk::Image sparseMask(vk::Context& context) {
  std::vector<std::uint32_t> values(std::size_t(kWidth) * kHeight, 0);
  for (std::uint32_t y = 0; y < kHeight; y += 2)
    for (std::uint32_t x = 0; x < kWidth; x += 2) values[std::size_t(y) * kWidth + x] = 1;
  vk::Image image = vk::createImage(context, VK_FORMAT_R32_UINT, kWidth, kHeight,
                                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context, image, std::as_bytes(std::span(values)), vk::kComputeWrite);
  return image;
}

// The HDR colour of the pixels a render shades: every pixel, or sparseMask's (the others are left undefined).
std::vector<float> shaded(const ImageRGBA32F& hdr, bool masked) {
  std::vector<float> values;
  for (std::uint32_t y = 0; y < kHeight; y += masked ? 2 : 1)
    for (std::uint32_t x = 0; x < kWidth; x += masked ? 2 : 1)
      for (int c = 0; c < 4; ++c) values.push_back(hdr.pixels[(std::size_t(y) * kWidth + x) * 4 + std::size_t(c)]);
  return values;
}

// Tolerance: none. Each view's passes are its renderer's own, recorded as render() records them; only the
// command buffer (and, on a GPU, the queue) they run in differs. Whole rasterized views (the main queue, in turn)
// and masked ray-cast ones (compute only: the right view on a GPU's compute queue).
TEST_F(ConcurrentEyes, EachViewIsWhatItsRendererAloneMakes) {
  const renderer::Scene scene = builtIn("courtyard");
  const vk::Image leftMask = sparseMask(context()), rightMask = sparseMask(context());
  for (const bool rays : {false, true}) {
    const renderer::RendererOptions options = eyeRendererOptions({}, rays ? HybridSurfaces::RayCast : HybridSurfaces::Raster);
    renderer::DeferredRenderer center(context(), kWidth, kHeight, options), left(context(), kWidth, kHeight, options),
        right(context(), kWidth, kHeight, options);
    for (renderer::DeferredRenderer* r : {&center, &left, &right}) r->setScene(scene);
    if (rays)
      for (renderer::DeferredRenderer* r : {&left, &right}) r->setSurfaceBvh(renderer::SceneBvh::build(scene));
    const auto surfaces = rays ? renderer::ShadeMask::Surfaces::RayCast : renderer::ShadeMask::Surfaces::Raster;
    const renderer::ShadeMask leftShading = rays ? renderer::ShadeMask{&leftMask, 1, surfaces} : renderer::ShadeMask{};
    const renderer::ShadeMask rightShading = rays ? renderer::ShadeMask{&rightMask, 1, surfaces} : renderer::ShadeMask{};
    const renderer::ViewMatrices centerView = renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight));
    const stereo::StereoParameters parameters;
    const renderer::ViewMatrices leftView = referenceEyeView(scene, centerView, stereo::Eye::Left, parameters);
    const renderer::ViewMatrices rightView = referenceEyeView(scene, centerView, stereo::Eye::Right, parameters);
    (void)center.render(centerView);
    (void)left.render(leftView, leftShading, center);
    const ImageRGBA32F leftAlone = left.readHdrColor();
    (void)right.render(rightView, rightShading, center);
    const ImageRGBA32F rightAlone = right.readHdrColor();

    const std::vector<renderer::ConcurrentView> views = {{&left, leftView, leftShading, &center},
                                                         {&right, rightView, rightShading, &center}};
    const renderer::ConcurrentTimings timings = renderer::DeferredRenderer::renderConcurrently(views);
    const char* what = rays ? "ray-cast masked views" : "rasterized whole views";
    EXPECT_EQ(shaded(left.readHdrColor(), rays), shaded(leftAlone, rays)) << what;
    EXPECT_EQ(shaded(right.readHdrColor(), rays), shaded(rightAlone, rays)) << what;
    ASSERT_EQ(timings.views.size(), 2u) << what;
    ASSERT_TRUE(timings.spanGpuMs && timings.views[0].totalGpuMs && timings.views[1].totalGpuMs) << what;
    // The span holds each view's own time (at once: the longer one at least; in turn: their sum).
    EXPECT_GE(*timings.spanGpuMs, std::max(*timings.views[0].totalGpuMs, *timings.views[1].totalGpuMs) * 0.999) << what;
  }
}

TEST_F(ConcurrentEyes, ARendererTwiceOrLendingItsShadowsToAViewOfTheCallIsRefused) {
  const renderer::Scene scene = builtIn("cover");
  renderer::DeferredRenderer first(context(), kWidth, kHeight), second(context(), kWidth, kHeight);
  first.setScene(scene);
  second.setScene(scene);
  const renderer::ViewMatrices view = renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight));
  (void)first.render(view);
  const std::vector<renderer::ConcurrentView> twice = {{&first, view, {}, nullptr}, {&first, view, {}, nullptr}};
  EXPECT_THROW(renderer::DeferredRenderer::renderConcurrently(twice), std::invalid_argument);
  const std::vector<renderer::ConcurrentView> lending = {{&first, view, {}, nullptr}, {&second, view, {}, &first}};
  EXPECT_THROW(renderer::DeferredRenderer::renderConcurrently(lending), std::invalid_argument);
}

// The courtyard's center view rendered for the hybrid at the default budget, and two eye renderers, all made for
// `surfaces`.
struct HybridViews {
  HybridViews(vk::Context& context, HybridSurfaces surfaces)
      : options(eyeRendererOptions({}, surfaces)),
        center(context, kWidth, kHeight, options),
        left(context, kWidth, kHeight, options),
        right(context, kWidth, kHeight, options) {
    parameters.method = stereo::StereoMethod::Hybrid;
    for (renderer::DeferredRenderer* r : {&center, &left, &right}) r->setScene(scene);
    centerView = renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight),
                                              {parameters.weaponDepthOffset, parameters.weaponDepthScale});
    (void)center.render(centerView);
  }
  const renderer::Scene scene = builtIn("courtyard");
  stereo::StereoParameters parameters;
  renderer::RendererOptions options;
  renderer::DeferredRenderer center, left, right;
  renderer::ViewMatrices centerView;
};

// Tolerance: none. With an eye renderer per eye the hybrid renders the same masked pixels with the same passes;
// only which renderer (and queue) draws the right eye differs. Ray-cast surfaces with the occlusion's base depth
// (courtyard), rasterized ones, and the left eye rasterized beside the right eye's rays, at the default budget.
TEST_F(ConcurrentEyes, TheHybridWithAnEyeRendererPerEyeMakesTheSameEyes) {
  for (const HybridSurfaces surfaces : {HybridSurfaces::RayCast, HybridSurfaces::Raster, HybridSurfaces::Mixed}) {
    HybridViews v(context(), surfaces);
    HybridSynthesizer synthesizer(context());
    const HybridSynthesis inTurn = synthesizer.synthesize(v.center, v.left, v.scene, v.centerView, v.parameters, 1, surfaces);
    const HybridSynthesis atOnce =
        synthesizer.synthesize(v.center, {&v.left, &v.right}, v.scene, v.centerView, v.parameters, 1, surfaces);
    const char* name = hybridSurfacesName(surfaces);
    ASSERT_GT(inTurn.maskedPixels[0] + inTurn.maskedPixels[1], 0u) << name;
    // At once only where the right eye's rays can run on a compute queue (a GPU's; lavapipe has none).
    EXPECT_EQ(atOnce.timings.concurrentEyes, context().hasConcurrentQueue() && surfaces != HybridSurfaces::Raster) << name;
    EXPECT_FALSE(inTurn.timings.concurrentEyes) << name;
    EXPECT_EQ(atOnce.masks, inTurn.masks) << name;
    EXPECT_EQ(atOnce.eyes.left.pixels, inTurn.eyes.left.pixels) << name;
    EXPECT_EQ(atOnce.eyes.right.pixels, inTurn.eyes.right.pixels) << name;
  }
}

// Tolerance: none. Mixed surfaces are each eye's own path: the left eye as the rasterized hybrid makes it, the right
// as the ray-cast hybrid does (its occlusion region given the base's depth), from the same masks; the right eye
// renders on a GPU's compute queue beside the left eye's raster.
TEST_F(ConcurrentEyes, MixedSurfacesRasterizeTheLeftEyeAndCastTheRightEyesRays) {
  HybridViews v(context(), HybridSurfaces::Mixed);
  HybridSynthesizer synthesizer(context());
  auto run = [&](HybridSurfaces surfaces) {
    return synthesizer.synthesize(v.center, {&v.left, &v.right}, v.scene, v.centerView, v.parameters, 1, surfaces);
  };
  const HybridSynthesis raster = run(HybridSurfaces::Raster), rays = run(HybridSurfaces::RayCast);
  const HybridSynthesis mixed = run(HybridSurfaces::Mixed);
  using Surfaces = renderer::ShadeMask::Surfaces;
  EXPECT_EQ(mixed.surfaces, (std::array<Surfaces, 2>{Surfaces::Raster, Surfaces::RayCast}));
  EXPECT_TRUE(mixed.timings.mixedSurfaces && mixed.timings.raycastSurfaces);
  ASSERT_GT(mixed.maskedPixels[0], 0u);
  ASSERT_GT(mixed.maskedPixels[1], 0u);
  EXPECT_EQ(mixed.masks, raster.masks);
  EXPECT_EQ(mixed.eyes.left.pixels, raster.eyes.left.pixels);
  EXPECT_EQ(mixed.eyes.right.pixels, rays.eyes.right.pixels);
}

// The frame's time is its parts': the span up to the eye renders (the displacement and classification with the
// base depth and, one renderer per eye, the eyes' ray setup beside them), the eye renders and the composites. In
// turn the eye renders take their passes' sum (one timed run: no medians between them); at once, their span (not
// less than the slower eye). Tolerance: the timestamps' float sums.
TEST_F(ConcurrentEyes, TheHybridsTotalIsItsPartsWithTheEyeRendersTogether) {
  HybridViews v(context(), HybridSurfaces::RayCast);
  HybridSynthesizer synthesizer(context());
  for (const bool together : {false, true}) {
    const std::array<renderer::DeferredRenderer*, 2> eyes = {&v.left, together ? &v.right : &v.left};
    const HybridSynthesis hybrid =
        synthesizer.synthesize(v.center, eyes, v.scene, v.centerView, v.parameters, 1, HybridSurfaces::RayCast);
    const HybridTimings& t = hybrid.timings;
    ASSERT_TRUE(t.total && t.frontSpan && t.displacement && t.classification && t.baseDepth && t.eyeRenders &&
                t.composite && t.eyeGeometry && t.maskedShading);
    EXPECT_GT(*t.baseDepth, 0.0);  // the base depth runs beside the classification, so the front is one span
    EXPECT_NEAR(*t.total, *t.frontSpan + *t.eyeRenders + *t.composite, 1e-9);
    const double passes = *t.eyeGeometry - *t.baseDepth + *t.maskedShading;
    if (t.concurrentEyes) {
      double slower = 0.0;
      for (const auto* eye : {&t.leftEyePasses, &t.rightEyePasses}) {
        double own = 0.0;
        for (const renderer::PassTiming& pass : *eye) own += pass.gpuMs;
        slower = std::max(slower, own);
      }
      EXPECT_GE(*t.eyeRenders, slower * 0.999);
    } else {
      EXPECT_NEAR(*t.eyeRenders, passes, 1e-6 * std::max(1.0, passes));
    }
  }
}

// The second eye renderer is planned for only where it is made: a hybrid run on a device with a compute queue
// (requireMemory adds concurrentDeviceBytes there). It holds a renderer's targets: at least the per-sample bytes.
TEST(ConcurrentEyesMemory, AHybridRunPlansASecondEyeRendererForAComputeQueue) {
  const MemoryEstimate hybrid = renderMemoryEstimate(1920, 1080, 1920, 2, true);
  const MemoryEstimate search = renderMemoryEstimate(1920, 1080, 1920, 2, false);
  EXPECT_GE(hybrid.concurrentDeviceBytes, kDeviceBytesPerSample * 4 * 1920 * 1080);
  EXPECT_EQ(search.concurrentDeviceBytes, 0u);
}

}  // namespace
}  // namespace s3d::frame
