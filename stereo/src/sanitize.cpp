#include "s3d/stereo/sanitize.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "s3d/stereo/stereo_shared.h"

namespace s3d::stereo {
namespace {

bool isInvalidDepth(float depth) { return !(depth > 0.0f); }  // NaN, -inf, zero and negative; +inf is sky

std::string shortNumber(float value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", double(value));
  return text;
}

}  // namespace

std::uint64_t sanitizeColor(ImageRGBA32F& color) {
  std::uint64_t replaced = 0;
  for (float& value : color.pixels)
    if (!std::isfinite(value)) {
      value = 0.0f;
      ++replaced;
    }
  return replaced;
}

std::uint64_t sanitizeDepth(DepthImage& linearDepth, float zeroParallaxDistance) {
  std::uint64_t replaced = 0;
  for (float& depth : linearDepth.pixels)
    if (isInvalidDepth(depth)) {
      depth = gpu::sanitizedDepth(depth, zeroParallaxDistance);
      ++replaced;
    }
  return replaced;
}

std::uint64_t countInvalidDepth(const DepthImage& linearDepth) {
  std::uint64_t invalid = 0;
  for (float depth : linearDepth.pixels) invalid += isInvalidDepth(depth) ? 1 : 0;
  return invalid;
}

ClampedZeroParallax clampZeroParallaxDistance(float zpp, float nearPlane, float farPlane) {
  if (!(nearPlane > 0.0f) || !(farPlane > nearPlane) || !std::isfinite(farPlane))
    throw std::invalid_argument("zero-parallax clamp needs 0 < near < far (got near " + std::to_string(nearPlane) +
                                ", far " + std::to_string(farPlane) + ")");
  if (!std::isfinite(zpp) || !(zpp > 0.0f))
    throw std::invalid_argument("zeroParallaxDistance must be positive (got " + std::to_string(zpp) + ")");
  const float lowest = kMinZppFractionOfNear * nearPlane;
  const float highest = kMaxZppFractionOfFar * farPlane;
  if (zpp < lowest)
    return {lowest, "zeroParallaxDistance " + shortNumber(zpp) + " is in front of the near plane " +
                        shortNumber(nearPlane) + " (nothing could come out of the screen): clamped to " +
                        shortNumber(lowest)};
  if (zpp > highest)
    return {highest, "zeroParallaxDistance " + shortNumber(zpp) + " is beyond half the far plane " +
                         shortNumber(farPlane) + " (at the far plane every surface would pop out, with the parallax "
                         "near the camera unbounded): clamped to " + shortNumber(highest)};
  return {zpp, std::nullopt};
}

}  // namespace s3d::stereo
