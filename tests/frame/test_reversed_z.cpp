// Reversed-Z (RendererOptions::reversedZ): the reconstruction of linear depth from a reversed depth buffer, and
// the renderer giving the same linear depth and the same stereo eyes in both depth conventions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/gpu/linear_depth.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/synthesis.h"
#include "vulkan_test.h"

namespace s3d {
namespace {

constexpr float kWorldNear = 0.1f, kWorldFar = 1000.0f, kWeaponNear = 0.02f, kWeaponFar = 4.0f, kSplit = 0.1f;

// Device depth a reversed zero-to-one projection (near n -> 1, far f -> 0) writes for linear depth d, in
// viewport range [a, b].
float reversedDeviceDepthOf(double d, double n, double f, double a, double b) {
  double ndcZ = n / (n - f) + n * f / ((f - n) * d);
  return float(a + ndcZ * (b - a));
}

TEST(ReversedLinearDepth, WorldDepthIsReconstructed) {
  const gpu::LinearDepthParams p = gpu::makeReversedLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  // Relative tolerance 1e-5: near 0 floats are dense, so the far end is as exact as the near end (standard Z
  // needs 2e-3 here, test_linear_depth.cpp).
  for (double d : {0.1001, 0.5, 2.0, 10.0, 100.0, 900.0})
    EXPECT_NEAR(gpu::linearDepthFromReversedDevice(p, reversedDeviceDepthOf(d, kWorldNear, kWorldFar, 0.0, 1.0 - kSplit)), d,
                d * 1e-5)
        << d;
}

TEST(ReversedLinearDepth, FirstPersonDepthUsesItsOwnRange) {
  const gpu::LinearDepthParams p = gpu::makeReversedLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  for (double d : {0.02, 0.1, 0.3, 0.6, 3.9}) {
    const float device = reversedDeviceDepthOf(d, kWeaponNear, kWeaponFar, 1.0 - kSplit, 1.0);
    ASSERT_GE(device, 1.0f - kSplit);
    // Relative 2e-4: this layer lives in [0.9, 1], where float steps are 6e-8, and its far end is the coarse one
    // now: a step is d^2 / (n * 0.1) * 6e-8 = 1.1e-4 relative at 3.9 m (n = 2 cm). The weapon itself spans
    // 0.27-0.6 m: 1e-5 relative at most.
    EXPECT_NEAR(gpu::linearDepthFromReversedDevice(p, device), d, d * 2e-4) << d;
    EXPECT_TRUE(gpu::isFirstPersonDeviceDepth(p, device));
  }
}

TEST(ReversedLinearDepth, TheClearedZeroIsSkyAtInfiniteDistance) {
  const gpu::LinearDepthParams p = gpu::makeReversedLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  EXPECT_TRUE(std::isinf(gpu::linearDepthFromReversedDevice(p, 0.0f)));
  EXPECT_TRUE(gpu::isSkyDeviceDepth(p, 0.0f));
  EXPECT_FALSE(gpu::isSkyDeviceDepth(p, 1e-30f));  // the smallest depth of a real surface is not sky
}

TEST(ReversedLinearDepth, ReversedProjectionPutsTheNearPlaneAtOneAndTheFarPlaneAtZero) {
  const glm::mat4 reversed =
      renderer::reversedDepthProjection(renderer::vulkanPerspective(1.0f, 1.5f, kWorldNear, kWorldFar), kWorldNear, kWorldFar);
  auto ndcDepth = [&](float viewDepth) {
    const glm::vec4 clip = reversed * glm::vec4(0.0f, 0.0f, -viewDepth, 1.0f);
    return clip.z / clip.w;
  };
  EXPECT_NEAR(ndcDepth(kWorldNear), 1.0f, 1e-6f);
  EXPECT_NEAR(ndcDepth(kWorldFar), 0.0f, 1e-6f);
}

// The courtyard's center view rendered in both depth conventions.
class ReversedZRenderTest : public test::VulkanTest {
 protected:
  static constexpr std::uint32_t kWidth = 96, kHeight = 54;

  struct Frame {
    DepthImage linearDepth;
    stereo::StereoPair eyes;
  };

  Frame render(bool reversedZ, std::uint32_t supersample = 1) {
    renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
    renderer::DeferredRenderer deferred(context(), kWidth, kHeight, {.supersample = supersample, .reversedZ = reversedZ});
    deferred.setScene(scene);
    const stereo::StereoParameters parameters;
    deferred.render(renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight),
                                                 {parameters.weaponDepthOffset, parameters.weaponDepthScale}));
    Frame frame{deferred.readLinearDepth(), {}};
    frame.eyes = stereo::synthesizeTimed(context(), deferred.displayColor(), deferred.linearDepth(), parameters).eyes;
    return frame;
  }
};

// Largest relative difference of the finite linear depths; fails where only one of them is sky.
double largestRelativeDepthDifference(const DepthImage& standard, const DepthImage& reversed) {
  double worst = 0.0;
  for (std::size_t i = 0; i < standard.pixels.size(); ++i) {
    const float a = standard.pixels[i], b = reversed.pixels[i];
    EXPECT_EQ(std::isinf(a), std::isinf(b)) << "sky in one convention only at pixel " << i;
    if (std::isinf(a) || std::isinf(b)) continue;
    worst = std::max(worst, std::abs(double(a) - double(b)) / double(a));
  }
  return worst;
}

