// Eye views for the stereo frame: the kernels' parallax derived from them is the views' own eye-to-center mapping
// on the shared center view, and the views the kernels cannot reproduce are refused naming the field.
#include <gtest/gtest.h>

#include <cmath>

#include "s3d/stereo/eye_views.h"

namespace s3d::stereo {
namespace {

constexpr std::uint32_t kWidth = 1920, kHeight = 1080;

// A 16:9 screen 1 m wide seen at 2 m by eyes 65 mm apart (samples/views/tv-pair.json's geometry): each eye's
// frustum through the screen's edges, tangents +-0.5 shifted by 0.0325 / 2 towards the other eye.
ViewConfiguration tvPair() {
  const double shift = 0.0325 / 2.0, up = std::atan(0.28125);
  ViewConfiguration views;
  views.eyes[0] = {-0.0325, std::atan(-0.5 + shift), std::atan(0.5 + shift), up, -up, kWidth, kHeight};
  views.eyes[1] = {0.0325, std::atan(-0.5 - shift), std::atan(0.5 - shift), up, -up, kWidth, kHeight};
  return views;
}

// samples/views/headset-pair.json at the TV pair's size: wider outwards than inwards, mirrored.
ViewConfiguration headsetPair() {
  ViewConfiguration views;
  views.eyes[0] = {-0.0315, -0.7854, 0.6981, 0.7330, -0.8203, kWidth, kHeight};
  views.eyes[1] = {0.0315, -0.6981, 0.7854, 0.7330, -0.8203, kWidth, kHeight};
  return views;
}

TEST(EyeViews, TheKernelsParallaxIsTheViewsMappingOnTheSharedCenter) {
  // The kernels read eye pixel x of the left eye from center column x + W m (1 - zpd / d), the right eye's from
  // x - W m (1 - zpd / d), same row. 1e-3 px: m and zpd are floats (relative 6e-8 of up to 210 px here).
  const ViewConfiguration views = tvPair();
  ASSERT_FALSE(eyeViewsProblem(views, kWidth, kHeight).has_value());
  const EyeViewsParallax parallax = eyeViewsParallax(views);
  const CenterView center = sharedCenterView(views);
  for (int eye = 0; eye < 2; ++eye)
    for (double depth : {0.3, 1.0, 2.0, 7.5, 900.0})
      for (double u : {0.5, 400.25, 960.5, 1919.5})
        for (double v : {0.5, 540.5, 1079.5}) {
          const double shift = double(kWidth) * double(parallax.maxSeparation) *
                               (1.0 - double(parallax.zeroParallaxDistance) / depth);
          const glm::dvec2 mapped = centerPixelForEyePixel(views, center, eye, {u, v}, depth);
          EXPECT_NEAR(mapped.x, u + (eye == 0 ? shift : -shift), 1e-3) << "eye " << eye << " depth " << depth;
          EXPECT_NEAR(mapped.y, v, 1e-9) << "eye " << eye;
        }
}

TEST(EyeViews, TheTvPairConvergesOnItsScreen) {
  // Each eye's frustum is shifted by 0.01625 of the 1.0 tangent width (the half baseline over the distance);
  // 1e-6: float parameters.
  const EyeViewsParallax parallax = eyeViewsParallax(tvPair());
  EXPECT_NEAR(parallax.zeroParallaxDistance, 2.0, 1e-6);
  EXPECT_NEAR(parallax.maxSeparation, 0.01625, 1e-6);
}

TEST(EyeViews, TheZeroParallaxDistanceIsInWorldUnits) {
  ViewConfiguration views = tvPair();
  const EyeViewsParallax metres = eyeViewsParallax(views);
  views.worldScale = 100.0;  // centimetres
  const EyeViewsParallax centimetres = eyeViewsParallax(views);
  EXPECT_FLOAT_EQ(centimetres.zeroParallaxDistance, 100.0f * metres.zeroParallaxDistance);
  EXPECT_FLOAT_EQ(centimetres.maxSeparation, metres.maxSeparation);
}

TEST(EyeViews, TheSharedCenterIsTheMeanFrustumAtTheEyesMidpoint) {
  ViewConfiguration views = tvPair();
  views.eyes[0].positionX = 0.1, views.eyes[1].positionX = 0.165;  // a head origin 0.1325 m left of the midpoint
  const CenterView center = sharedCenterView(views);
  EXPECT_NEAR(center.tanLeft, -0.5, 1e-12);
  EXPECT_NEAR(center.tanRight, 0.5, 1e-12);
  EXPECT_NEAR(center.tanUp, 0.28125, 1e-12);
  EXPECT_NEAR(center.eyeOffset[0], -0.0325, 1e-12);
  EXPECT_NEAR(center.eyeOffset[1], 0.0325, 1e-12);
  EXPECT_EQ(center.width, kWidth);
  EXPECT_EQ(center.height, kHeight);
}

TEST(EyeViews, AHeadsetsOutwardTurnedFrustaAreRefusedNamingTheLeftAngle) {
  const std::optional<EyeViewsProblem> found = eyeViewsProblem(headsetPair(), kWidth, kHeight);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(fieldName(*found), "eyes[0].angleLeft");
  EXPECT_NE(found->problem.find("converging eyes only"), std::string::npos) << found->problem;
}

TEST(EyeViews, ParallelEyesWithOneFrustumAreRefused) {
  ViewConfiguration views = tvPair();
  views.eyes[0].angleLeft = views.eyes[1].angleLeft;
  views.eyes[0].angleRight = views.eyes[1].angleRight;
  const std::optional<EyeViewsProblem> found = eyeViewsProblem(views, kWidth, kHeight);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(fieldName(*found), "eyes[0].angleLeft");
}

TEST(EyeViews, VerticalFieldsDifferingByMoreThanAQuarterRowAreRefused) {
  // One row is 0.5625 / 1080 = 5.2e-4 tangent units: 1e-4 (0.19 rows) passes, 2e-4 (0.38 rows) does not.
  ViewConfiguration views = tvPair();
  views.eyes[1].angleUp = std::atan(0.28125 + 1e-4);
  EXPECT_FALSE(eyeViewsProblem(views, kWidth, kHeight).has_value());
  views.eyes[1].angleUp = std::atan(0.28125 + 2e-4);
  const std::optional<EyeViewsProblem> found = eyeViewsProblem(views, kWidth, kHeight);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(fieldName(*found), "eyes[1].angleUp");
}

TEST(EyeViews, HorizontalExtentsDifferingByMoreThanAQuarterColumnAreRefused) {
  // One column is 1.0 / 1920 = 5.2e-4 tangent units.
  ViewConfiguration views = tvPair();
  views.eyes[1].angleRight = std::atan(std::tan(views.eyes[1].angleRight) + 2e-4);
  const std::optional<EyeViewsProblem> found = eyeViewsProblem(views, kWidth, kHeight);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(fieldName(*found), "eyes[1].angleRight");
}

TEST(EyeViews, AnEyeOfAnotherSizeThanTheFrameIsRefused) {
  const std::optional<EyeViewsProblem> found = eyeViewsProblem(tvPair(), kWidth, kHeight / 2);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(fieldName(*found), "eyes[0].height");
}

TEST(EyeViews, FrustaShiftedByMoreThanAQuarterOfTheWidthAreRefused) {
  ViewConfiguration views = tvPair();
  views.eyes[0].angleLeft = std::atan(-0.5 + 0.3), views.eyes[0].angleRight = std::atan(0.5 + 0.3);
  views.eyes[1].angleLeft = std::atan(-0.5 - 0.3), views.eyes[1].angleRight = std::atan(0.5 - 0.3);
  const std::optional<EyeViewsProblem> found = eyeViewsProblem(views, kWidth, kHeight);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(fieldName(*found), "eyes[0].angleLeft");
  EXPECT_NE(found->problem.find("0.3 of the width"), std::string::npos) << found->problem;
}

TEST(EyeViews, OutOfRangeValuesAreRefusedNamingTheField) {
  ViewConfiguration views = tvPair();
  views.worldScale = NAN;
  EXPECT_EQ(fieldName(*eyeViewsProblem(views, kWidth, kHeight)), "worldScale");
  views = tvPair();
  views.eyes[1].angleDown = -1.6;  // beyond a quarter turn
  EXPECT_EQ(fieldName(*eyeViewsProblem(views, kWidth, kHeight)), "eyes[1].angleDown");
  views = tvPair();
  views.eyes[0].angleRight = -0.46;  // left of its own angleLeft
  EXPECT_EQ(fieldName(*eyeViewsProblem(views, kWidth, kHeight)), "eyes[0].angleRight");
  views = tvPair();
  views.eyes[1].positionX = -0.04;  // the right eye left of the left one
  EXPECT_EQ(fieldName(*eyeViewsProblem(views, kWidth, kHeight)), "eyes[1].positionX");
}

}  // namespace
}  // namespace s3d::stereo
