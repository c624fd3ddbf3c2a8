#pragma once
// Ray casts against the world with Embree 3 (the seed's section 4.6.2 uses "a ray-cast against the world"
// for the crosshair, and ray casts for the zero-parallax control). Built from the same meshes the renderer
// draws, in world space; the first-person layer (the weapon) is not part of the world.
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::comfort {

class WorldQueries {
 public:
  // Builds an Embree scene from scene.objects with Layer::World (vertices transformed by object.transform).
  // Throws std::runtime_error naming the Embree call that failed, std::out_of_range for a bad mesh index
  // and std::invalid_argument for a triangle index outside its mesh.
  explicit WorldQueries(const renderer::Scene& scene);
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

}  // namespace s3d::comfort
