#include "s3d/comfort/display_profile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "s3d/number_text.h"

#include "json_fields.h"

namespace s3d::comfort {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kArcminutesPerRadian = 180.0 * 60.0 / kPi;

// Ranges of the profile's fields (checked by validate and by the JSON reader alike).
constexpr detail::Range kLengthRange{0.0, 100.0, true};        // metres: any real screen or focal distance
constexpr detail::Range kInterocularRange{0.04, 0.08};         // metres: the adult range with margin
constexpr detail::Range kFieldOfViewRange{0.0, 170.0, true, true};  // degrees: tan(fov / 2) stays finite

void requireIn(float value, detail::Range range, const char* name) {
  const bool below = range.lowOpen ? !(value > range.low) : !(value >= range.low);
  const bool above = range.highOpen ? !(value < range.high) : !(value <= range.high);
  if (!std::isfinite(value) || below || above)
    throw std::invalid_argument(std::string("display profile: ") + name + " = " + numberText(value) +
                                " is outside " + detail::describe(range));
}

}  // namespace

std::vector<std::string> builtInDisplayProfileNames() { return {"tv55", "monitor27", "hmd"}; }

DisplayProfile builtInDisplayProfile(const std::string& name) {
  // 16:9 width of a diagonal d: d * 16 / sqrt(16^2 + 9^2) inches.
  auto widthOfDiagonal = [](double inches) { return float(inches * 0.0254 * 16.0 / std::sqrt(337.0)); };
  if (name == "tv55") return {name, widthOfDiagonal(55.0), 2.5f, 0.063f};
  if (name == "monitor27") return {name, widthOfDiagonal(27.0), 0.7f, 0.063f};
  if (name == "hmd") return headMountedDisplay(name, 1.3f, 90.0f);
  std::string choices;
  for (const std::string& n : builtInDisplayProfileNames()) choices += (choices.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown display profile '" + name + "' (choices: " + choices + ", or a .json display profile)");
}

DisplayProfile headMountedDisplay(std::string name, float focalDistanceMeters, float fieldOfViewDegrees,
                                  float interocularMeters) {
  DisplayProfile display;
  display.name = std::move(name);
  display.viewingDistanceMeters = focalDistanceMeters;
  display.fieldOfViewDegrees = fieldOfViewDegrees;
  display.interocularMeters = interocularMeters;
  // The virtual screen at the focal distance spans the field of view.
  display.screenWidthMeters = float(2.0 * focalDistanceMeters * std::tan(0.5 * fieldOfViewDegrees * kPi / 180.0));
  return display;
}

void validate(const DisplayProfile& display) {
  requireIn(display.screenWidthMeters, kLengthRange, "screenWidthMeters");
  requireIn(display.viewingDistanceMeters, kLengthRange, "viewingDistanceMeters");
  requireIn(display.interocularMeters, kInterocularRange, "interocularMeters");
  if (display.fieldOfViewDegrees != 0.0f) requireIn(display.fieldOfViewDegrees, kFieldOfViewRange, "fieldOfViewDegrees");
}

DisplayProfile displayProfileFromJson(const nlohmann::json& document) {
  detail::ObjectReader reader(document, "display");
  DisplayProfile display;
  display.name = "custom";
  if (const nlohmann::json* name = reader.find("name")) {
    if (!name->is_string() || name->get<std::string>().empty())
      throw std::invalid_argument("'display.name' must be a non-empty string");
    display.name = name->get<std::string>();
  }
  reader.number("interocularMeters", display.interocularMeters, kInterocularRange);
  const bool headMounted = document.contains("fieldOfViewDegrees") || document.contains("focalDistanceMeters");
  auto require = [&](const char* key) {
    if (!document.contains(key))
      throw std::invalid_argument("'" + reader.pathOf(key) + "' is missing (" +
                                  (headMounted ? "a head-mounted display needs focalDistanceMeters and fieldOfViewDegrees"
                                               : "a screen needs screenWidthMeters and viewingDistanceMeters") +
                                  ")");
  };
  if (headMounted) {
    require("focalDistanceMeters");
    require("fieldOfViewDegrees");
    float focal = 0.0f, fieldOfView = 0.0f;
    reader.number("focalDistanceMeters", focal, kLengthRange);
    reader.number("fieldOfViewDegrees", fieldOfView, kFieldOfViewRange);
    display = headMountedDisplay(display.name, focal, fieldOfView, display.interocularMeters);
  } else {
    require("screenWidthMeters");
    require("viewingDistanceMeters");
    reader.number("screenWidthMeters", display.screenWidthMeters, kLengthRange);
    reader.number("viewingDistanceMeters", display.viewingDistanceMeters, kLengthRange);
  }
  if (const nlohmann::json* views = reader.find("eyeViews")) {
    try {
      display.eyeViews = viewConfigurationFromJson(*views);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("'" + reader.pathOf("eyeViews") + "': " + error.what());
    }
  }
  reader.finish();
  return display;
}

nlohmann::json toJson(const DisplayProfile& display) {
  nlohmann::json document{{"name", display.name}, {"interocularMeters", detail::shortest(display.interocularMeters)}};
  if (display.fieldOfViewDegrees > 0.0f) {
    document["focalDistanceMeters"] = detail::shortest(display.viewingDistanceMeters);
    document["fieldOfViewDegrees"] = detail::shortest(display.fieldOfViewDegrees);
  } else {
    document["screenWidthMeters"] = detail::shortest(display.screenWidthMeters);
    document["viewingDistanceMeters"] = detail::shortest(display.viewingDistanceMeters);
  }
  if (display.eyeViews) document["eyeViews"] = toJson(*display.eyeViews);
  return document;
}

DisplayProfile loadDisplayProfile(const std::filesystem::path& file) {
  const nlohmann::json document = detail::readJsonFile(file, "display profile");
  try {
    return displayProfileFromJson(document);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument("display profile '" + file.string() + "': " + error.what());
  }
}

DisplayProfile resolveDisplayProfile(const std::string& nameOrFile) {
  const bool isFile = nameOrFile.size() > 5 && nameOrFile.compare(nameOrFile.size() - 5, 5, ".json") == 0;
  if (isFile) return loadDisplayProfile(nameOrFile);
  return builtInDisplayProfile(nameOrFile);  // throws listing the built-in names
}

double disparityArcminutes(const DisplayProfile& display, double parallaxMeters) {
  const double e = display.interocularMeters, v = display.viewingDistanceMeters;
  const double screenVergence = 2.0 * std::atan(e / (2.0 * v));
  // The lines of sight through the two image points cross at the angle 2 atan((e - P) / (2 v)); beyond
  // P = e they diverge, which the same formula gives as a negative vergence.
  const double pointVergence = 2.0 * std::atan((e - parallaxMeters) / (2.0 * v));
  return (screenVergence - pointVergence) * kArcminutesPerRadian;
}

ParallaxStatistics parallaxStatistics(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                                      const DisplayProfile& display) {
  if (stereoDepth.empty()) throw std::invalid_argument("parallaxStatistics: empty depth image");
  ParallaxStatistics stats;
  stats.minParallaxPx = std::numeric_limits<double>::infinity();
  stats.maxParallaxPx = -std::numeric_limits<double>::infinity();
  std::uint64_t beyond = 0, negative = 0;
  const double width = double(stereoDepth.width);
  std::vector<float> parallaxes;
  parallaxes.reserve(stereoDepth.pixelCount());
  for (float depth : stereoDepth.pixels) {
    const float sanitized = gpu::sanitizedDepth(depth, parameters.zeroParallaxDistance);
    const double parallaxPx =
        2.0 * double(gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, sanitized)) * width;
    stats.minParallaxPx = std::min(stats.minParallaxPx, parallaxPx);
    stats.maxParallaxPx = std::max(stats.maxParallaxPx, parallaxPx);
    if (std::isfinite(sanitized)) parallaxes.push_back(float(parallaxPx));
    const double disparity = disparityArcminutes(display, parallaxPx / width * display.screenWidthMeters);
    if (std::abs(disparity) > 60.0) ++beyond;
    if (parallaxPx < 0.0) ++negative;
  }
  auto percentile = [&](double share) {
    if (parallaxes.empty()) return 0.0;
    const auto at = parallaxes.begin() + std::ptrdiff_t(share * double(parallaxes.size() - 1) + 0.5);
    std::nth_element(parallaxes.begin(), at, parallaxes.end());
    return double(*at);
  };
  stats.p05ParallaxPx = percentile(0.05);
  stats.p95ParallaxPx = percentile(0.95);
  const double pixels = double(stereoDepth.pixelCount());
  stats.minParallaxPercent = 100.0 * stats.minParallaxPx / width;
  stats.maxParallaxPercent = 100.0 * stats.maxParallaxPx / width;
  stats.minDisparityArcmin = disparityArcminutes(display, stats.minParallaxPx / width * display.screenWidthMeters);
  stats.maxDisparityArcmin = disparityArcminutes(display, stats.maxParallaxPx / width * display.screenWidthMeters);
  stats.shareBeyondOneDegree = double(beyond) / pixels;
  stats.shareNegative = double(negative) / pixels;
  return stats;
}

}  // namespace s3d::comfort
