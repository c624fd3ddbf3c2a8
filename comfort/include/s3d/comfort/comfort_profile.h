#pragma once
// Comfort profiles: every stereo and comfort parameter of a render in one struct, loaded from and saved to
// JSON (`s3d render --profile FILE`, `--save-profile FILE`, and the `s3d tune` tool). Reading is strict:
// unknown keys and out-of-range values are errors naming the key (and the file); keys left out keep their
// defaults, so a profile may hold only what it changes.
//
// The JSON document (every key optional; defaults are those of the structs below):
// { "stereo": {"maxSeparation", "zeroParallaxDistance", "edgeCrop" (null: s3d render a guard band, else = maxSeparation),
//              "method": "seed"|"search"|"iterative"|"forward", "searchTaps", "iterations"},
//   "weapon": {"depthOffset", "depthScale"},
//   "zeroParallaxControl": {"engageDistance", "releaseMargin", "minimumDistance", "responseSeconds",
//                           "maxChangePerSecond", "ringRays", "ringAngleRadians"},
//   "crosshair": {"distance" (null: the scene's), "margin", "responseSeconds"},
//   "display": "tv55"|"monitor27"|"hmd" or a display object (display_profile.h's toJson form),
//   "allowNegativeParallax": false }
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/zero_parallax_control.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

// The crosshair's placement over frames (seed 4.6.2: "smoothly moved towards the viewer").
struct CrosshairSettings {
  std::optional<float> distance;  // default crosshair depth (world units); nullopt: the scene's own
  float margin = 0.25f;           // in front of an aim-ray hit (world units)
  float responseSeconds = 0.1f;   // time constant of its critically damped approach over frames
};

struct ComfortProfile {
  // maxSeparation, zeroParallaxDistance (the zero-parallax control's rest value), edgeCrop, method,
  // searchTaps, iterations, and the weapon depth push (weaponDepthOffset, weaponDepthScale).
  stereo::StereoParameters stereo;
  // Thresholds, damping, per-frame bound, hysteresis and ray pattern. Its restDistance is not part of the
  // profile: the control rests at stereo.zeroParallaxDistance (see zeroParallaxSettings()).
  ZeroParallaxControlSettings zeroParallax;
  CrosshairSettings crosshair;
  DisplayProfile display = builtInDisplayProfile("tv55");  // a built-in profile or a custom display
  // Off (default): nothing in the frame gets negative parallax (the weapon push and the ZPP control keep
  // everything at or behind the screen plane). On: the weapon may pop out of the screen.
  bool allowNegativeParallax = false;

  // zeroParallax with restDistance = stereo.zeroParallaxDistance (and minimumDistance no larger).
  ZeroParallaxControlSettings zeroParallaxSettings() const;
};

// Throws std::invalid_argument naming the first out-of-range or inconsistent parameter.
void validate(const ComfortProfile& profile);

// Strict reading (see the top of this file); throws std::invalid_argument naming the key and the problem.
ComfortProfile comfortProfileFromJson(const nlohmann::json& document);
// Every key written (edgeCrop < 0 as null, a built-in display by its name): comfortProfileFromJson(toJson(p))
// gives p back.
nlohmann::json toJson(const ComfortProfile& profile);

// Reads a profile; errors name the file: std::runtime_error when it cannot be read or is not JSON,
// std::invalid_argument for unknown keys or out-of-range values.
ComfortProfile loadComfortProfile(const std::filesystem::path& file);
// Validates, then writes the profile atomically (a temporary file renamed into place); throws
// std::invalid_argument for an invalid profile, std::runtime_error naming the file when writing fails.
void saveComfortProfile(const std::filesystem::path& file, const ComfortProfile& profile);

}  // namespace s3d::comfort
