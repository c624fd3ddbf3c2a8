// The zero-parallax control (seed 4.6.2): targets, damping, per-frame bound, hysteresis, ray casts.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/frame/scene_world.h"
#include "s3d/comfort/zero_parallax_control.h"
#include "s3d/renderer/scene.h"

namespace s3d::comfort {
namespace {

constexpr float kFrame = 1.0f / 60.0f;

TEST(ZeroParallaxControl, StepResponseApproachesTheTargetWithoutOvershoot) {
  // A surface 0.5 m ahead: target = 1 m * 0.5 / 2 = 0.25 m. Critically damped (and bounded to 1 m/s at
  // first): monotonic, never past the goal, within 1 mm after 16 time constants (4 s at 60 Hz).
  ZeroParallaxController control;
  float previous = control.current();
  for (int frame = 0; frame < 240; ++frame) {
    float value = control.update(0.5f, kFrame);
    EXPECT_LE(value, previous + 1e-6f) << frame;  // never rises while the goal is below
    EXPECT_GE(value, 0.25f - 1e-6f) << frame;    // never below the goal
    previous = value;
  }
  EXPECT_NEAR(control.current(), 0.25f, 1e-3f);
}

TEST(ZeroParallaxControl, NeverChangesMoreThanTheBoundPerFrame) {
  ZeroParallaxControlSettings settings;
  settings.maxChangePerSecond = 0.6f;  // 0.01 per 60 Hz frame
  settings.responseSeconds = 0.01f;  // a filter that would jump almost at once
  ZeroParallaxController control(settings);
  float previous = control.current();
  for (int frame = 0; frame < 100; ++frame) {
    float value = control.update(frame < 50 ? std::optional<float>(0.3f) : std::nullopt, kFrame);
    EXPECT_LE(std::abs(value - previous), 0.01f + 1e-6f) << frame;
    previous = value;
  }
}

TEST(ZeroParallaxControl, ReturnsToItsRestValueWhenThePlayerStepsBack) {
  ZeroParallaxController control;
  for (int frame = 0; frame < 120; ++frame) control.update(0.6f, kFrame);
  EXPECT_LT(control.current(), 0.5f);
  for (int frame = 0; frame < 240; ++frame) control.update(std::nullopt, kFrame);
  EXPECT_NEAR(control.current(), 1.0f, 1e-3f);
  EXPECT_FALSE(control.engaged());
}

TEST(ZeroParallaxControl, HysteresisHoldsTheControlAroundTheEngageDistance) {
  // Distances jittering between 1.95 and 2.15 m (inside the 0.25 m release margin) must not release it.
  ZeroParallaxController control;
  control.update(1.95f, kFrame);
  ASSERT_TRUE(control.engaged());
  for (int frame = 0; frame < 60; ++frame) {
    control.update(frame % 2 ? 2.15f : 1.95f, kFrame);
    EXPECT_TRUE(control.engaged()) << frame;
  }
  control.update(2.3f, kFrame);  // beyond 2 + 0.25
  EXPECT_FALSE(control.engaged());
}

TEST(ZeroParallaxControl, TargetIsClampedToTheMinimum) {
  ZeroParallaxController control;
  EXPECT_FLOAT_EQ(control.target(0.01f), 0.25f);
  EXPECT_FLOAT_EQ(control.target(std::nullopt), 1.0f);
}

TEST(ZeroParallaxControl, InconsistentSettingsAreRejectedByName) {
  ZeroParallaxControlSettings settings;
  settings.minimumDistance = 2.0f;  // above the rest value
  EXPECT_THROW(ZeroParallaxController{settings}, std::invalid_argument);
  settings = {};
  settings.responseSeconds = NAN;
  try {
    ZeroParallaxController control(settings);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("responseSeconds"), std::string::npos) << error.what();
  }
}

TEST(ZeroParallaxControl, RingRaysFindAWallBesideTheAim) {
  // A wall 1 m ahead covering only the right of the view: the aim misses, a ring ray hits it.
  // Tolerance 1e-3 m: float ray casts times a cosine.
  renderer::Scene scene;
  scene.meshes.push_back(renderer::makeBox(glm::vec3(0.5f)));
  renderer::Object wall;
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.05f, 0.0f, -1.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f, 4.0f, 1.0f));
  scene.objects.push_back(wall);
  scene.camera.position = glm::vec3(0.0f);
  WorldQueries world(frame::worldMeshes(scene));
  ZeroParallaxControlSettings settings;
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 10.0f).has_value());
  std::optional<float> nearest = nearestSurfaceAhead(world, scene.camera, settings, 10.0f);
  ASSERT_TRUE(nearest.has_value());
  EXPECT_NEAR(*nearest, 1.0f, 1e-3f);
}

}  // namespace
}  // namespace s3d::comfort
