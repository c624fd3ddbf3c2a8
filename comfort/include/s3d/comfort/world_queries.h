#pragma once
// Ray casts against the world with Embree 3 (the seed's section 4.6.2 uses "a ray-cast against the world"
// for the crosshair, and ray casts for the zero-parallax control). Built from the triangles the host draws, as
// plain geometry (the s3d tools hand over their renderer scene's world layer); the first-person layer (the weapon)
// is not part of the world.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>

#include <glm/glm.hpp>

namespace s3d::comfort {

// One triangle mesh of the world as the host stores it: vertex i's position is the three floats `strideBytes * i`
// bytes after `positions` (an interleaved vertex array needs no copy), placed in the world by `transform`.
struct WorldMesh {
  const void* positions = nullptr;
  std::size_t vertexCount = 0;
  std::size_t strideBytes = 3 * sizeof(float);
  std::span<const std::uint32_t> indices;  // triangle list
  glm::mat4 transform{1.0f};               // mesh -> world
};

class WorldQueries {
 public:
  // Builds an Embree scene from the meshes (copied: they need not outlive the constructor). Throws
  // std::runtime_error naming the Embree call that failed and std::invalid_argument for a triangle index outside
  // its mesh or a mesh with vertices but no positions.
  explicit WorldQueries(std::span<const WorldMesh> meshes);
  ~WorldQueries();
  WorldQueries(const WorldQueries&) = delete;
  WorldQueries& operator=(const WorldQueries&) = delete;

  // Distance from origin along the normalized direction to the first world surface within maxDistance
  // (either side of a triangle counts), or nothing. Throws std::invalid_argument for a zero or non-finite
  // direction or a maxDistance that is not positive. Safe to call from several threads at once.
  std::optional<float> castRay(glm::vec3 origin, glm::vec3 direction, float maxDistance) const;

 private:
  struct Embree;  // RTCDevice + RTCScene, released in reverse order
  std::unique_ptr<Embree> embree_;
};

// The host's ray cast, which the crosshair placement and the per-frame rules take: distance from origin along the
// normalized direction to the first world surface within maxDistance, or nothing. The first-person layer is not
// part of the world.
using RayCast = std::function<std::optional<float>(glm::vec3 origin, glm::vec3 direction, float maxDistance)>;
// Embree's, for hosts without a physics engine; `world` must outlive the callback.
RayCast embreeRayCast(const WorldQueries& world);

}  // namespace s3d::comfort
