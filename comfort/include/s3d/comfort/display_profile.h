#pragma once
// Viewing geometry for the comfort report: on-screen parallax -> angular disparity for a given display.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/comfort/view_configuration.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

struct DisplayProfile {
  std::string name;
  float screenWidthMeters = 1.218f;    // the image's width on the screen (55-inch 16:9 television)
  float viewingDistanceMeters = 2.5f;  // eyes to screen (for a head-mounted display: its focal distance)
  float interocularMeters = 0.063f;
  // Head-mounted display only (0: a flat screen): the horizontal field of view in degrees. Its virtual screen
  // lies at the focal distance f = viewingDistanceMeters and spans screenWidthMeters = 2 f tan(fov / 2).
  float fieldOfViewDegrees = 0.0f;
  // The per-eye views the display reports (a headset's, as OpenXR gives them; view_configuration.h), if known:
  // `s3d render` then synthesizes those eyes, as with --views.
  std::optional<ViewConfiguration> eyeViews;
};

// A head-mounted display focused at `focalDistanceMeters` with a horizontal field of view (degrees).
DisplayProfile headMountedDisplay(std::string name, float focalDistanceMeters, float fieldOfViewDegrees,
                                  float interocularMeters = 0.063f);

// "tv55" (55-inch 16:9 at 2.5 m), "monitor27" (27-inch 16:9 at 0.7 m), "hmd" (90-degree horizontal field of
// view focused at 1.3 m, so the virtual screen is 2.6 m wide). Throws std::invalid_argument listing them.
DisplayProfile builtInDisplayProfile(const std::string& name);
std::vector<std::string> builtInDisplayProfileNames();

// Throws std::invalid_argument naming the first field that is not finite or outside its range (widths and
// distances in (0, 100] m, interocular distance in [0.04, 0.08] m, field of view in (0, 170) degrees).
void validate(const DisplayProfile& display);

// JSON form. A flat screen: {"name", "screenWidthMeters", "viewingDistanceMeters", "interocularMeters"};
// a head-mounted display: {"name", "focalDistanceMeters", "fieldOfViewDegrees", "interocularMeters"}.
// "interocularMeters" may be left out (63 mm), "name" too (then "custom"); either may hold "eyeViews": a views
// document (view_configuration.h's format). Unknown keys, missing or out-of-range values throw
// std::invalid_argument naming the key.
DisplayProfile displayProfileFromJson(const nlohmann::json& document);
nlohmann::json toJson(const DisplayProfile& display);
// Reads a JSON display profile; errors name the file (std::runtime_error for I/O, invalid_argument for content).
DisplayProfile loadDisplayProfile(const std::filesystem::path& file);
// A built-in name, or else the path of a JSON display profile (anything ending in .json).
DisplayProfile resolveDisplayProfile(const std::string& nameOrFile);

// Angular disparity in arcminutes of a point shown with on-screen parallax `parallaxMeters` (right-eye image
// minus left-eye image position; positive: behind the screen): the difference between the vergence angle of
// the screen and that of the point. Parallax at or beyond the interocular distance diverges the eyes: the
// result is then the screen's full vergence angle plus the excess, still finite.
double disparityArcminutes(const DisplayProfile& display, double parallaxMeters);

struct ParallaxStatistics {
  double minParallaxPx = 0.0, maxParallaxPx = 0.0;            // right-eye minus left-eye position
  // The 5th and 95th percentile of the parallax of the pixels with finite depth: the range the bulk of the
  // scene's geometry spans (the depth impression a mapping keeps, without the few nearest and farthest pixels
  // and without the sky, which sits at the far end of the range whatever the mapping). 0 without geometry.
  double p05ParallaxPx = 0.0, p95ParallaxPx = 0.0;
  double minParallaxPercent = 0.0, maxParallaxPercent = 0.0;  // of the image width
  double minDisparityArcmin = 0.0, maxDisparityArcmin = 0.0;
  double shareBeyondOneDegree = 0.0;  // pixels whose |disparity| exceeds 60 arcminutes (the 1-degree rule)
  double shareNegative = 0.0;         // pixels in front of the screen
};

// Over the pixels of the stereo pass's linear depth (weapon pushed): the parallax each pixel is given,
// 2 * parallaxFromDepth(depth) * width between the eyes.
ParallaxStatistics parallaxStatistics(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                                      const DisplayProfile& display);

}  // namespace s3d::comfort
