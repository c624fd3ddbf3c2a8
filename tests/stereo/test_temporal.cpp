// The temporal flicker metric: the change of the eye's error along the camera's motion, zero for the reference
// and for an exact method, zero for an error that sticks to the surface, the change where it comes and goes.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/stereo/reprojection.h"
#include "s3d/stereo/temporal.h"

namespace s3d::stereo {
namespace {

constexpr std::uint32_t kWidth = 16, kHeight = 5;

// A 90-degree frustum (tangent +-1 over the width): one pixel is 1/8 tangent units.
glm::mat4 projection() {
  glm::mat4 p(0.0f);
  p[0][0] = 1.0f;
  p[1][1] = 1.0f;
  p[2][3] = -1.0f;
  p[3][2] = 0.1f;
  return p;
}

ImageRGBA8 ramp(int offset, int shift = 0) {
  ImageRGBA8 image(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y)[c] = std::uint8_t(10 + 9 * ((int(x) - shift) & 15) + 7 * y + 3 * c + offset);
  return image;
}

DepthImage plane(float depth) {
  DepthImage image(kWidth, kHeight);
  for (float& d : image.pixels) d = depth;
  return image;
}

EyeFrame frame(const ImageRGBA8& synthesized, const ImageRGBA8& reference, const DepthImage& depth) {
  return EyeFrame{&synthesized, &reference, &depth, {}, 0};
}

const gpu::EyeMotion kStatic = staticEyeMotion(projection());

TEST(TemporalFlicker, IsZeroForTheReferenceAndAnExactMethodOnAStaticCamera) {
  // The reference changes between the frames (lighting, parameters), the camera does not.
  const ImageRGBA8 before = ramp(0), after = ramp(9);
  const DepthImage depth = plane(4.0f);
  const FlickerStats reference = temporalFlicker(frame(after, after, depth), frame(before, before, depth), kStatic, {}, {});
  EXPECT_EQ(reference.all.meanLevels, 0.0);
  EXPECT_EQ(reference.all.pixelCount, kWidth * kHeight);
  EXPECT_EQ(reference.newlyVisiblePixels, 0u);
}

TEST(TemporalFlicker, IsZeroForAStaticErrorOnAStaticCamera) {
  const ImageRGBA8 eye = ramp(0), reference = ramp(40);  // a large error that stays put
  const DepthImage depth = plane(4.0f);
  const FlickerStats stats = temporalFlicker(frame(eye, reference, depth), frame(eye, reference, depth), kStatic,
                                             std::vector<std::uint8_t>(kWidth * kHeight, 1), {});
  // Tolerance: the static round trip through the projection lands within 1e-5 px of the pixel centre.
  EXPECT_NEAR(stats.all.meanLevels, 0.0, 1e-3);
  EXPECT_NEAR(stats.halo.meanLevels, 0.0, 1e-3);
  EXPECT_EQ(stats.disocclusion.pixelCount, 0u);
}

TEST(TemporalFlicker, MeasuresAnErrorThatComesAndGoesPerRegion) {
  // A static camera and reference; the eye gains +12 levels on every channel in the left half of the frame only.
  const ImageRGBA8 reference = ramp(0);
  const DepthImage depth = plane(4.0f);
  ImageRGBA8 flickering = reference;
  std::vector<std::uint8_t> halo(kWidth * kHeight, 0), disocclusion(kWidth * kHeight, 0);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth / 2; ++x) {
      for (int c = 0; c < 3; ++c) flickering.at(x, y)[c] = std::uint8_t(flickering.at(x, y)[c] + 12);
      halo[y * kWidth + x] = 1;
    }
  for (std::uint32_t y = 0; y < kHeight; ++y) disocclusion[y * kWidth + 12] = 1;  // a column that did not flicker
  const FlickerStats stats =
      temporalFlicker(frame(flickering, reference, depth), frame(reference, reference, depth), kStatic, halo, disocclusion);
  // Tolerance as above: a static round trip.
  EXPECT_NEAR(stats.all.meanLevels, 6.0, 1e-3);  // half the pixels by 12
  EXPECT_NEAR(stats.halo.meanLevels, 12.0, 1e-3);
  EXPECT_EQ(stats.halo.pixelCount, kWidth * kHeight / 2);
  EXPECT_NEAR(stats.disocclusion.meanLevels, 0.0, 1e-3);
  // Cropping 4 columns a side leaves columns 4..11: 4 of their 8 columns flicker.
  EyeFrame current = frame(flickering, reference, depth), previous = frame(reference, reference, depth);
  current.cropColumns = previous.cropColumns = 4;
  const FlickerStats cropped = temporalFlicker(current, previous, kStatic, {}, {});
  EXPECT_NEAR(cropped.all.meanLevels, 6.0, 1e-3);
  EXPECT_EQ(cropped.all.pixelCount, 8u * kHeight);
}

// The camera moves 1 unit to the right between the frames; a plane at depth 4 then moves 2 pixels left on screen:
// the current pixel x shows what the previous frame showed at x + 2.
const gpu::EyeMotion kSideways = eyeMotion(glm::mat4(1.0f), projection(),
                                           glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)), projection());

