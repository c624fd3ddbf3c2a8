#include "s3d/comfort/display_profile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace s3d::comfort {
namespace {

constexpr double kArcminutesPerRadian = 180.0 * 60.0 / 3.14159265358979323846;

}  // namespace

std::vector<std::string> builtInDisplayProfileNames() { return {"tv55", "monitor27", "hmd"}; }

DisplayProfile builtInDisplayProfile(const std::string& name) {
  // 16:9 width of a diagonal d: d * 16 / sqrt(16^2 + 9^2) inches.
  auto widthOfDiagonal = [](double inches) { return float(inches * 0.0254 * 16.0 / std::sqrt(337.0)); };
  if (name == "tv55") return {name, widthOfDiagonal(55.0), 2.5f, 0.063f};
  if (name == "monitor27") return {name, widthOfDiagonal(27.0), 0.7f, 0.063f};
  if (name == "hmd") return {name, float(2.0 * 1.3 * std::tan(0.5 * 3.14159265358979323846 / 2.0)), 1.3f, 0.063f};
  std::string choices;
  for (const std::string& n : builtInDisplayProfileNames()) choices += (choices.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown display profile '" + name + "' (choices: " + choices + ")");
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
  for (float depth : stereoDepth.pixels) {
    const float sanitized = gpu::sanitizedDepth(depth, parameters.zeroParallaxDistance);
    const double parallaxPx =
        2.0 * double(gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, sanitized)) * width;
    stats.minParallaxPx = std::min(stats.minParallaxPx, parallaxPx);
    stats.maxParallaxPx = std::max(stats.maxParallaxPx, parallaxPx);
    const double disparity = disparityArcminutes(display, parallaxPx / width * display.screenWidthMeters);
    if (std::abs(disparity) > 60.0) ++beyond;
    if (parallaxPx < 0.0) ++negative;
  }
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
