#pragma once
// `s3d tune`: every parameter the panel edits, by name (shared by the sliders, the --script `set` command and
// the comfort profile), and the view modes the window can show.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/comfort/comfort_profile.h"

namespace s3d::tune {

// What the view area shows.
enum class ViewMode {
  Anaglyph,         // red-cyan Dubois anaglyph of the synthesized eyes (what `s3d render` writes as anaglyph.png)
  SideBySide,       // half side-by-side of the synthesized eyes
  Left,             // the synthesized left eye
  Right,            // the synthesized right eye
  Reference,        // anaglyph of the two-pass reference eyes
  ErrorHeatMap,     // half side-by-side of both eyes' error heat maps against the reference
  ParallaxHeatMap,  // the parallax the stereo pass gives every pixel
  ComfortOverlay,   // the anaglyph with pixels beyond the comfort limit (1 degree of disparity) marked
};

// "anaglyph", "sbs", "left", "right", "reference", "error", "parallax", "comfort", in ViewMode order.
const std::vector<std::string>& viewModeNames();
const char* viewModeName(ViewMode mode);
ViewMode parseViewMode(const std::string& name);  // throws std::invalid_argument listing the choices
bool viewNeedsReference(ViewMode mode);          // the view shows the two-pass reference eyes or their error

struct TuneSettings {
  // Every stereo and comfort parameter (stereo, weapon push, zero-parallax control, crosshair, display): what a
  // comfort profile holds (comfort_profile.h).
  comfort::ComfortProfile profile;
  // Seed 4.6.2's zero-parallax control on the live camera, resting at profile.stereo.zeroParallaxDistance: a
  // switch of the tool (`s3d render --sequence` always runs it), so not part of the profile.
  bool zeroParallaxControl = false;
};

// Throws std::invalid_argument naming the first invalid value.
void validate(const TuneSettings& settings);

// The parameter names, in panel order: maxSeparation, zeroParallaxDistance, edgeCrop, method, taps, iterations,
// weaponDepthOffset, weaponDepthScale, zppControl, zppEngageDistance, zppReleaseMargin, zppMinimumDistance,
// zppResponseSeconds, zppMaxChangePerSecond, crosshairDistance, crosshairMargin, display, allowNegativeParallax.
const std::vector<std::string>& parameterNames();

// Sets one parameter from its text form (numbers; method by name; display by built-in name or a .json display
// profile's path; zppControl and allowNegativeParallax on/off/true/false).
// Throws std::invalid_argument naming the parameter (unknown name, unparsable or invalid value); the settings
// are left unchanged then.
void setParameter(TuneSettings& settings, const std::string& name, const std::string& value);

// Comfort profiles (comfort::saveComfortProfile / loadComfortProfile): loading replaces settings.profile (keys a
// profile leaves out take their defaults) and keeps the tool's own switches. Errors name the file and the key.
void saveProfile(const std::filesystem::path& path, const TuneSettings& settings);
TuneSettings loadProfile(const std::filesystem::path& path, TuneSettings base = {});

}  // namespace s3d::tune
