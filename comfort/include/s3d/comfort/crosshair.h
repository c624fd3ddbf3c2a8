#pragma once
// The seed's crosshair placement (section 4.6.2): "the crosshair is located a few meters away from the
// weapon ... when getting close to a wall ... a ray-cast against the world is performed and in case of a
// hit, the crosshair is smoothly moved towards the viewer".
#include <limits>

#include <glm/glm.hpp>

#include "s3d/camera.h"
#include "s3d/comfort/world_queries.h"

namespace s3d::comfort {

// Smallest depth the crosshair is ever given (world units), whatever the camera's near plane says:
// parallaxFromDepth divides by it.
inline constexpr float kMinCrosshairDepth = 0.01f;

struct CrosshairPlacement {
  float depth = 0.0f;     // linear view depth of the crosshair in world units
  bool hitWorld = false;  // the aim ray hit a world surface closer than the default distance
  float surfaceDistance = std::numeric_limits<float>::infinity();  // that surface's depth (inf: no hit)
};

// Casts a ray from the camera along its aim (-Z of the camera's view, from cameraView). The aim is
// the view axis, so the distance along it is the crosshair's linear view depth. Without a hit within
// defaultDistance the crosshair stays at defaultDistance; with one it sits `margin` in front of the hit,
// never nearer than max(camera.nearPlane, kMinCrosshairDepth).
// A pure function of this frame; CrosshairSmoother adds the seed's smoothing over frames. placeCrosshairAlongAim
// with the camera's aim and the world's embreeRayCast.
// Throws std::invalid_argument when defaultDistance is not positive and finite or margin is negative/NaN.
CrosshairPlacement placeCrosshair(const WorldQueries& world, const Camera& camera, float defaultDistance,
                                  float margin = 0.25f);

// The camera as the crosshair's ray cast needs it (a host's own, no s3d::Camera needed).
struct FrameCamera {
  glm::vec3 position{0.0f};
  glm::vec3 aim{0.0f, 0.0f, -1.0f};  // the view axis (normalized), so a distance along it is a linear depth
  float nearPlane = 0.1f;
};

// The crosshair along the aim (the seed's ray cast): `margin` in front of a hit within defaultDistance, never
// nearer than max(nearPlane, kMinCrosshairDepth); defaultDistance without a hit (or without a ray cast).
// Throws std::invalid_argument when defaultDistance is not positive and finite or margin is negative/NaN.
CrosshairPlacement placeCrosshairAlongAim(const RayCast& rayCast, const FrameCamera& camera, float defaultDistance,
                                          float margin);

// The seed's "smoothly moved towards the viewer": over frames the crosshair's depth approaches each frame's
// placement exponentially (time constant responseSeconds; 0: at once), so it never overshoots, and it is never
// left behind the surface the aim ray hits (that would be the depth conflict the placement avoids): a wall
// appearing closer than the smoothed depth clamps it to the surface, from where it glides the last margin.
class CrosshairSmoother {
 public:
  explicit CrosshairSmoother(float responseSeconds);  // throws std::invalid_argument when negative or NaN
  // Advances one frame of `seconds` (> 0) toward placement.depth and returns the crosshair's depth.
  float update(const CrosshairPlacement& placement, float seconds);
  float current() const { return current_; }

 private:
  float responseSeconds_;
  float current_ = 0.0f;  // 0: no frame yet (the first frame starts at its placement)
};

}  // namespace s3d::comfort
