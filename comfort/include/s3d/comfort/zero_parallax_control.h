#pragma once
// Zero-parallax control (seed 4.6.2): "in case a potential depth conflict is detected, the ZPP distance is
// smoothly reduced based on the distance to the closest object". A few Embree ray casts find the nearest
// world surface ahead; the zero-parallax distance follows a target derived from it through a critically
// damped filter with a per-frame bound and hysteresis, and returns to its rest value when the player steps
// back.
#include <optional>

#include "s3d/camera.h"
#include "s3d/comfort/world_queries.h"

namespace s3d::comfort {

struct ZeroParallaxControlSettings {
  float restDistance = 1.0f;        // the zero-parallax distance when nothing is close (world units)
  float engageDistance = 2.0f;      // the control engages when the nearest surface is closer than this
  float releaseMargin = 0.25f;      // hysteresis: it releases only beyond engageDistance + releaseMargin
  float minimumDistance = 0.25f;    // the zero-parallax distance never goes below this
  float responseSeconds = 0.25f;    // time constant of the critically damped filter
  float maxChangePerSecond = 1.0f;  // world units per second (times the frame time: the bound per frame)
  int ringRays = 8;                 // rays on a ring around the aim, besides the aim itself
  float ringAngleRadians = 0.2f;    // angle between the aim and the ring's rays
};

// Throws std::invalid_argument naming the first setting that is NaN, non-positive or inconsistent.
void validate(const ZeroParallaxControlSettings& settings);

// Distance along the view axis to the nearest world surface hit by the aim ray or a ring ray within
// maxDistance (ray length times the cosine of its angle, so it compares with linear depth); nullopt: no hit.
std::optional<float> nearestSurfaceAhead(const WorldQueries& world, const Camera& camera,
                                         const ZeroParallaxControlSettings& settings, float maxDistance);

class ZeroParallaxController {
 public:
  explicit ZeroParallaxController(const ZeroParallaxControlSettings& settings = {});

  // The zero-parallax distance the control aims for at this nearest-surface distance (nullopt: open space).
  // Engaged, it scales the rest value by distance / engageDistance (a surface at the engage distance keeps
  // the rest value), clamped to [minimumDistance, restDistance].
  float target(std::optional<float> nearestSurface);

  // Advances one frame of `seconds` toward target(nearestSurface) and returns the new zero-parallax distance.
  float update(std::optional<float> nearestSurface, float seconds);

  // A hard rule (no negative parallax): lowers the value to at most `ceiling` at once, leaving no velocity
  // that would carry it further; the next update() continues smoothly from there. Returns the value.
  float limit(float ceiling);

  float current() const { return current_; }
  bool engaged() const { return engaged_; }

 private:
  ZeroParallaxControlSettings settings_;
  float current_;
  float velocity_ = 0.0f;
  bool engaged_ = false;
};

}  // namespace s3d::comfort
