#include "s3d/comfort/comfort_report.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace s3d::comfort {

double vergenceDistanceMeters(const DisplayProfile& display, double parallaxMeters) {
  const double e = display.interocularMeters;
  if (parallaxMeters >= e) return std::numeric_limits<double>::infinity();
  return e * display.viewingDistanceMeters / (e - parallaxMeters);
}

FrameComfort frameComfort(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                          const DisplayProfile& display, std::vector<std::uint8_t>* violations) {
  FrameComfort comfort;
  comfort.parallax = parallaxStatistics(stereoDepth, parameters, display);  // throws on an empty image
  const std::uint32_t width = stereoDepth.width;
  const gpu::StereoConstants constants = stereo::makeStereoConstants(parameters, width, stereoDepth.height);
  const std::uint32_t visibleBegin = std::uint32_t(std::max(constants.cropBegin, 0));
  const std::uint32_t visibleEnd = std::uint32_t(std::clamp(constants.cropEnd, 0, int(width)));
  auto parallaxPxAt = [&](std::uint32_t x, std::uint32_t y) {
    const float depth = gpu::sanitizedDepth(*stereoDepth.at(x, y), parameters.zeroParallaxDistance);
    return 2.0 * double(gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, depth)) *
           double(width);
  };
  if (violations) violations->assign(stereoDepth.pixelCount(), 0);
  auto flag = [&](std::uint32_t x, std::uint32_t y, std::uint8_t rule) {
    if (violations) (*violations)[std::size_t(y) * width + x] |= rule;
  };
  for (std::uint32_t y = 0; y < stereoDepth.height; ++y) {
    // The count itself is parallaxStatistics'; the flags mark the same pixels.
    if (violations)
      for (std::uint32_t x = 0; x < width; ++x)
        if (std::abs(disparityArcminutes(display, parallaxPxAt(x, y) / double(width) * display.screenWidthMeters)) >
            60.0)  // the 1-degree rule, as parallaxStatistics counts it
          flag(x, y, kBeyondOneDegree);
    // Runs of negative parallax from each visible edge inward.
    std::uint32_t fromLeft = 0, fromRight = 0;
    for (std::uint32_t x = visibleBegin; x < visibleEnd && parallaxPxAt(x, y) < 0.0; ++x) {
      ++fromLeft;
      flag(x, y, kWindowViolation);
    }
    if (fromLeft < visibleEnd - visibleBegin)
      for (std::uint32_t x = visibleEnd; x > visibleBegin && parallaxPxAt(x - 1, y) < 0.0; --x) {
        ++fromRight;
        flag(x - 1, y, kWindowViolation);
      }
    comfort.windowViolationPixels += fromLeft + fromRight;
    comfort.windowViolationColumns = std::max({comfort.windowViolationColumns, fromLeft, fromRight});
  }
  return comfort;
}

stereo::StereoParameters pushWeaponBehindScreen(stereo::StereoParameters parameters, float weaponNearest,
                                                float weaponFarthest) {
  if (!(weaponNearest > 0.0f) || !(weaponFarthest >= weaponNearest))
    throw std::invalid_argument("pushWeaponBehindScreen: the weapon's depth range must be positive and ordered");
  const float screen = parameters.zeroParallaxDistance;
  const float pushedNearest = parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponNearest;
  const float pushedFarthest = parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponFarthest;
  if (pushedNearest >= screen) return parameters;
  if (pushedFarthest > screen && weaponFarthest > weaponNearest) {
    parameters.weaponDepthScale = (pushedFarthest - screen) / (weaponFarthest - weaponNearest);
  }  // else: shifted back whole, at its own scale
  parameters.weaponDepthOffset = screen - parameters.weaponDepthScale * weaponNearest;
  return parameters;
}

std::optional<float> nearestDepth(const DepthImage& stereoDepth) {
  std::optional<float> nearest;
  for (float depth : stereoDepth.pixels)
    if (depth > 0.0f && std::isfinite(depth) && (!nearest || depth < *nearest)) nearest = depth;
  return nearest;
}

