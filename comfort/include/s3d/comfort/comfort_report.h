#pragma once
// The per-frame comfort report beyond the parallax range (display_profile.h): stereo window violations and the
// rules that keep every pixel at or behind the screen plane. (No zone of comfort in vergence distance: the
// constants of Shibata et al. 2011's fit could not be checked against the paper, so the 1-degree rule of
// display_profile.h is the only disparity limit reported and budgeted; docs/DESIGN.md "Comfort report".)
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/camera.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

// Distance from the eyes at which the lines of sight through two image points `parallaxMeters` apart cross
// (e v / (e - P)); +inf when they are parallel or diverge (P >= e).
double vergenceDistanceMeters(const DisplayProfile& display, double parallaxMeters);

struct FrameComfort {
  ParallaxStatistics parallax;
  // Stereo window violations: negative-parallax pixels in horizontal runs that touch the left or right edge
  // of the visible image (inside the edge crop). The frame's edge cuts off an object in front of it.
  std::uint64_t windowViolationPixels = 0;
  std::uint32_t windowViolationColumns = 0;  // the widest such run, in columns
};

// The rules of FrameComfort a pixel breaks, as bit flags (frameComfort's `violations`).
inline constexpr std::uint8_t kBeyondOneDegree = 1;  // |disparity| over 60 arcmin: parallax.shareBeyondOneDegree
inline constexpr std::uint8_t kWindowViolation = 2;  // counted in windowViolationPixels

// Over the stereo pass's linear depth (weapon pushed), as parallaxStatistics does. When `violations` is
// given it receives, per pixel (row-major), the flags above (for overlays such as `s3d tune`'s comfort view).
FrameComfort frameComfort(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                          const DisplayProfile& display, std::vector<std::uint8_t>* violations = nullptr);

// With negative parallax disallowed, the weapon push (pushed = offset + scale * d over the weapon's unpushed
// depth range [weaponNearest, weaponFarthest]) made to keep the whole weapon at or behind the zero-parallax
// plane. A weapon whose nearest pushed point is in front of the plane is squeezed: that point moves onto the
// plane while the farthest pushed point stays where it was (it may be capped to stay in front of a wall);
// when the farthest point is itself in front of the plane, the whole weapon is shifted back instead.
stereo::StereoParameters pushWeaponBehindScreen(stereo::StereoParameters parameters, float weaponNearest,
                                                float weaponFarthest);

// The nearest finite positive depth of the frame, if any: the zero-parallax distance may not exceed it when
// negative parallax is disallowed.
std::optional<float> nearestDepth(const DepthImage& stereoDepth);

struct WeaponConflicts {
  std::uint64_t weaponPixels = 0;
  std::uint64_t conflictPixels = 0;  // weapon pixels whose pushed depth lies behind the world surface there
};

// For every weapon pixel (weaponMask, the renderer's first-person mask), casts the world camera's ray through
// the pixel center into the Embree world: a world hit nearer than the pixel's pushed depth means the pushed
// weapon would appear behind a wall it is in front of. `projection`: the camera's projection of the depth image
// (Vulkan clip space, its aspect ratio).
WeaponConflicts countWeaponConflicts(const WorldQueries& world, const Camera& camera, const glm::mat4& projection,
                                     const DepthImage& pushedDepth, const std::vector<std::uint8_t>& weaponMask);

// Comfort of one eye of a per-eye view configuration (view_configuration.h, a head-mounted display): the eye is
// the view's own camera, so every pixel shows its surface at its true distance: vergence at the pixel's view depth
// over the views' world scale (metres), accommodation at the display's focal distance (viewingDistanceMeters; for
// the "hmd" profile 1.3 m). Both are taken along the view axis (the virtual image is a plane at the focal distance).
struct EyeViewComfort {
  std::uint64_t pixelCount = 0;        // pixels with known depth (sky included: vergence at infinity)
  double meanConflictDiopters = 0.0;   // vergence-accommodation conflict |1 / vergence - 1 / focal|
  double p95ConflictDiopters = 0.0;
  double maxConflictDiopters = 0.0;
  // The 1-degree rule of the flat-screen report with the focal plane as the screen: the vergence angle more than
  // 60 arcminutes from the focal plane's.
  double shareBeyondOneDegree = 0.0;
  double nearestMeters = 0.0;            // the nearest vergence distance shown
};

// `eyeDepth`: the linear view depth each eye pixel shows (world units; +inf sky, NaN or <= 0 unknown and left
// out); `interocularMeters`: the views' eye separation. When `conflictDiopters` is given it receives the conflict
// per pixel (row-major; NaN where the depth is unknown). Throws std::invalid_argument for an empty image or a
// non-positive world scale or separation.
EyeViewComfort eyeViewComfort(const DepthImage& eyeDepth, double worldScale, double interocularMeters,
                              const DisplayProfile& display, std::vector<float>* conflictDiopters = nullptr);

}  // namespace s3d::comfort
