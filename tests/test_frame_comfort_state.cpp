// The per-frame comfort call a host makes (frame_comfort_state.h): weapon push, zero-parallax hold, crosshair by
// the host's ray cast, HUD depth/parallax/fade, statistics.
#include <gtest/gtest.h>

#include <cmath>

#include "s3d/comfort/frame_comfort_state.h"

namespace s3d::comfort {
namespace {

FrameComfortInput baseInput() {
  FrameComfortInput input;
  input.width = 1000;
  input.parameters.maxSeparation = 0.02f;
  input.parameters.zeroParallaxDistance = 4.0f;
  input.parameters.weaponDepthOffset = 0.0f;
  input.parameters.weaponDepthScale = 1.0f;
  input.crosshairDistance = 20.0f;
  return input;
}

RayCast wallAt(float distance) {
  return [distance](glm::vec3, glm::vec3, float maxDistance) -> std::optional<float> {
    if (distance > maxDistance) return std::nullopt;
    return distance;
  };
}

TEST(FrameComfortState, AWeaponInFrontOfTheScreenIsPushedOntoTheZeroParallaxPlane) {
  FrameComfortInput input = baseInput();
  input.weapon = {500, 0.5f, 1.5f};
  const FrameComfortState state = frameComfortState(input);
  EXPECT_TRUE(state.weaponPushed);
  EXPECT_NEAR(state.parameters.weaponDepthOffset + state.parameters.weaponDepthScale * 0.5f,
              state.parameters.zeroParallaxDistance, 1e-5f);
}

TEST(FrameComfortState, NegativeParallaxAllowedLeavesPushAndZeroParallaxAsGiven) {
  FrameComfortInput input = baseInput();
  input.weapon = {500, 0.5f, 1.5f};
  input.nearestWorldDepth = 1.0f;
  input.allowNegativeParallax = true;
  const FrameComfortState state = frameComfortState(input);
  EXPECT_FALSE(state.weaponPushed);
  EXPECT_FALSE(state.zeroParallaxLimited);
  EXPECT_EQ(state.parameters.zeroParallaxDistance, 4.0f);
}

TEST(FrameComfortState, TheZeroParallaxDistanceIsHeldAtTheNearestWorldDepth) {
  FrameComfortInput input = baseInput();
  input.nearestWorldDepth = 2.5f;
  const FrameComfortState state = frameComfortState(input);
  EXPECT_TRUE(state.zeroParallaxLimited);
  EXPECT_EQ(state.parameters.zeroParallaxDistance, 2.5f);
}

TEST(FrameComfortState, TheNearestDepthComesFromTheStereoDepthWhenGiven) {
  FrameComfortInput input = baseInput();
  DepthImage depth(4, 2, 10.0f);
  *depth.at(1, 1) = 3.0f;
  *depth.at(2, 0) = std::numeric_limits<float>::infinity();
  input.stereoDepth = &depth;
  const DisplayProfile display = builtInDisplayProfile("monitor27");
  input.display = &display;
  const FrameComfortState state = frameComfortState(input);
  EXPECT_EQ(state.parameters.zeroParallaxDistance, 3.0f);
  ASSERT_TRUE(state.statistics.has_value());
  EXPECT_EQ(state.statistics->shareOutsideComfortZone, frameComfort(depth, state.parameters, display).shareOutsideComfortZone);
}

TEST(FrameComfortState, TheCrosshairSitsTheMarginInFrontOfTheHostsRayHit) {
  FrameComfortInput input = baseInput();
  input.rayCast = wallAt(6.0f);
  input.crosshairMargin = 0.5f;
  const FrameComfortState state = frameComfortState(input);
  EXPECT_TRUE(state.crosshairHitWorld);
  EXPECT_FLOAT_EQ(state.crosshairDepth, 5.5f);
  EXPECT_FLOAT_EQ(state.crosshair.parallaxPx, gpu::parallaxFromDepth(0.02f, 4.0f, 5.5f) * 1000.0f);
}

TEST(FrameComfortState, WithoutAHitTheCrosshairStaysAtItsDistance) {
  FrameComfortInput input = baseInput();
  input.rayCast = wallAt(50.0f);
  const FrameComfortState state = frameComfortState(input);
  EXPECT_FALSE(state.crosshairHitWorld);
  EXPECT_EQ(state.crosshairDepth, 20.0f);
}

TEST(FrameComfortState, AHudElementBehindThePushedWeaponFadesAndOneInFrontOfTheScreenMovesOntoIt) {
  FrameComfortInput input = baseInput();
  input.weapon = {500, 4.5f, 5.0f};  // already behind the screen: not pushed
  input.hud = {{"health", 8.0f}, {"ammo", 1.0f}};
  const FrameComfortState state = frameComfortState(input);
  ASSERT_EQ(state.hud.size(), 2u);
  EXPECT_TRUE(state.hud[0].fadesBehindWeapon);  // 8 > 4.5
  EXPECT_EQ(state.hud[1].depth, 4.0f);          // not in front of the screen plane
  EXPECT_FALSE(state.hud[1].fadesBehindWeapon);
  EXPECT_FLOAT_EQ(state.hud[1].parallaxPx, 0.0f);
}

TEST(FrameComfortState, AZeroWidthIsRefused) {
  FrameComfortInput input = baseInput();
  input.width = 0;
  EXPECT_THROW(frameComfortState(input), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::comfort
