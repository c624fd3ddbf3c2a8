#pragma once
// `s3d tune`: every parameter the panel edits, by name (shared by the sliders, the --script `set` command and
// the comfort profile), and the view modes the window can show.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/comfort/zero_parallax_control.h"
#include "s3d/stereo/stereo.h"

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
  stereo::StereoParameters stereo;  // maxSeparation, zeroParallaxDistance, edgeCrop, method, taps, weapon push
  // Seed 4.6.2's zero-parallax control on the live camera; its restDistance is stereo.zeroParallaxDistance.
  bool zeroParallaxControl = false;
  comfort::ZeroParallaxControlSettings zeroParallax;
  float crosshairDistance = 8.0f;  // HUD crosshair depth without a hit (world units; the scenes' default)
  std::string display = "tv55";    // comfort numbers: one of comfort::builtInDisplayProfileNames()
};

// Throws std::invalid_argument naming the first invalid value.
void validate(const TuneSettings& settings);

// The parameter names, in panel order: maxSeparation, zeroParallaxDistance, edgeCrop, method, taps, iterations,
// weaponDepthOffset, weaponDepthScale, zppControl, zppEngageDistance, zppReleaseMargin, zppMinimumDistance,
// zppResponseSeconds, zppMaxChangePerSecond, crosshairDistance, display.
const std::vector<std::string>& parameterNames();

// Sets one parameter from its text form (numbers; method and display by name; zppControl on/off/true/false).
// Throws std::invalid_argument naming the parameter (unknown name, unparsable or invalid value); the settings
// are left unchanged then.
void setParameter(TuneSettings& settings, const std::string& name, const std::string& value);

// Comfort profile: a flat JSON object of parameterNames() -> value. Until the comfort module's profile format
// lands in main, the tool saves and loads through these two functions only (one place to swap).
nlohmann::json profileJson(const TuneSettings& settings);
TuneSettings settingsFromProfile(const nlohmann::json& profile, TuneSettings base = {});  // unknown key: throws
void saveProfile(const std::filesystem::path& path, const TuneSettings& settings);  // atomic (s3d::io)
TuneSettings loadProfile(const std::filesystem::path& path, const TuneSettings& base = {});

}  // namespace s3d::tune
