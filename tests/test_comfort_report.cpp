// The per-frame comfort report: Shibata et al.'s zone of comfort, stereo window violations, and the rules that
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

TEST(ShibataComfortZone, HoldsTheScreenAndFollowsTheFitByHand) {
  // Far limit in diopters (1/v - 0.442) / 1.129, near (1/v + 0.626) / 1.035 (the constants of comfort_report.cpp,
  // written out here); at 0.7 m both limits are finite, at 2.5 m the far one lies beyond infinity.
  const ComfortZone monitor = shibataComfortZone(builtInDisplayProfile("monitor27"));
  EXPECT_NEAR(monitor.farMeters, 1.129 / (1.0 / 0.7 - 0.442), 1e-6);
  EXPECT_NEAR(monitor.nearMeters, 1.035 / (1.0 / 0.7 + 0.626), 1e-6);
  EXPECT_LT(monitor.nearMeters, 0.7);
  EXPECT_GT(monitor.farMeters, 0.7);
  const ComfortZone tv = shibataComfortZone(builtInDisplayProfile("tv55"));
  EXPECT_EQ(tv.farMeters, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(tv.nearMeters, 1.035 / (1.0 / 2.5 + 0.626), 1e-6);
}

TEST(FrameComfort, CountsPixelsOutsideTheZoneOfComfort) {
  // Row 0 on the screen plane (inside); row 1 at a quarter of the zero-parallax distance: parallax
  // 2 * 0.05 * (1 - 4) = -30 % of a 0.62 m monitor, about 18.6 cm crossed, vergence 0.7 * 0.063 / 0.249 = 0.18 m,
  // far nearer than the 0.5 m near limit.
  DepthImage depth(40, 2, 1.0f);
  for (std::uint32_t x = 0; x < 40; ++x) *depth.at(x, 1) = 0.25f;
  stereo::StereoParameters parameters{0.05f, 1.0f, 0.0f};
  const FrameComfort comfort = frameComfort(depth, parameters, builtInDisplayProfile("monitor27"));
  EXPECT_DOUBLE_EQ(comfort.shareOutsideComfortZone, 0.5);
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