WeaponConflicts countWeaponConflicts(const WorldQueries& world, const Camera& camera, const glm::mat4& projection,
                                     const DepthImage& pushedDepth, const std::vector<std::uint8_t>& weaponMask) {
  if (weaponMask.size() != pushedDepth.pixelCount())
    throw std::invalid_argument("countWeaponConflicts: the mask and the depth image differ in size");
  WeaponConflicts result;
  const glm::mat4 worldFromView = glm::inverse(cameraView(camera));
  for (std::uint32_t y = 0; y < pushedDepth.height; ++y)
    for (std::uint32_t x = 0; x < pushedDepth.width; ++x) {
      if (!weaponMask[std::size_t(y) * pushedDepth.width + x]) continue;
      const float depth = *pushedDepth.at(x, y);
      ++result.weaponPixels;
      // The world camera's ray through this pixel, at unit view depth.
      const float ndcX = (float(x) + 0.5f) / float(pushedDepth.width) * 2.0f - 1.0f;
      const float ndcY = (float(y) + 0.5f) / float(pushedDepth.height) * 2.0f - 1.0f;
      const glm::vec3 viewDirection((ndcX + projection[2][0]) / projection[0][0],
                                    (ndcY + projection[2][1]) / projection[1][1], -1.0f);
      const glm::vec3 direction = glm::mat3(worldFromView) * viewDirection;
      const float lengthPerDepth = glm::length(viewDirection);
      if (std::optional<float> hit = world.castRay(camera.position, direction, depth * lengthPerDepth))
        if (*hit / lengthPerDepth < depth) ++result.conflictPixels;
    }
  return result;
}

EyeViewComfort eyeViewComfort(const DepthImage& eyeDepth, double worldScale, double interocularMeters,
                              const DisplayProfile& display, std::vector<float>* conflictDiopters) {
  if (eyeDepth.pixelCount() == 0) throw std::invalid_argument("eye view comfort: the depth image is empty");
  if (!(worldScale > 0.0) || !std::isfinite(worldScale) || !(interocularMeters > 0.0) || !std::isfinite(interocularMeters))
    throw std::invalid_argument("eye view comfort: world scale and eye separation must be positive");
  validate(display);
  const double focalDiopters = 1.0 / double(display.viewingDistanceMeters);
  // Vergence angle (radians) of a point at `diopters` for eyes `interocularMeters` apart.
  auto vergence = [&](double diopters) { return 2.0 * std::atan(0.5 * interocularMeters * diopters); };
  const double focalVergence = vergence(focalDiopters);
  constexpr double kOneDegree = 3.14159265358979323846 / 180.0;
  if (conflictDiopters) conflictDiopters->assign(eyeDepth.pixelCount(), std::numeric_limits<float>::quiet_NaN());
  std::vector<double> conflicts;
  conflicts.reserve(eyeDepth.pixelCount());
  std::uint64_t beyondOneDegree = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < eyeDepth.pixelCount(); ++i) {
    const double depth = eyeDepth.pixels[i];
    if (!(depth > 0.0)) continue;  // unknown (NaN or <= 0)
    const double meters = depth / worldScale;
    const double diopters = std::isinf(meters) ? 0.0 : 1.0 / meters;
    const double conflict = std::abs(diopters - focalDiopters);
    conflicts.push_back(conflict);
    if (conflictDiopters) (*conflictDiopters)[i] = float(conflict);
    if (std::abs(vergence(diopters) - focalVergence) > kOneDegree) ++beyondOneDegree;
    nearest = std::min(nearest, meters);
  }
  EyeViewComfort comfort;
  comfort.pixelCount = conflicts.size();
  if (conflicts.empty()) return comfort;
  double sum = 0.0;
  for (double c : conflicts) sum += c;
  comfort.meanConflictDiopters = sum / double(conflicts.size());
  std::sort(conflicts.begin(), conflicts.end());
  comfort.p95ConflictDiopters = conflicts[std::min(conflicts.size() - 1, std::size_t(0.95 * double(conflicts.size())))];
  comfort.maxConflictDiopters = conflicts.back();
  comfort.shareBeyondOneDegree = double(beyondOneDegree) / double(conflicts.size());
  comfort.nearestMeters = nearest;
  return comfort;
}

}  // namespace s3d::comfort
