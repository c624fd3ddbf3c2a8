#include "s3d/hud/crosshair.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace s3d::hud {
namespace {

using Color = std::array<std::uint8_t, 4>;

// Pixel rectangle [x0, x1) x [y0, y1) in image coordinates; may lie partly or wholly outside the image.
struct Rect {
  long x0, y0, x1, y1;
  Rect grown(long by) const { return {x0 - by, y0 - by, x1 + by, y1 + by}; }
};

void fill(ImageRGBA8& image, Rect rect, const Color& color) {
  const long x0 = std::max(rect.x0, 0L), x1 = std::min(rect.x1, long(image.width));
  const long y0 = std::max(rect.y0, 0L), y1 = std::min(rect.y1, long(image.height));
  for (long y = y0; y < y1; ++y)
    for (long x = x0; x < x1; ++x) std::copy(color.begin(), color.end(), image.at(std::uint32_t(x), std::uint32_t(y)));
}

// Round half up, clamped far outside any image so the long arithmetic below cannot overflow.
long pixelIndex(float value) {
  constexpr float kFar = 1.0e7f;
  return long(std::floor(std::clamp(value, -kFar, kFar) + 0.5f));
}

}  // namespace

CrosshairStyle crosshairStyleForHeight(std::uint32_t height) {
  const float scale = float(height) / 720.0f;
  const CrosshairStyle base;
  CrosshairStyle style;
  style.armLengthPx = std::max(2, int(std::lround(float(base.armLengthPx) * scale)));
  style.thicknessPx = std::max(1, int(std::lround(float(base.thicknessPx) * scale)));
  style.gapPx = std::max(1, int(std::lround(float(base.gapPx) * scale)));
  return style;
}

void drawCrosshair(ImageRGBA8& image, float centerXPx, float centerYPx, const CrosshairStyle& style) {
  if (!std::isfinite(centerXPx) || !std::isfinite(centerYPx))
    throw std::invalid_argument("drawCrosshair: the position must be finite");
  if (style.armLengthPx < 1 || style.thicknessPx < 1 || style.gapPx < 0)
    throw std::invalid_argument("drawCrosshair: arm length and thickness must be >= 1 px, the gap >= 0 px");
  const long cx = pixelIndex(centerXPx), cy = pixelIndex(centerYPx);
  const long gap = style.gapPx, arm = style.armLengthPx;
  // Across an arm: thickness pixels around the center line (one more before it than after for even widths).
  const long across0 = -long(style.thicknessPx / 2), across1 = across0 + style.thicknessPx;
  const Rect arms[4] = {
      {cx - gap - arm, cy + across0, cx - gap, cy + across1},          // left
      {cx + gap + 1, cy + across0, cx + gap + 1 + arm, cy + across1},  // right
      {cx + across0, cy - gap - arm, cx + across1, cy - gap},          // up
      {cx + across0, cy + gap + 1, cx + across1, cy + gap + 1 + arm},  // down
  };
  for (const Rect& rect : arms) fill(image, rect.grown(1), style.outline);  // outlines first ...
  for (const Rect& rect : arms) fill(image, rect, style.color);             // ... so no arm's outline covers another arm
}

float crosshairEyeOffsetPx(const stereo::StereoParameters& parameters, float crosshairDepth, std::uint32_t width,
                           stereo::Eye eye) {
  if (!(crosshairDepth > 0.0f))
    throw std::invalid_argument("crosshairEyeOffsetPx: depth must be positive (got " + std::to_string(crosshairDepth) + ")");
  const float parallaxPx =
      gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, crosshairDepth) * float(width);
  return eye == stereo::Eye::Left ? -parallaxPx : parallaxPx;
}

}  // namespace s3d::hud
