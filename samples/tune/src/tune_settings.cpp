#include "s3d/tune/tune_settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "s3d/comfort/display_profile.h"
#include "s3d/io/image_io.h"

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

void validate(const TuneSettings& settings) {
  stereo::validate(settings.stereo);
  comfort::ZeroParallaxControlSettings control = settings.zeroParallax;
  control.restDistance = settings.stereo.zeroParallaxDistance;
  control.minimumDistance = std::min(control.minimumDistance, control.restDistance);  // as the sequence job does
  comfort::validate(control);
  if (!(settings.crosshairDistance > 0.0f) || !std::isfinite(settings.crosshairDistance))
    throw std::invalid_argument("crosshairDistance must be a positive distance (got " +
                                std::to_string(settings.crosshairDistance) + ")");
  (void)comfort::builtInDisplayProfile(settings.display);  // throws naming the profile and the choices
}

const std::vector<std::string>& parameterNames() {
  static const std::vector<std::string> names = {
      "maxSeparation",     "zeroParallaxDistance", "edgeCrop",           "method",
      "taps",              "iterations",           "weaponDepthOffset",  "weaponDepthScale",
      "zppControl",        "zppEngageDistance",    "zppReleaseMargin",   "zppMinimumDistance",
      "zppResponseSeconds", "zppMaxChangePerSecond", "crosshairDistance", "display"};
  return names;
}

namespace {
// One parameter from its text form, without checking the whole: a profile sets all before validating once.
void assignParameter(TuneSettings& next, const std::string& name, const std::string& value) {
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
  } else if (name == "taps") next.stereo.searchTaps = parseIntegerOf(name, value);
  else if (name == "iterations") next.stereo.iterations = parseIntegerOf(name, value);
  else if (name == "weaponDepthOffset") next.stereo.weaponDepthOffset = number();
  else if (name == "weaponDepthScale") next.stereo.weaponDepthScale = number();
  else if (name == "zppControl") next.zeroParallaxControl = parseSwitchOf(name, value);
  else if (name == "zppEngageDistance") next.zeroParallax.engageDistance = number();
  else if (name == "zppReleaseMargin") next.zeroParallax.releaseMargin = number();
  else if (name == "zppMinimumDistance") next.zeroParallax.minimumDistance = number();
  else if (name == "zppResponseSeconds") next.zeroParallax.responseSeconds = number();
  else if (name == "zppMaxChangePerSecond") next.zeroParallax.maxChangePerSecond = number();
  else if (name == "crosshairDistance") next.crosshairDistance = number();
  else if (name == "display") next.display = value;
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

nlohmann::json profileJson(const TuneSettings& settings) {
  const stereo::StereoParameters& s = settings.stereo;
  const comfort::ZeroParallaxControlSettings& z = settings.zeroParallax;
  return {{"maxSeparation", s.maxSeparation},
          {"zeroParallaxDistance", s.zeroParallaxDistance},
          {"edgeCrop", s.edgeCrop},
          {"method", stereo::methodName(s.method)},
          {"taps", s.searchTaps},
          {"iterations", s.iterations},
          {"weaponDepthOffset", s.weaponDepthOffset},
          {"weaponDepthScale", s.weaponDepthScale},
          {"zppControl", settings.zeroParallaxControl},
          {"zppEngageDistance", z.engageDistance},
          {"zppReleaseMargin", z.releaseMargin},
          {"zppMinimumDistance", z.minimumDistance},
          {"zppResponseSeconds", z.responseSeconds},
          {"zppMaxChangePerSecond", z.maxChangePerSecond},
          {"crosshairDistance", settings.crosshairDistance},
          {"display", settings.display}};
}

TuneSettings settingsFromProfile(const nlohmann::json& profile, TuneSettings base) {
  if (!profile.is_object()) throw std::invalid_argument("a comfort profile must be a JSON object");
  for (const auto& [name, value] : profile.items()) {
    std::string text;
    if (value.is_string()) text = value.get<std::string>();
    else if (value.is_boolean()) text = value.get<bool>() ? "on" : "off";
    else if (value.is_number()) {
      std::ostringstream stream;
      stream.precision(9);  // round-trips a float
      stream << value.get<double>();
      text = stream.str();
    } else
      throw std::invalid_argument(name + ": expected a number, a name or true/false (got " + value.dump() + ")");
    assignParameter(base, name, text);
  }
  validate(base);
  return base;
}

void saveProfile(const std::filesystem::path& path, const TuneSettings& settings) {
  validate(settings);
  io::writeTextFile(path, profileJson(settings).dump(2) + "\n");
}

TuneSettings loadProfile(const std::filesystem::path& path, const TuneSettings& base) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot open comfort profile '" + path.string() + "'");
  nlohmann::json profile;
  try {
    profile = nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& error) {
    throw std::invalid_argument("comfort profile '" + path.string() + "' is not valid JSON: " + error.what());
  }
  try {
    return settingsFromProfile(profile, base);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument("comfort profile '" + path.string() + "': " + error.what());
  }
}

}  // namespace s3d::tune
