// Comfort: Embree world queries and the seed's crosshair placement by a ray cast along the aim (4.6.2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/frame/scene_world.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/renderer/scene.h"

namespace s3d::comfort {
namespace {

// Float ray/triangle intersection a few metres from the origin is good to well under 1e-4 m.
constexpr float kDistanceTolerance = 1e-4f;

// A box with the given half extents whose near face (+Z side) is `distance` ahead of the origin along -Z,
// in the given layer. The scene camera stays at the origin, looking down -Z (yaw 0, pitch 0).
renderer::Scene sceneWithBoxAhead(float distance, glm::vec3 halfExtents = glm::vec3(0.5f),
                                  renderer::Layer layer = renderer::Layer::World) {
  renderer::Scene scene;
  scene.meshes.push_back(renderer::makeBox(halfExtents));
  renderer::Object box;
  box.layer = layer;
  box.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -distance - halfExtents.z));
  scene.objects.push_back(box);
  scene.camera.position = glm::vec3(0.0f);
  return scene;
}

// A wall 4 m wide, 3 m high, 0.2 m thick, its face `distance` ahead.
renderer::Scene sceneWithWallAhead(float distance) { return sceneWithBoxAhead(distance, {2.0f, 1.5f, 0.1f}); }

TEST(WorldQueries, RayHitsABoxAtTheAnalyticDistance) {
  const WorldQueries world(frame::worldMeshes(sceneWithBoxAhead(3.0f)));
  const std::optional<float> hit = world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 100.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 3.0f, kDistanceTolerance);
}

TEST(WorldQueries, HitDistanceIsMeasuredAlongTheNormalizedDirection) {
  // The direction is 5x too long and slanted 45 degrees in x-z: the face 3 m ahead is 3 * sqrt(2) m away.
  const WorldQueries world(frame::worldMeshes(sceneWithBoxAhead(3.0f, glm::vec3(10.0f, 10.0f, 0.5f))));
  const std::optional<float> hit = world.castRay(glm::vec3(0.0f), glm::vec3(5.0f, 0.0f, -5.0f), 100.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 3.0f * std::sqrt(2.0f), kDistanceTolerance);
}

TEST(WorldQueries, RayPointingAwayMisses) {
  const WorldQueries world(frame::worldMeshes(sceneWithBoxAhead(3.0f)));
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 100.0f).has_value());
}

TEST(WorldQueries, SurfaceBeyondMaxDistanceIsNotHit) {
  const WorldQueries world(frame::worldMeshes(sceneWithBoxAhead(3.0f)));
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 2.5f).has_value());
}

TEST(WorldQueries, FirstPersonObjectsAreNotPartOfTheToolsWorld) {
  // The weapon lives in camera space 0.3 m ahead; the ray along the aim must pass through it.
  const WorldQueries world(frame::worldMeshes(sceneWithBoxAhead(0.3f, glm::vec3(0.5f), renderer::Layer::FirstPerson)));
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 100.0f).has_value());
}

TEST(WorldQueries, EmptyWorldMissesEverything) {
  const WorldQueries world{std::span<const WorldMesh>{}};
  EXPECT_FALSE(world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 100.0f).has_value());
}

// One triangle in the plane z = -2 around the -Z axis, as packed positions (12-byte stride).
const std::vector<glm::vec3> kTrianglePositions{{-1.0f, -1.0f, -2.0f}, {1.0f, -1.0f, -2.0f}, {0.0f, 1.0f, -2.0f}};
const std::vector<std::uint32_t> kTriangleIndices{0, 1, 2};

TEST(WorldQueries, PackedPositionsArePlacedByTheMeshTransform) {
  // Moved 1 m further along -Z, the plane is 3 m ahead.
  const WorldMesh mesh{kTrianglePositions.data(), kTrianglePositions.size(), sizeof(glm::vec3), kTriangleIndices,
                       glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.0f))};
  const WorldQueries world(std::span<const WorldMesh>(&mesh, 1));
  const std::optional<float> hit = world.castRay(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 100.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 3.0f, kDistanceTolerance);
}

