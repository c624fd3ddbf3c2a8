// The two-pass reference cameras: a point at depth d lands parallaxFromDepth(d) * width away from its
// center-view position, checked in double precision.
#include <gtest/gtest.h>

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
  // Tolerance 1e-4 px: the requirement; double precision leaves ~1e-9 px of rounding.
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
