#include "s3d/tune/tune_settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "s3d/comfort/display_profile.h"

namespace s3d::tune {
namespace {

std::string joinedNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

double parseNumberOf(const std::string& name, const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value))
    throw std::invalid_argument(name + ": expected a number (got '" + text + "')");
  return value;
}

int parseIntegerOf(const std::string& name, const std::string& text) {
  const double value = parseNumberOf(name, text);
  if (value != std::floor(value) || std::abs(value) > 1.0e6)
    throw std::invalid_argument(name + ": expected a whole number (got '" + text + "')");
  return int(value);
}

bool parseSwitchOf(const std::string& name, const std::string& text) {
  if (text == "on" || text == "true" || text == "1") return true;
  if (text == "off" || text == "false" || text == "0") return false;
  throw std::invalid_argument(name + ": expected on or off (got '" + text + "')");
}

}  // namespace

const std::vector<std::string>& viewModeNames() {
  static const std::vector<std::string> names = {"anaglyph",  "sbs",   "left",     "right",
                                                 "reference", "error", "parallax", "comfort"};
  return names;
}

const char* viewModeName(ViewMode mode) { return viewModeNames().at(std::size_t(mode)).c_str(); }

ViewMode parseViewMode(const std::string& name) {
  const std::vector<std::string>& names = viewModeNames();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return ViewMode(i);
  throw std::invalid_argument("unknown view '" + name + "' (choices: " + joinedNames(names) + ")");
}

bool viewNeedsReference(ViewMode mode) { return mode == ViewMode::Reference || mode == ViewMode::ErrorHeatMap; }

void validate(const TuneSettings& settings) { comfort::validate(settings.profile); }

const std::vector<std::string>& parameterNames() {
  static const std::vector<std::string> names = {
      "maxSeparation",     "zeroParallaxDistance", "edgeCrop",           "method",
      "taps",              "iterations",           "weaponDepthOffset",  "weaponDepthScale",
      "zppControl",        "zppEngageDistance",    "zppReleaseMargin",   "zppMinimumDistance",
      "zppResponseSeconds", "zppMaxChangePerSecond", "crosshairDistance", "crosshairMargin", "display",
      "allowNegativeParallax", "hybridBudget", "hybridBase", "hybridCell", "hybridScoreFloor",
      "disparityMapping"};
  return names;
}

namespace {
// One parameter from its text form, without checking the whole: a profile sets all before validating once.
void assignParameter(TuneSettings& settings, const std::string& name, const std::string& value) {
  comfort::ComfortProfile& next = settings.profile;
  auto number = [&] { return float(parseNumberOf(name, value)); };
  if (name == "maxSeparation") next.stereo.maxSeparation = number();
  else if (name == "zeroParallaxDistance") next.stereo.zeroParallaxDistance = number();
  else if (name == "edgeCrop") next.stereo.edgeCrop = number();
  else if (name == "method") {
    try {
      next.stereo.method = stereo::parseStereoMethod(value);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("method: " + std::string(error.what()));
    }
  } else if (name == "hybridBase") {
    try {
      next.stereo.hybridBase = stereo::parseStereoMethod(value);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("hybridBase: " + std::string(error.what()));
    }
  } else if (name == "hybridBudget") next.stereo.hybridBudget = number();
  else if (name == "hybridCell") next.stereo.hybridCell = parseIntegerOf(name, value);
  else if (name == "hybridScoreFloor") next.stereo.hybridScoreFloor = number();
  else if (name == "taps") next.stereo.searchTaps = parseIntegerOf(name, value);
  else if (name == "iterations") next.stereo.iterations = parseIntegerOf(name, value);
  else if (name == "weaponDepthOffset") next.stereo.weaponDepthOffset = number();
  else if (name == "weaponDepthScale") next.stereo.weaponDepthScale = number();
  else if (name == "zppControl") settings.zeroParallaxControl = parseSwitchOf(name, value);
  else if (name == "zppEngageDistance") next.zeroParallax.engageDistance = number();
  else if (name == "zppReleaseMargin") next.zeroParallax.releaseMargin = number();
  else if (name == "zppMinimumDistance") next.zeroParallax.minimumDistance = number();
  else if (name == "zppResponseSeconds") next.zeroParallax.responseSeconds = number();
  else if (name == "zppMaxChangePerSecond") next.zeroParallax.maxChangePerSecond = number();
  else if (name == "crosshairDistance") next.crosshair.distance = number();
  else if (name == "crosshairMargin") next.crosshair.margin = number();
  else if (name == "allowNegativeParallax") next.allowNegativeParallax = parseSwitchOf(name, value);
  else if (name == "disparityMapping") {
    try {
      next.stereo.disparityMapping = stereo::parseDisparityMapping(value);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("disparityMapping: " + std::string(error.what()));
    }
  }
  else if (name == "display") {
    try {
      next.display = comfort::resolveDisplayProfile(value);
    } catch (const std::exception& error) {
      throw std::invalid_argument("display: " + std::string(error.what()));
    }
  }
  else
    throw std::invalid_argument("unknown parameter '" + name + "' (choices: " + joinedNames(parameterNames()) + ")");
}
}  // namespace

void setParameter(TuneSettings& settings, const std::string& name, const std::string& value) {
  TuneSettings next = settings;  // all or nothing: an invalid value leaves the settings as they were
  assignParameter(next, name, value);
  try {
    validate(next);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(name + " = " + value + ": " + error.what());
  }
  settings = next;
}

void saveProfile(const std::filesystem::path& path, const TuneSettings& settings) {
  comfort::saveComfortProfile(path, settings.profile);
}

TuneSettings loadProfile(const std::filesystem::path& path, TuneSettings base) {
  base.profile = comfort::loadComfortProfile(path);
  return base;
}

}  // namespace s3d::tune
