#include "s3d/comfort/crosshair.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "s3d/renderer/deferred_renderer.h"

namespace s3d::comfort {

CrosshairPlacement placeCrosshair(const WorldQueries& world, const renderer::Camera& camera, float defaultDistance,
                                  float margin) {
  if (!(defaultDistance > 0.0f) || !std::isfinite(defaultDistance))
    throw std::invalid_argument("placeCrosshair: defaultDistance must be positive and finite (got " +
                                std::to_string(defaultDistance) + ")");
  if (!(margin >= 0.0f) || !std::isfinite(margin))
    throw std::invalid_argument("placeCrosshair: margin must be >= 0 and finite (got " + std::to_string(margin) + ")");

  // The camera's aim is -Z of its view space; in world space that is minus the third column of view^-1.
  const glm::mat4 worldFromView = glm::inverse(renderer::cameraView(camera));
  const glm::vec3 aim = -glm::vec3(worldFromView[2]);
  const glm::vec3 eye = glm::vec3(worldFromView[3]);

  const std::optional<float> hit = world.castRay(eye, aim, defaultDistance);
  if (!hit || *hit >= defaultDistance) return {defaultDistance, false};
  const float nearest = std::max(camera.nearPlane, kMinCrosshairDepth);
  return {std::max(*hit - margin, nearest), true};
}

}  // namespace s3d::comfort
