// The two-pass reference cameras: a point at depth d lands parallaxFromDepth(d) * width away from its
// center-view position, checked in double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/stereo/stereo.h"

namespace s3d::stereo {
namespace {

constexpr double kWidth = 1280.0;

double pixelX(const glm::dmat4& view, const glm::dmat4& projection, const glm::dvec3& world) {
  glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
  return (clip.x / clip.w * 0.5 + 0.5) * kWidth;
}

double pixelY(const glm::dmat4& view, const glm::dmat4& projection, const glm::dvec3& world) {
  glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
  return (clip.y / clip.w * 0.5 + 0.5) * 720.0;
}

struct CenterCamera {
  glm::dmat4 view = glm::lookAt(glm::dvec3(1.0, 1.7, 6.0), glm::dvec3(0.3, 1.2, -4.0), glm::dvec3(0, 1, 0));
  glm::dmat4 projection = [] {
    glm::dmat4 p = glm::perspectiveRH_ZO(1.0, kWidth / 720.0, 0.1, 1000.0);
    p[1][1] = -p[1][1];  // Vulkan's y points down
    return p;
  }();
};

class OffAxisEyeCamera : public ::testing::TestWithParam<double> {};

TEST_P(OffAxisEyeCamera, PointAtEveryDepthLandsWhereTheParallaxFormulaSays) {
  // Tolerance 1e-4 px: the eye cameras' required accuracy; double precision leaves ~1e-9 px of rounding.
  const double maxSeparation = 0.02, zeroParallaxDistance = GetParam();
  CenterCamera center;
  EyeCameraT<double> left = offAxisEyeCamera(center.view, center.projection, Eye::Left, maxSeparation, zeroParallaxDistance);
  EyeCameraT<double> right = offAxisEyeCamera(center.view, center.projection, Eye::Right, maxSeparation, zeroParallaxDistance);
  const glm::dmat4 worldFromView = glm::inverse(center.view);
  for (double depth : {0.1, 0.5, 1.0, 3.0, 10.0, 100.0, 999.0}) {
    for (double ndcX : {-0.8, 0.0, 0.45}) {
      // A view-space point at this depth and horizontal screen position, moved into the world.
      glm::dvec3 viewPoint(ndcX * depth / center.projection[0][0], 0.3 * depth, -depth);
      glm::dvec3 world = glm::dvec3(worldFromView * glm::dvec4(viewPoint, 1.0));
      double parallaxPx = double(maxSeparation * (1.0 - zeroParallaxDistance / depth)) * kWidth;
      double centerX = pixelX(center.view, center.projection, world);
      EXPECT_NEAR(pixelX(left.view, left.projection, world), centerX - parallaxPx, 1e-4) << "depth " << depth;
      EXPECT_NEAR(pixelX(right.view, right.projection, world), centerX + parallaxPx, 1e-4) << "depth " << depth;
      // Parallel axes: no vertical parallax.
      EXPECT_NEAR(pixelY(left.view, left.projection, world), pixelY(center.view, center.projection, world), 1e-4);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ZeroParallaxDistances, OffAxisEyeCamera, ::testing::Values(0.5, 1.0, 4.0));

TEST(OffAxisEyeCameraSetup, EyesAreSeparatedByTwiceTheDerivedOffset) {
  CenterCamera center;
  EyeCameraT<double> left = offAxisEyeCamera(center.view, center.projection, Eye::Left, 0.02, 2.0);
  EyeCameraT<double> right = offAxisEyeCamera(center.view, center.projection, Eye::Right, 0.02, 2.0);
  glm::dvec3 leftPosition(glm::inverse(left.view)[3]), rightPosition(glm::inverse(right.view)[3]);
  double expectedOffset = 2.0 * 0.02 * 2.0 / center.projection[0][0];
  EXPECT_NEAR(glm::distance(leftPosition, rightPosition), 2.0 * expectedOffset, 1e-12);
}

}  // namespace
}  // namespace s3d::stereo

namespace s3d::stereo {
namespace {

// Pixel displacement of a first-person point at camera-space depth d for the left eye's terms.
double leftEyeShiftPx(const OffAxisTerms<double>& terms, double projectionScaleX, double depth) {
  return (projectionScaleX * terms.eyeOffset / depth - terms.frustumShift) * 0.5 * kWidth;
}

TEST(PushedLayerTerms, AScaleOnlyPushIsExactEverywhere) {
  // offset 0: m (1 - zpp / (k d)) is a camera's parallax; tolerance 1e-9 px (double rounding).
  const double p00 = 1.2, m = 0.02, zpp = 1.0, scale = 2.5;
  OffAxisTerms<double> terms = pushedLayerTerms(p00, m, zpp, 0.0, scale, 0.3, 0.6);
  for (double d : {0.1, 0.3, 0.45, 0.6, 3.0})
    EXPECT_NEAR(leftEyeShiftPx(terms, p00, d), -m * (1.0 - zpp / (scale * d)) * kWidth, 1e-9) << d;
}

TEST(PushedLayerTerms, AnOffsetPushIsExactAtTheWeaponsNearestAndFarthestDepth) {
  const double p00 = 1.2, m = 0.02, zpp = 1.0, offset = 1.0, scale = 1.0, nearest = 0.27, farthest = 0.6;
  OffAxisTerms<double> terms = pushedLayerTerms(p00, m, zpp, offset, scale, nearest, farthest);
  for (double d : {nearest, farthest})
    EXPECT_NEAR(leftEyeShiftPx(terms, p00, d), -m * (1.0 - zpp / (offset + scale * d)) * kWidth, 1e-9) << d;
}

TEST(PushedLayerTerms, BetweenTheEndsTheReferenceStaysWithinAPixelOfThePushedParallax) {
  // The chord of 1/d' over 1/d: for the courtyard's weapon (0.27-0.6 m, offset 1 m) at 1280 px the largest
  // gap is 0.59 px; 1 px is the bound the reference promises for a pushed weapon.
  const double p00 = 1.2, m = 0.02, zpp = 1.0, offset = 1.0, scale = 1.0, nearest = 0.27, farthest = 0.6;
  OffAxisTerms<double> terms = pushedLayerTerms(p00, m, zpp, offset, scale, nearest, farthest);
  double largestGapPx = 0.0;
  for (double d = nearest; d <= farthest; d += 0.001) {
    double wanted = -m * (1.0 - zpp / (offset + scale * d)) * kWidth;
    largestGapPx = std::max(largestGapPx, std::abs(leftEyeShiftPx(terms, p00, d) - wanted));
  }
  EXPECT_LT(largestGapPx, 1.0);
  RecordProperty("largestGapPx", std::to_string(largestGapPx));
}

}  // namespace
}  // namespace s3d::stereo