TEST(TemporalFlicker, FollowsTheSurfaceAsTheCameraMoves) {
  const ImageRGBA8 before = ramp(0, 2), after = ramp(0, 0);  // the texture two pixels further right before
  const DepthImage depth = plane(4.0f);
  // An error stuck to the surface (it moved with it) is no flicker; nor is the reference's own change.
  const ImageRGBA8 errorBefore = ramp(5, 2), errorAfter = ramp(5, 0);
  const FlickerStats stuck = temporalFlicker(frame(errorAfter, after, depth), frame(errorBefore, before, depth), kSideways, {}, {});
  EXPECT_NEAR(stuck.all.meanLevels, 0.0, 1e-3);  // tolerance: the reprojection lands within 1e-4 px of texel centres
  EXPECT_EQ(stuck.newlyVisiblePixels, 2u * kHeight);  // the two columns that came in at the right edge
  EXPECT_EQ(stuck.all.pixelCount, (kWidth - 2) * kHeight);
  EXPECT_NEAR(temporalFlicker(frame(after, after, depth), frame(before, before, depth), kSideways, {}, {}).all.meanLevels,
              0.0, 1e-9);
  // An error that stays on the screen while the surface moves under it changes on the surface.
  const ImageRGBA8 screenError = ramp(5, 0);
  const FlickerStats onScreen =
      temporalFlicker(frame(screenError, after, depth), frame(ramp(5, 0), before, depth), kSideways, {}, {});
  EXPECT_GT(onScreen.all.meanLevels, 1.0);
}

TEST(TemporalFlicker, LeavesOutWhatTheMotionDisoccluded) {
  // Before, a near surface (depth 1) covered the columns the background at depth 4 now shows there.
  const ImageRGBA8 before = ramp(0, 2), after = ramp(0, 0);
  const DepthImage depthAfter = plane(4.0f);
  DepthImage depthBefore = plane(4.0f);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 6; x < 10; ++x) *depthBefore.at(x, y) = 1.0f;
  const FlickerStats stats = temporalFlicker(frame(after, after, depthAfter), frame(before, before, depthBefore), kSideways, {}, {});
  // Current columns 4..7 land on the occluder's columns 6..9 and 2 columns come in from the edge.
  EXPECT_EQ(stats.newlyVisiblePixels, (4u + 2u) * kHeight);
}

TEST(TemporalFlicker, TheWeaponStaysOnScreen) {
  // First-person pixels do not move with the world: compared with the same pixel of the previous frame.
  const ImageRGBA8 reference = ramp(0);
  const DepthImage depth = plane(0.5f);
  EyeFrame current = frame(reference, reference, depth), previous = frame(reference, reference, depth);
  ImageRGBA8 wrong = reference;
  wrong.at(3, 2)[0] = std::uint8_t(wrong.at(3, 2)[0] + 30);
  current.synthesized = &wrong;
  current.firstPerson.assign(kWidth * kHeight, 1);
  previous.firstPerson.assign(kWidth * kHeight, 1);
  const FlickerStats stats = temporalFlicker(current, previous, kSideways, {}, {});
  EXPECT_EQ(stats.newlyVisiblePixels, 0u);
  EXPECT_NEAR(stats.all.meanLevels, 10.0 / double(kWidth * kHeight), 1e-9);  // 30 levels on one channel of one pixel
}

// A per-layer reference (a nonlinear map): one eye camera per segment of the frame's curve, each a camera at world
// x = `x` looking down -z with projection shift P20 = `shift`.
struct LayerCamera {
  float x, shift;
};
glm::mat4 viewAt(float x) { return glm::translate(glm::mat4(1.0f), glm::vec3(-x, 0.0f, 0.0f)); }
glm::mat4 projectionWithShift(float shift) {
  glm::mat4 p = projection();
  p[2][0] = shift;
  return p;
}
ReferenceCameras layeredCameras(const std::vector<LayerCamera>& layers, const std::vector<double>& boundaries,
                                std::uint8_t layerOfEveryPixel) {
  ReferenceCameras cameras;
  for (std::size_t k = 0; k < layers.size(); ++k) {
    cameras.view.push_back(viewAt(layers[k].x));
    cameras.projection.push_back(projectionWithShift(layers[k].shift));
    cameras.segments.push_back({k == 0 ? 0.0 : boundaries[k - 1], k + 1 == layers.size() ? INFINITY : boundaries[k]});
  }
  cameras.layerOfPixel.assign(kWidth * kHeight, layerOfEveryPixel);
  return cameras;
}
// A plane at depth `depth` whose error (synthesized - reference, 8-bit levels) is 7.3 levels per world unit of x
// (3.65 per pixel at depth 4: the rounding to whole levels differs from pixel to pixel): an error that sticks to
// the surface, as a layer's camera sees it (x_ndc = X / d - P20 with P00 = 1).
ImageRGBA8 stuckError(const LayerCamera& camera, float depth) {
  ImageRGBA8 image(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float ndc = 2.0f * (float(x) + 0.5f) / float(kWidth) - 1.0f;
      const float worldX = camera.x + (ndc + camera.shift) * depth;
      const float value = 100.0f + 7.3f * worldX;  // the reference is 100 everywhere
      EXPECT_TRUE(value > 0.0f && value < 255.0f) << worldX;
      for (int c = 0; c < 3; ++c) image.at(x, y)[c] = std::uint8_t(std::lround(value));
    }
  return image;
}

