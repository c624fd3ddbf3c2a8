// The per-frame comfort report: pixels beyond the 1-degree rule, stereo window violations, and the rules that
// keep every pixel at or behind the screen plane.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/zero_parallax_control.h"

namespace s3d::comfort {
namespace {

TEST(VergenceDistance, IsTheScreenAtZeroParallaxAndInfinityAtTheEyeSeparation) {
  const DisplayProfile tv = builtInDisplayProfile("tv55");
  EXPECT_NEAR(vergenceDistanceMeters(tv, 0.0), 2.5, 1e-6);  // float profile lengths: 1e-6 m
  // Crossed parallax of one interocular distance: the lines of sight meet halfway to the screen.
  EXPECT_NEAR(vergenceDistanceMeters(tv, -0.063), 1.25, 1e-6);
  EXPECT_EQ(vergenceDistanceMeters(tv, double(tv.interocularMeters)), std::numeric_limits<double>::infinity());
}

TEST(FrameComfort, CountsPixelsBeyondTheOneDegreeRule) {
  // Row 0 on the screen plane; row 1 at a quarter of the zero-parallax distance: parallax
  // 2 * 0.05 * (1 - 4) = -30 % of a 0.60 m monitor, about 18 cm crossed: far beyond 60 arcmin at 0.7 m.
  DepthImage depth(40, 2, 1.0f);
  for (std::uint32_t x = 0; x < 40; ++x) *depth.at(x, 1) = 0.25f;
  stereo::StereoParameters parameters{0.05f, 1.0f, 0.0f};
  const FrameComfort comfort = frameComfort(depth, parameters, builtInDisplayProfile("monitor27"));
  EXPECT_DOUBLE_EQ(comfort.parallax.shareBeyondOneDegree, 0.5);
}

TEST(EyeViewComfort, ConflictAndOneDegreeShareOfAHeadsetsEyeByHand) {
  // The hmd profile focuses at 1.3 m; world scale 2 (2 world units per metre). Pixels: on the focal plane (2.6
  // units), at 0.3 m (0.6 units), the sky, and one of unknown depth (left out).
  const DisplayProfile hmd = builtInDisplayProfile("hmd");
  DepthImage depth(4, 1);
  depth.pixels = {2.6f, 0.6f, std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()};
  std::vector<float> perPixel;
  const EyeViewComfort comfort = eyeViewComfort(depth, 2.0, 0.063, hmd, &perPixel);
  EXPECT_EQ(comfort.pixelCount, 3u);
  const double focal = 1.0 / 1.3;
  // Tolerance 1e-5 D: depths held as floats.
  EXPECT_NEAR(perPixel[0], 0.0, 1e-5);
  EXPECT_NEAR(perPixel[1], 1.0 / 0.3 - focal, 1e-5);
  EXPECT_NEAR(perPixel[2], focal, 1e-5);
  EXPECT_TRUE(std::isnan(perPixel[3]));
  EXPECT_NEAR(comfort.maxConflictDiopters, 1.0 / 0.3 - focal, 1e-5);
  EXPECT_NEAR(comfort.meanConflictDiopters, (1.0 / 0.3 - focal + focal) / 3.0, 1e-5);
  EXPECT_NEAR(comfort.nearestMeters, 0.3, 1e-6);
  // Vergence beyond 1 degree from the focal plane's (63 mm eyes): 0.3 m yes (10.6 degrees against 2.8), the sky
  // (2.8 degrees off) too.
  EXPECT_NEAR(comfort.shareBeyondOneDegree, 2.0 / 3.0, 1e-12);
  EXPECT_THROW((void)eyeViewComfort(depth, 0.0, 0.063, hmd), std::invalid_argument);
}

TEST(EyeViewComfort, TheOneDegreeRuleHoldsOnBothSidesOfTheFocalPlane) {
  // Focal plane at 1.3 m, 63 mm eyes (vergence 2.776 degrees): the rule's limits lie at 0.956 m and 2.033 m. Just
  // inside them (0.97 m: 0.94 degrees off, 2.0 m: 0.97) and just beyond (0.94 m: 1.06, 2.07 m: 1.03); world
  // scale 1.
  const DisplayProfile hmd = builtInDisplayProfile("hmd");
  DepthImage depth(5, 1);
  depth.pixels = {1.3f, 0.97f, 2.0f, 0.94f, 2.07f};
  const EyeViewComfort comfort = eyeViewComfort(depth, 1.0, 0.063, hmd);
  EXPECT_EQ(comfort.pixelCount, 5u);
  EXPECT_NEAR(comfort.shareBeyondOneDegree, 2.0 / 5.0, 1e-12);
  // Wider eyes turn the same depths' vergence further from the focal plane's: at 80 mm all four off-focal pixels
  // are beyond (1.20-1.35 degrees off).
  EXPECT_NEAR(eyeViewComfort(depth, 1.0, 0.080, hmd).shareBeyondOneDegree, 4.0 / 5.0, 1e-12);
}

TEST(FrameComfort, WindowViolationsAreNegativeParallaxRunsTouchingTheLeftOrRightEdge) {
  // 3 near columns at the left edge and 2 at the right edge of 3 rows; a near block in the middle does not count.
  DepthImage depth(20, 3, 2.0f);
  for (std::uint32_t y = 0; y < 3; ++y) {
    for (std::uint32_t x : {0u, 1u, 2u, 18u, 19u}) *depth.at(x, y) = 0.5f;
    for (std::uint32_t x = 8; x < 12; ++x) *depth.at(x, y) = 0.5f;
  }
  stereo::StereoParameters parameters{0.02f, 1.0f, 0.0f};  // no crop: the visible image is all 20 columns
  const FrameComfort comfort = frameComfort(depth, parameters, builtInDisplayProfile("tv55"));
  EXPECT_EQ(comfort.windowViolationPixels, 3u * (3u + 2u));
  EXPECT_EQ(comfort.windowViolationColumns, 3u);
}

TEST(FrameComfort, ViolationFlagsMarkThePixelsItCounts) {
  // The window-violation layout above in one row: the edge runs are flagged, the near block in the middle is
  // not. On tv55 the near pixels (2 * 0.02 * (1 - 2) = -4 % of 1.22 m: 4.9 cm crossed, 67 arcmin) are beyond
  // 1 degree, the far ones (+2 %: 34 arcmin) are not.
  DepthImage depth(20, 1, 2.0f);
  for (std::uint32_t x : {0u, 1u, 2u, 18u, 19u, 9u, 10u}) *depth.at(x, 0) = 0.5f;
  stereo::StereoParameters parameters{0.02f, 1.0f, 0.0f};
  std::vector<std::uint8_t> violations;
  const FrameComfort comfort = frameComfort(depth, parameters, builtInDisplayProfile("tv55"), &violations);
  ASSERT_EQ(violations.size(), 20u);
  for (std::uint32_t x = 0; x < 20; ++x) {
    EXPECT_EQ(violations[x] & kWindowViolation, (x <= 2 || x >= 18) ? kWindowViolation : 0) << x;
    EXPECT_EQ(violations[x] & kBeyondOneDegree, *depth.at(x, 0) < 1.0f ? kBeyondOneDegree : 0) << x;
  }
  EXPECT_EQ(comfort.windowViolationPixels, 5u);
  // The monitor layout of the 1-degree test: the near row is flagged, the screen-plane row is not.
  DepthImage nearRow(4, 2, 1.0f);
  for (std::uint32_t x = 0; x < 4; ++x) *nearRow.at(x, 1) = 0.25f;
  (void)frameComfort(nearRow, {0.05f, 1.0f, 0.0f}, builtInDisplayProfile("monitor27"), &violations);
  for (std::uint32_t x = 0; x < 4; ++x) {
    EXPECT_EQ(violations[x] & kBeyondOneDegree, 0) << x;
    EXPECT_EQ(violations[4 + x] & kBeyondOneDegree, kBeyondOneDegree) << x;
  }
}

TEST(FrameComfort, WindowViolationsStartInsideTheEdgeCrop) {
  // edgeCrop 0.1 of 20 columns: columns 0-1 and 18-19 are black; the near run at columns 2-3 touches the edge.
  DepthImage depth(20, 1, 2.0f);
  *depth.at(2, 0) = *depth.at(3, 0) = 0.5f;
  stereo::StereoParameters parameters{0.02f, 1.0f, 0.1f};
  EXPECT_EQ(frameComfort(depth, parameters, builtInDisplayProfile("tv55")).windowViolationPixels, 2u);
}

TEST(PushWeaponBehindScreen, SqueezesTheNearestPointOntoThePlaneKeepingTheFarthest) {
  stereo::StereoParameters parameters;
  parameters.zeroParallaxDistance = 0.7f;
  parameters.weaponDepthOffset = 0.3f;  // pushed range 0.3 + [0.27, 0.6] = [0.57, 0.9]
  parameters.weaponDepthScale = 1.0f;
  const stereo::StereoParameters pushed = pushWeaponBehindScreen(parameters, 0.27f, 0.6f);
  EXPECT_NEAR(pushed.weaponDepthOffset + pushed.weaponDepthScale * 0.27f, 0.7f, 1e-6f);  // float rounding
  EXPECT_NEAR(pushed.weaponDepthOffset + pushed.weaponDepthScale * 0.6f, 0.9f, 1e-6f);
}

TEST(PushWeaponBehindScreen, ShiftsTheWeaponBackWhenItLiesWhollyInFront) {
  stereo::StereoParameters parameters;
  parameters.zeroParallaxDistance = 2.0f;
  parameters.weaponDepthOffset = 0.0f;
  parameters.weaponDepthScale = 1.0f;
  const stereo::StereoParameters pushed = pushWeaponBehindScreen(parameters, 0.27f, 0.6f);
  EXPECT_NEAR(pushed.weaponDepthOffset, 2.0f - 0.27f, 1e-6f);
  EXPECT_EQ(pushed.weaponDepthScale, 1.0f);
}

TEST(PushWeaponBehindScreen, LeavesAWeaponBehindThePlaneAlone) {
  stereo::StereoParameters parameters;  // 1 + [0.27, 0.6] behind a plane at 1 m
  const stereo::StereoParameters pushed = pushWeaponBehindScreen(parameters, 0.27f, 0.6f);
  EXPECT_EQ(pushed.weaponDepthOffset, parameters.weaponDepthOffset);
  EXPECT_EQ(pushed.weaponDepthScale, parameters.weaponDepthScale);
}

TEST(ZeroParallaxControlLimit, CutsAtOnceAndTheNextFramesStayBounded) {
  ZeroParallaxController control;  // rest 1 m, 1 m/s
  EXPECT_EQ(control.limit(0.4f), 0.4f);
  float previous = control.current();
  for (int frame = 0; frame < 10; ++frame) {  // open space: back toward the rest value, bounded, no jump
    const float next = control.update(std::nullopt, 1.0f / 12.0f);
    EXPECT_LE(next - previous, 1.0f / 12.0f + 1e-6f);
    EXPECT_GE(next, previous);
    previous = next;
  }
  EXPECT_EQ(control.limit(2.0f), previous);  // a ceiling above the value changes nothing
}

TEST(CrosshairSmoother, ApproachesANearerPlacementWithoutOvershoot) {
  CrosshairSmoother smoother(0.1f);
  EXPECT_EQ(smoother.update({8.0f, false}, 1.0f / 12.0f), 8.0f);  // the first frame starts at its placement
  float previous = 8.0f;
  for (int frame = 0; frame < 24; ++frame) {
    const float depth = smoother.update({3.75f, true, 4.0f}, 1.0f / 12.0f);
    EXPECT_LE(depth, previous);  // monotonic (it reaches 3.75 exactly once float rounding runs out)
    EXPECT_GE(depth, 3.75f);
    previous = depth;
  }
  EXPECT_LT(smoother.current(), 8.0f);
  EXPECT_NEAR(previous, 3.75f, 1e-3f);  // two seconds at 0.1 s: the tail is below a millimetre
}

TEST(CrosshairSmoother, IsNeverLeftBehindTheSurfaceItAimsAt) {
  CrosshairSmoother smoother(0.5f);  // slow: without the clamp it would lag far behind
  smoother.update({8.0f, false}, 1.0f / 12.0f);
  EXPECT_EQ(smoother.update({1.75f, true, 2.0f}, 1.0f / 12.0f), 2.0f);  // a wall appears 2 m ahead
  EXPECT_LT(smoother.update({1.75f, true, 2.0f}, 1.0f / 12.0f), 2.0f);  // then it glides the last margin
}

}  // namespace
}  // namespace s3d::comfort
