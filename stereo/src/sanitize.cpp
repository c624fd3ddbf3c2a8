#include "s3d/stereo/sanitize.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "s3d/number_text.h"
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

std::uint64_t fillUnknownDepthFromBackground(DepthImage& linearDepth) {
  float farthestKnown = -S3D_INFINITY;
  for (float depth : linearDepth.pixels)
    if (!isInvalidDepth(depth) && depth > farthestKnown) farthestKnown = depth;
  if (farthestKnown == -S3D_INFINITY) farthestKnown = S3D_INFINITY;
  std::uint64_t filled = 0;
  const std::size_t width = linearDepth.width;
  for (std::size_t row = 0; row < linearDepth.height; ++row) {
    float* depth = linearDepth.pixels.data() + row * width;
    std::size_t x = 0;
    while (x < width) {
      if (!isInvalidDepth(depth[x])) {
        ++x;
        continue;
      }
      std::size_t end = x;
      while (end < width && isInvalidDepth(depth[end])) ++end;
      // Known neighbours of the run [x, end); a missing side does not vote.
      const float before = x > 0 ? depth[x - 1] : -S3D_INFINITY;
      const float after = end < width ? depth[end] : -S3D_INFINITY;
      float fill = before > after ? before : after;
      if (fill == -S3D_INFINITY) fill = farthestKnown;
      for (std::size_t i = x; i < end; ++i) depth[i] = fill;
      filled += end - x;
      x = end;
    }
  }
  return filled;
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
    throw std::invalid_argument("zero-parallax clamp needs 0 < near < far (got near " + numberText(nearPlane) +
                                ", far " + numberText(farPlane) + ")");
  if (!std::isfinite(zpp) || !(zpp > 0.0f))
    throw std::invalid_argument("zeroParallaxDistance must be positive (got " + numberText(zpp) + ")");
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