TEST(TemporalFlicker, ALayeredReferenceMovesEachPixelWithItsOwnLayersCameras) {
  // The plane at depth 4 (inverse depth 0.25). Current frame (centre at x = 0.5): segments [0, 0.2] and
  // [0.2, inf], so layer 1 renders the plane. Previous frame (centre at x = 0): segments [0, 0.3] and [0.3, inf],
  // so there layer 0 rendered it. The cameras differ per layer and per frame, as a per-frame curve's do.
  const float depth = 4.0f;
  const std::vector<LayerCamera> currentLayers{{0.5f - 0.3f, 0.2f}, {0.5f + 0.2f, -0.05f}};
  const std::vector<LayerCamera> previousLayers{{0.1f, 0.02f}, {-0.4f, -0.1f}};
  const ReferenceCameras current = layeredCameras(currentLayers, {0.2}, 1);
  const ReferenceCameras previous = layeredCameras(previousLayers, {0.3}, 0);
  const ImageRGBA8 reference(kWidth, kHeight, 100);  // error = eye - 100
  const DepthImage plane4 = plane(depth);
  const ImageRGBA8 eyeNow = stuckError(currentLayers[1], depth), eyeBefore = stuckError(previousLayers[0], depth);
  const EyeFrame now = frame(eyeNow, reference, plane4), before = frame(eyeBefore, reference, plane4);
  // Tolerance 0.75 levels (the mean of two roundings to whole levels is about 1/3): an error stuck to the surface is
  // no flicker when every pixel moves from its own layer's camera to the one that rendered it before.
  const FlickerStats layered = temporalFlicker(now, before, current, previous, {}, {});
  EXPECT_LT(layered.all.meanLevels, 0.75);
  EXPECT_GT(layered.all.pixelCount, kWidth * kHeight / 2);
  // Either camera taken by its index instead (the same layer number before, or layer 0 now) misplaces the surface
  // by half a world unit or more: 3.6 levels and more on this error.
  const FlickerStats sameIndex = temporalFlicker(
      now, before, eyeMotion(current.view[1], current.projection[1], previous.view[1], previous.projection[1]), {}, {});
  const FlickerStats firstLayer = temporalFlicker(
      now, before, eyeMotion(current.view[0], current.projection[0], previous.view[0], previous.projection[0]), {}, {});
  EXPECT_GT(sameIndex.all.meanLevels, 2.5);
  EXPECT_GT(firstLayer.all.meanLevels, 2.5);
}

TEST(TemporalFlicker, LayeredCamerasMustMatchTheirSegmentsAndTheImage) {
  const ImageRGBA8 a = ramp(0);
  const DepthImage depth = plane(4.0f);
  const ReferenceCameras good = layeredCameras({{0.0f, 0.0f}, {0.1f, 0.0f}}, {0.5}, 1);
  ReferenceCameras missingSegment = good;
  missingSegment.segments.pop_back();
  ReferenceCameras unknownLayer = good;
  unknownLayer.layerOfPixel[3] = 2;
  ReferenceCameras wrongSize = good;
  wrongSize.layerOfPixel.resize(7);
  for (const ReferenceCameras* bad : {&missingSegment, &unknownLayer, &wrongSize})
    EXPECT_THROW((void)temporalFlicker(frame(a, a, depth), frame(a, a, depth), *bad, good, {}, {}), std::invalid_argument);
  EXPECT_THROW((void)temporalFlicker(frame(a, a, depth), frame(a, a, depth), good, ReferenceCameras{}, {}, {}),
               std::invalid_argument);
}

TEST(TemporalFlicker, RejectsImagesOfDifferentSizes) {
  const ImageRGBA8 a = ramp(0);
  const ImageRGBA8 b(5, 4);
  const DepthImage depth = plane(4.0f), otherDepth(5, 4);
  EXPECT_THROW((void)temporalFlicker(frame(a, a, depth), frame(b, b, otherDepth), kStatic, {}, {}), std::invalid_argument);
  EXPECT_THROW((void)temporalFlicker(frame(a, a, depth), frame(a, a, depth), kStatic, std::vector<std::uint8_t>(3), {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace s3d::stereo
