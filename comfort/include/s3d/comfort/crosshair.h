#pragma once
// The seed's crosshair placement (section 4.6.2): "the crosshair is located a few meters away from the
// weapon ... when getting close to a wall ... a ray-cast against the world is performed and in case of a
// hit, the crosshair is smoothly moved towards the viewer".
#include "s3d/comfort/world_queries.h"
#include "s3d/renderer/scene.h"

namespace s3d::comfort {

// Smallest depth the crosshair is ever given (world units), whatever the camera's near plane says:
// parallaxFromDepth divides by it.
inline constexpr float kMinCrosshairDepth = 0.01f;

struct CrosshairPlacement {
  float depth = 0.0f;     // linear view depth of the crosshair in world units
  bool hitWorld = false;  // the aim ray hit a world surface closer than the default distance
};

// Casts a ray from the camera along its aim (-Z of the camera's view, from renderer::cameraView). The aim is
// the view axis, so the distance along it is the crosshair's linear view depth. Without a hit within
// defaultDistance the crosshair stays at defaultDistance; with one it sits `margin` in front of the hit,
// never nearer than max(camera.nearPlane, kMinCrosshairDepth).
// A pure function of this frame: the seed's smoothing over frames comes later, with frame sequences.
// Throws std::invalid_argument when defaultDistance is not positive and finite or margin is negative/NaN.
CrosshairPlacement placeCrosshair(const WorldQueries& world, const renderer::Camera& camera, float defaultDistance,
                                  float margin = 0.25f);

}  // namespace s3d::comfort
