#include "s3d/comfort/crosshair.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "s3d/number_text.h"

namespace s3d::comfort {

CrosshairPlacement placeCrosshair(const WorldQueries& world, const Camera& camera, float defaultDistance,
                                  float margin) {
  // The camera's aim is -Z of its view space; in world space that is minus the third column of view^-1.
  const glm::mat4 worldFromView = glm::inverse(cameraView(camera));
  return placeCrosshairAlongAim(embreeRayCast(world),
                                {glm::vec3(worldFromView[3]), -glm::vec3(worldFromView[2]), camera.nearPlane},
                                defaultDistance, margin);
}

CrosshairPlacement placeCrosshairAlongAim(const RayCast& rayCast, const FrameCamera& camera, float defaultDistance,
                                          float margin) {
  if (!(defaultDistance > 0.0f) || !std::isfinite(defaultDistance))
    throw std::invalid_argument("placeCrosshair: defaultDistance must be positive and finite (got " +
                                numberText(defaultDistance) + ")");
  if (!(margin >= 0.0f) || !std::isfinite(margin))
    throw std::invalid_argument("placeCrosshair: margin must be >= 0 and finite (got " + numberText(margin) + ")");
  const std::optional<float> hit = rayCast ? rayCast(camera.position, camera.aim, defaultDistance) : std::nullopt;
  if (!hit || *hit >= defaultDistance) return {defaultDistance, false};
  const float nearest = std::max(camera.nearPlane, kMinCrosshairDepth);
  return {std::max(*hit - margin, nearest), true, *hit};
}

CrosshairSmoother::CrosshairSmoother(float responseSeconds) : responseSeconds_(responseSeconds) {
  if (!(responseSeconds >= 0.0f) || !std::isfinite(responseSeconds))
    throw std::invalid_argument("crosshair smoothing: responseSeconds must be >= 0 and finite");
}

float CrosshairSmoother::update(const CrosshairPlacement& placement, float seconds) {
  if (!(seconds > 0.0f) || !std::isfinite(seconds))
    throw std::invalid_argument("crosshair smoothing: frame time must be positive and finite");
  if (current_ <= 0.0f || responseSeconds_ == 0.0f) {
    current_ = placement.depth;
  } else {
    // First-order approach solved exactly over the frame: monotonic, no overshoot for any frame time.
    current_ = placement.depth + (current_ - placement.depth) * std::exp(-seconds / responseSeconds_);
  }
  current_ = std::min(current_, placement.surfaceDistance);  // never behind the surface it is aimed at
  return current_;
}

}  // namespace s3d::comfort
