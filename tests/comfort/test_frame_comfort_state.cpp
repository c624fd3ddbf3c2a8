// The per-frame comfort call a host makes (frame_comfort_state.h): weapon push, zero-parallax hold, crosshair by
// the host's ray cast, the disparity budget from the host's depth range, HUD depth/parallax/fade, statistics.
#include <gtest/gtest.h>

#include <cmath>

#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/stereo/depth_range.h"

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
  EXPECT_EQ(state.statistics->windowViolationPixels, frameComfort(depth, state.parameters, display).windowViolationPixels);
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

// A 1000 x 2 frame: a wall at 1.5 m in row 0, the sky in row 1, and one pixel at `nearest`.
DepthImage wallAndSky(float nearest) {
  DepthImage depth(1000, 2, 1.5f);
  for (std::uint32_t x = 0; x < 1000; ++x) *depth.at(x, 1) = std::numeric_limits<float>::infinity();
  *depth.at(10, 0) = nearest;
  return depth;
}

TEST(FrameComfortState, TheBudgetFitsAFrameWiderThanTheDisplayAllows) {
  // The host's 2 % separation puts the sky beyond 1 degree on a monitor (about 1 % allowed per eye); with its
  // controller and the frame's depth range the statistics over the same depth show no pixel beyond it.
  FrameComfortInput input = baseInput();
  const DepthImage depth = wallAndSky(0.8f);
  const DisplayProfile display = builtInDisplayProfile("monitor27");
  input.stereoDepth = &depth;
  input.display = &display;
  EXPECT_GT(frameComfortState(input).statistics->parallax.shareBeyondOneDegree, 0.4);
  DisparityBudgetController controller(disparityBudget(display), false);
  const stereo::DepthRange range = stereo::reduceDepthRangeReference(depth);
  input.budget = FrameBudget{&controller, &range};
  const FrameComfortState state = frameComfortState(input);
  ASSERT_TRUE(state.budget.has_value());
  EXPECT_TRUE(state.budget->cut);  // the first frame jumps to its target
  EXPECT_EQ(state.parameters.maxSeparation, state.budget->parameters.maxSeparation);
  EXPECT_EQ(state.parameters.zeroParallaxDistance, 0.8f);  // the nearest pixel, nothing in front of the screen
  EXPECT_EQ(state.statistics->parallax.shareBeyondOneDegree, 0.0);
  EXPECT_GE(state.statistics->parallax.minParallaxPx, 0.0);
  EXPECT_NEAR(state.budget->usedShare, 0.9, 1e-4);  // the controller's target share
}

TEST(FrameComfortState, TheBudgetKeepsThePushedWeaponBehindTheScreen) {
  // The range lacks the weapon (reduced from the world only): its pushed nearest point still bounds the plane,
  // and the HUD's parallax follows the chosen parameters.
  FrameComfortInput input = baseInput();
  input.weapon = {500, 0.5f, 0.7f};
  input.hud = {{"ammo", 2.0f}};
  DepthImage world = wallAndSky(6.0f);  // the world's nearest at 6 m: behind the weapon pushed to 4 m
  for (std::uint32_t x = 0; x < 1000; ++x) *world.at(x, 0) = 6.0f;
  const stereo::DepthRange range = stereo::reduceDepthRangeReference(world);
  DisparityBudgetController controller(disparityBudget(builtInDisplayProfile("tv55")), false);
  input.budget = FrameBudget{&controller, &range};
  const FrameComfortState state = frameComfortState(input);
  ASSERT_TRUE(state.budget.has_value());
  const float weaponNearestPushed = state.parameters.weaponDepthOffset + state.parameters.weaponDepthScale * 0.5f;
  EXPECT_NEAR(weaponNearestPushed, 4.0f, 1e-6f);  // the host's plane: the whole weapon shifted back onto it
  EXPECT_LE(state.parameters.zeroParallaxDistance, weaponNearestPushed);
  EXPECT_EQ(state.hud[0].depth, state.parameters.zeroParallaxDistance);  // 2 m: held on the chosen plane
  input.hud = {{"ammo", 9.0f}};
  DisparityBudgetController again(disparityBudget(builtInDisplayProfile("tv55")), false);
  input.budget = FrameBudget{&again, &range};
  const FrameComfortState behind = frameComfortState(input);
  EXPECT_FLOAT_EQ(behind.hud[0].parallaxPx, gpu::parallaxFromDepth(behind.parameters.maxSeparation,
                                                                   behind.parameters.zeroParallaxDistance, 9.0f) *
                                                1000.0f);
  EXPECT_GT(behind.hud[0].parallaxPx, 0.0f);
}

TEST(FrameComfortState, AnEmptyDepthRangeKeepsTheHostsParameters) {
  FrameComfortInput input = baseInput();
  const stereo::DepthRange empty = stereo::reduceDepthRangeReference(DepthImage(4, 4, 0.0f));  // all invalid
  DisparityBudgetController controller(disparityBudget(builtInDisplayProfile("tv55")), false);
  input.budget = FrameBudget{&controller, &empty};
  const FrameComfortState state = frameComfortState(input);
  EXPECT_FALSE(state.budget.has_value());
  EXPECT_EQ(state.parameters.maxSeparation, 0.02f);
  EXPECT_EQ(state.parameters.zeroParallaxDistance, 4.0f);
}

TEST(FrameComfortState, ABudgetWithoutItsPartsOrWithTheOtherNegativeParallaxRuleIsRefused) {
  FrameComfortInput input = baseInput();
  const stereo::DepthRange range = stereo::reduceDepthRangeReference(wallAndSky(1.0f));
  DisparityBudgetController popOut(disparityBudget(builtInDisplayProfile("tv55")), true);
  input.budget = FrameBudget{&popOut, &range};
  EXPECT_THROW(frameComfortState(input), std::invalid_argument);  // the frame disallows negative parallax
  input.budget = FrameBudget{nullptr, &range};
  EXPECT_THROW(frameComfortState(input), std::invalid_argument);
  input.budget = FrameBudget{&popOut, nullptr};
  input.allowNegativeParallax = true;
  EXPECT_THROW(frameComfortState(input), std::invalid_argument);
}

TEST(FrameComfortState, AZeroWidthIsRefused) {
  FrameComfortInput input = baseInput();
  input.width = 0;
  EXPECT_THROW(frameComfortState(input), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::comfort
