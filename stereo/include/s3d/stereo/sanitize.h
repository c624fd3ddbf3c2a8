#pragma once
// Counted clean-up of the stereo pass's inputs (NaN or Inf in color or depth is sanitized and counted,
// never propagated), and the zero-parallax distance kept inside the camera's depth range.
#include <cstdint>
#include <optional>
#include <string>

#include "s3d/image.h"

namespace s3d::stereo {

// Color channels that are NaN or +-inf become 0 (black, or transparent for alpha). Returns how many values
// were replaced.
std::uint64_t sanitizeColor(ImageRGBA32F& color);

// Depth that carries no information (NaN, -inf, zero, negative) becomes the zero-parallax distance, exactly
// what the stereo shaders read it as (gpu::sanitizedDepth), so CPU-side masks and statistics agree with the
// pass. +inf is the sky and stays. Returns how many pixels were replaced.
std::uint64_t sanitizeDepth(DepthImage& linearDepth, float zeroParallaxDistance);

// How many pixels sanitizeDepth would replace, without changing them.
std::uint64_t countInvalidDepth(const DepthImage& linearDepth);

// Input files' unknown depth (NaN, -inf, zero, negative; +inf is the sky and known) takes the farther of the
// nearest known depths left and right on its row: a hole is the background's, never the zero-parallax plane's
// nor the foreground's. A row without known depth takes the image's farthest known depth (the sky when none).
// Returns how many pixels were filled.
std::uint64_t fillUnknownDepthFromBackground(DepthImage& linearDepth);

// The zero-parallax plane must lie inside the camera's depth range [nearPlane, farPlane] with room behind it:
// at or beyond the far plane every surface pops out of the screen and the parallax near the camera grows as
// zpp / depth without bound; in front of the near plane (near zero) no surface can come out of the screen and
// the depth contrast collapses as zpp -> 0. Below kMinZppFractionOfNear * nearPlane it is clamped up to the
// near plane, above kMaxZppFractionOfFar * farPlane it is clamped down to that bound.
inline constexpr float kMinZppFractionOfNear = 1.0f;
inline constexpr float kMaxZppFractionOfFar = 0.5f;
struct ClampedZeroParallax {
  float zeroParallaxDistance;          // the value to use
  std::optional<std::string> warning;  // set when it was clamped: names the requested value, the bound and why
};
// Throws std::invalid_argument unless 0 < nearPlane < farPlane (finite) and zeroParallaxDistance is finite
// and positive (stereo::validate's rule).
ClampedZeroParallax clampZeroParallaxDistance(float zeroParallaxDistance, float nearPlane, float farPlane);

}  // namespace s3d::stereo