TEST(WorldQueries, ATriangleIndexBeyondTheVerticesIsRejectedNamingTheMesh) {
  const std::vector<std::uint32_t> indices{0, 1, 3};
  const WorldMesh meshes[] = {{kTrianglePositions.data(), 3, sizeof(glm::vec3), kTriangleIndices},
                              {kTrianglePositions.data(), 3, sizeof(glm::vec3), indices}};
  try {
    const WorldQueries world(meshes);
    FAIL() << "a triangle index past the vertices was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("world mesh 1 has triangle index 3 beyond its 3 vertices"),
              std::string::npos)
        << error.what();
  }
}

TEST(WorldQueries, ZeroDirectionIsRejected) {
  const WorldQueries world(frame::worldMeshes(sceneWithBoxAhead(3.0f)));
  EXPECT_THROW((void)world.castRay(glm::vec3(0.0f), glm::vec3(0.0f), 100.0f), std::invalid_argument);
}

TEST(CrosshairPlacement, StaysAtTheDefaultDistanceInTheOpen) {
  const renderer::Scene scene = sceneWithWallAhead(30.0f);  // a wall, but beyond the 8 m default
  const WorldQueries world(frame::worldMeshes(scene));
  const CrosshairPlacement placement = placeCrosshair(world, scene.camera, 8.0f);
  EXPECT_EQ(placement.depth, 8.0f);  // exact: the default is returned as given
  EXPECT_FALSE(placement.hitWorld);
}

TEST(CrosshairPlacement, MovesInFrontOfAWallTwoMetresAhead) {
  const renderer::Scene scene = sceneWithWallAhead(2.0f);
  const WorldQueries world(frame::worldMeshes(scene));
  const CrosshairPlacement placement = placeCrosshair(world, scene.camera, 8.0f, 0.25f);
  EXPECT_TRUE(placement.hitWorld);
  EXPECT_NEAR(placement.depth, 2.0f - 0.25f, kDistanceTolerance);
}

TEST(CrosshairPlacement, FollowsTheCameraAim) {
  // Yaw +90 degrees looks down -X (cameraView); the wall is moved there, 2 m from a raised camera.
  renderer::Scene scene = sceneWithWallAhead(2.0f);
  scene.objects[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.7f, 0.0f)) *
                               glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0.0f, 1.0f, 0.0f)) *
                               scene.objects[0].transform;
  scene.camera.position = glm::vec3(0.0f, 1.7f, 0.0f);
  scene.camera.yawRadians = glm::radians(90.0f);
  const WorldQueries world(frame::worldMeshes(scene));
  const CrosshairPlacement placement = placeCrosshair(world, scene.camera, 8.0f, 0.25f);
  EXPECT_TRUE(placement.hitWorld);
  EXPECT_NEAR(placement.depth, 1.75f, kDistanceTolerance);
}

TEST(CrosshairPlacement, NeverGoesNearerThanTheNearPlane) {
  // The wall is 0.15 m ahead: 0.15 - 0.25 would put the crosshair behind the eye.
  const renderer::Scene scene = sceneWithWallAhead(0.15f);
  const WorldQueries world(frame::worldMeshes(scene));
  EXPECT_EQ(placeCrosshair(world, scene.camera, 8.0f, 0.25f).depth, scene.camera.nearPlane);
}

TEST(CrosshairPlacement, StaysPositiveWithAZeroNearPlane) {
  renderer::Scene scene = sceneWithWallAhead(0.15f);
  scene.camera.nearPlane = 0.0f;
  const WorldQueries world(frame::worldMeshes(scene));
  EXPECT_EQ(placeCrosshair(world, scene.camera, 8.0f, 0.25f).depth, kMinCrosshairDepth);
}

TEST(CrosshairPlacement, CourtyardCrosshairIsTheDefaultOrInFrontOfAHit) {
  // The built-in default scene, CPU only: whatever the courtyard's layout, the depth is usable for parallax.
  const renderer::Scene scene = renderer::makeCourtyardScene();
  const WorldQueries world(frame::worldMeshes(scene));
  const CrosshairPlacement placement = placeCrosshair(world, scene.camera, scene.crosshairDistance);
  EXPECT_TRUE(std::isfinite(placement.depth));
  EXPECT_GT(placement.depth, 0.0f);
  if (placement.hitWorld) {
    EXPECT_LT(placement.depth, scene.crosshairDistance);
  } else {
    EXPECT_EQ(placement.depth, scene.crosshairDistance);
  }
}

}  // namespace
}  // namespace s3d::comfort