TEST_F(ReversedZRenderTest, WithSupersamplingTheNearestSampleIsChosenAlike) {
  // The supersampled resolve keeps each pixel's nearest sample, judged by linear depth read in the buffer's own
  // convention; both conventions must keep the same samples. Same tolerance as below.
  EXPECT_LT(largestRelativeDepthDifference(render(false, 2).linearDepth, render(true, 2).linearDepth), 1e-4);
}

TEST_F(ReversedZRenderTest, ReversedAndStandardZGiveTheSameLinearDepth) {
  // Tolerance: relative 1e-4. Standard Z stores world depth d in [0.1, 1] where a D32 float step is 2^-24 (6e-8),
  // which is a depth step of d^2 / (n * 0.9) * 6e-8: 6.6e-4 m (2e-5 relative) at the courtyard's far wall
  // (~32 m, near 0.1 m); reversed Z is ~100x finer there. The weapon (pushed to 1 m + depth) is first-person
  // depth in a 0.1-wide range: 2e-6 relative. 1e-4 leaves room for the rasterizer's interpolation of each.
  const double worst = largestRelativeDepthDifference(render(false).linearDepth, render(true).linearDepth);
  EXPECT_LT(worst, 1e-4);
  std::printf("reversed vs standard Z: largest relative linear-depth difference %.3g\n", worst);
}

TEST_F(ReversedZRenderTest, ReversedAndStandardZGiveTheSameStereoEyes) {
  // Tolerance: the depth differences above move a pixel's parallax by maxSeparation * zpp * delta(1/d), far under
  // a thousandth of a pixel, and lighting reconstructs positions from the same depth: an 8-bit level can flip
  // where a value sits on a rounding edge. At most 1 level, in at most 1 % of the channel values.
  const Frame standard = render(false), reversed = render(true);
  for (const auto& [a, b] : {std::pair{&standard.eyes.left, &reversed.eyes.left}, std::pair{&standard.eyes.right, &reversed.eyes.right}}) {
    int largest = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a->pixels.size(); ++i) {
      const int difference = std::abs(int(a->pixels[i]) - int(b->pixels[i]));
      largest = std::max(largest, difference);
      differing += difference != 0;
    }
    EXPECT_LE(largest, 1);
    EXPECT_LE(double(differing), 0.01 * double(a->pixels.size()));
    std::printf("reversed vs standard Z eye: %zu of %zu channel values differ, by at most %d\n", differing,
                a->pixels.size(), largest);
  }
}

TEST_F(ReversedZRenderTest, ReversedZKeepsFarDepthPrecise) {
  // A wall facing the camera at 3-9 km, near plane 0.1 m, far plane 100 km (the depth-range scene's planes).
  // Standard Z: a float step near device depth 1 is 6e-8, a depth step of d^2 / (n * 0.9) * 6e-8, 1e-3 to 5e-3
  // relative here. Reversed Z: floats near 0 are dense, so the error is the reconstruction's few ulps. Tolerance
  // 1e-4 relative for reversed Z, and standard Z shown to need more than that somewhere (why the mode exists).
  auto wallDepthError = [&](bool reversedZ, float distance) {
    renderer::Scene scene;
    scene.name = "far wall";
    scene.meshes.push_back(renderer::makeBox(glm::vec3(0.5f)));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.farPlane = 1e5f;
    renderer::Object wall;
    wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -distance - 0.5f)) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(4e4f, 4e4f, 1.0f));
    scene.objects.push_back(wall);
    scene.ambientOcclusion = false;
    renderer::DeferredRenderer deferred(context(), 16, 16, {.reversedZ = reversedZ});
    deferred.setScene(scene);
    deferred.render(renderer::centerViewMatrices(scene, 1.0f));
    return std::abs(double(*deferred.readLinearDepth().at(8, 8)) - double(distance)) / double(distance);
  };
  double worstStandard = 0.0, worstReversed = 0.0;
  for (float distance : {3000.0f, 5000.0f, 7000.0f, 9000.0f}) {
    worstReversed = std::max(worstReversed, wallDepthError(true, distance));
    worstStandard = std::max(worstStandard, wallDepthError(false, distance));
  }
  EXPECT_LT(worstReversed, 1e-4);
  EXPECT_GT(worstStandard, 1e-4);
  std::printf("wall at 3-9 km: relative depth error up to %.3g (standard Z), %.3g (reversed Z)\n", worstStandard,
              worstReversed);
}

TEST_F(ReversedZRenderTest, TheSkyAndTheWeaponKeepTheirLayersWithReversedZ) {
  renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  std::vector<std::uint8_t> masks[2];
  for (bool reversedZ : {false, true}) {
    renderer::DeferredRenderer deferred(context(), kWidth, kHeight, {.reversedZ = reversedZ});
    deferred.setScene(scene);
    deferred.render(renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight)));
    masks[reversedZ] = deferred.readFirstPersonMask();
  }
  EXPECT_EQ(masks[0], masks[1]);
  EXPECT_GT(std::count(masks[1].begin(), masks[1].end(), 1), 0);  // the weapon is in view
}

}  // namespace
}  // namespace s3d
