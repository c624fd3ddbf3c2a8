// Comfort's Embree world queries and the seed's crosshair placement by ray cast.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/comfort/world_queries.h"

namespace s3d::comfort {
namespace {

// A 1 m box centered `distance` + 0.5 m ahead of a camera at the origin looking down -Z.
renderer::Scene sceneWithBoxAhead(float distance, renderer::Layer layer = renderer::Layer::World) {
  renderer::Scene scene;
  scene.meshes.push_back(renderer::makeBox(glm::vec3(0.5f)));
  renderer::Object box;
  box.layer = layer;
  box.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -distance - 0.5f));
  scene.objects.push_back(box);
  scene.camera.position = glm::vec3(0.0f);
  return scene;
}

TEST(WorldQueries, RayHitsABoxAtItsAnalyticDistance) {
  // Tolerance 1e-4 m: single-precision ray/triangle intersection a few metres away.
  WorldQueries world(sceneWithBoxAhead(3.0f));
  std::optional<float> hit = world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 100.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 3.0f, 1e-4f);
}

TEST(WorldQueries, RayPointingAwayMisses) {
  WorldQueries world(sceneWithBoxAhead(3.0f));
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 100.0f).has_value());
}

TEST(WorldQueries, FirstPersonObjectsAreNotPartOfTheWorld) {
  WorldQueries world(sceneWithBoxAhead(0.3f, renderer::Layer::FirstPerson));
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 100.0f).has_value());
}

TEST(CrosshairPlacement, StaysAtTheDefaultDistanceInTheOpen) {
  renderer::Scene scene = sceneWithBoxAhead(30.0f);
  WorldQueries world(scene);
  CrosshairPlacement placement = placeCrosshair(world, scene.camera, 8.0f);
  EXPECT_FLOAT_EQ(placement.depth, 8.0f);
  EXPECT_FALSE(placement.hitWorld);
}

TEST(CrosshairPlacement, MovesInFrontOfAWallCloserThanTheDefault) {
  // Tolerance 1e-4 m as above; the crosshair sits `margin` in front of the hit.
  renderer::Scene scene = sceneWithBoxAhead(2.0f);
  WorldQueries world(scene);
  CrosshairPlacement placement = placeCrosshair(world, scene.camera, 8.0f, 0.25f);
  EXPECT_TRUE(placement.hitWorld);
  EXPECT_NEAR(placement.depth, 1.75f, 1e-4f);
}

TEST(CrosshairPlacement, NeverGoesNearerThanTheNearPlane) {
  renderer::Scene scene = sceneWithBoxAhead(0.15f);
  WorldQueries world(scene);
  EXPECT_FLOAT_EQ(placeCrosshair(world, scene.camera, 8.0f, 0.25f).depth, scene.camera.nearPlane);
}

}  // namespace
}  // namespace s3d::comfort
