#pragma once
// Ray casts against the world with Embree 3 (the seed's section 4.6.2 uses "a few ray casts" for the
// crosshair and the zero-parallax control). Built from the same meshes the renderer draws; the
// first-person layer is not part of the world.
#include <optional>

#include <glm/glm.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::comfort {

class WorldQueries {
 public:
  explicit WorldQueries(const renderer::Scene& scene);
  ~WorldQueries();
  WorldQueries(const WorldQueries&) = delete;
  WorldQueries& operator=(const WorldQueries&) = delete;

  // Distance along the (normalized) direction to the first world surface within maxDistance.
  std::optional<float> castRay(glm::vec3 origin, glm::vec3 direction, float maxDistance) const;

 private:
  struct Impl;
  Impl* impl_;
};

struct CrosshairPlacement {
  float depth = 0.0f;     // linear (view) depth of the crosshair in world units
  bool hitWorld = false;  // a surface closer than the default distance pulled it in
};

// The seed's crosshair: a few meters beyond the weapon, or just in front of the world surface the aim ray
// hits when that is closer. A pure function of this frame; smoothing over frames comes with sequences.
CrosshairPlacement placeCrosshair(const WorldQueries& world, const renderer::Camera& camera, float defaultDistance,
                                  float margin = 0.25f);

}  // namespace s3d::comfort
