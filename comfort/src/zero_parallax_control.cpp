#include "s3d/comfort/zero_parallax_control.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "s3d/comfort/critically_damped.h"
#include "s3d/number_text.h"

namespace s3d::comfort {
namespace {

void requirePositive(float value, const char* name) {
  if (!(value > 0.0f) || !std::isfinite(value))
    throw std::invalid_argument(std::string("zero-parallax control: ") + name + " must be positive and finite (got " +
                                numberText(value) + ")");
}

}  // namespace

void validate(const ZeroParallaxControlSettings& s) {
  requirePositive(s.restDistance, "restDistance");
  requirePositive(s.engageDistance, "engageDistance");
  requirePositive(s.minimumDistance, "minimumDistance");
  requirePositive(s.responseSeconds, "responseSeconds");
  requirePositive(s.maxChangePerSecond, "maxChangePerSecond");
  if (!(s.releaseMargin >= 0.0f) || !std::isfinite(s.releaseMargin))
    throw std::invalid_argument("zero-parallax control: releaseMargin must be >= 0 and finite");
  if (s.minimumDistance > s.restDistance)
    throw std::invalid_argument("zero-parallax control: minimumDistance is above restDistance");
  if (s.ringRays < 0 || s.ringRays > 64) throw std::invalid_argument("zero-parallax control: ringRays must be in [0, 64]");
  if (!(s.ringAngleRadians >= 0.0f) || !(s.ringAngleRadians < 1.5f))
    throw std::invalid_argument("zero-parallax control: ringAngleRadians must be in [0, 1.5)");
}

std::optional<float> nearestSurfaceAhead(const WorldQueries& world, const Camera& camera,
                                         const ZeroParallaxControlSettings& settings, float maxDistance) {
  const glm::mat4 cameraToWorld = glm::inverse(cameraView(camera));
  const glm::vec3 right(cameraToWorld[0]), up(cameraToWorld[1]), aim = -glm::vec3(cameraToWorld[2]);
  std::optional<float> nearest;
  auto cast = [&](glm::vec3 direction, float cosine) {
    if (std::optional<float> hit = world.castRay(camera.position, direction, maxDistance / cosine)) {
      const float depth = *hit * cosine;  // along the view axis, comparable with linear depth
      if (!nearest || depth < *nearest) nearest = depth;
    }
  };
  cast(aim, 1.0f);
  const float cosine = std::cos(settings.ringAngleRadians), sine = std::sin(settings.ringAngleRadians);
  for (int i = 0; i < settings.ringRays; ++i) {
    const float angle = 6.2831853f * float(i) / float(settings.ringRays);
    cast(aim * cosine + (right * std::cos(angle) + up * std::sin(angle)) * sine, cosine);
  }
  return nearest;
}

ZeroParallaxController::ZeroParallaxController(const ZeroParallaxControlSettings& settings)
    : settings_(settings), current_(settings.restDistance) {
  validate(settings);
}

float ZeroParallaxController::target(std::optional<float> nearestSurface) {
  // Hysteresis: engage below engageDistance, release only beyond engageDistance + releaseMargin.
  if (!nearestSurface)
    engaged_ = false;
  else if (*nearestSurface < settings_.engageDistance)
    engaged_ = true;
  else if (*nearestSurface > settings_.engageDistance + settings_.releaseMargin)
    engaged_ = false;
  if (!engaged_) return settings_.restDistance;
  const float scaled = settings_.restDistance * *nearestSurface / settings_.engageDistance;
  return std::clamp(scaled, settings_.minimumDistance, settings_.restDistance);
}

float ZeroParallaxController::update(std::optional<float> nearestSurface, float seconds) {
  if (!(seconds > 0.0f) || !std::isfinite(seconds))
    throw std::invalid_argument("zero-parallax control: frame time must be positive and finite");
  const float goal = target(nearestSurface);
  CriticallyDamped follower{current_, velocity_};
  current_ = follower.step(goal, seconds, settings_.responseSeconds, settings_.maxChangePerSecond * seconds);
  velocity_ = follower.velocity;
  return current_;
}

float ZeroParallaxController::limit(float ceiling) {
  if (ceiling < current_) {
    current_ = std::max(ceiling, 0.0f);
    velocity_ = 0.0f;
  }
  return current_;
}

}  // namespace s3d::comfort
