#include "s3d/hud/crosshair.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace s3d::hud {
namespace {

void fillRect(ImageRGBA8& image, int x0, int y0, int x1, int y1, const std::array<std::uint8_t, 4>& color) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, int(image.width));
  y1 = std::min(y1, int(image.height));
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) std::copy(color.begin(), color.end(), image.at(std::uint32_t(x), std::uint32_t(y)));
}

}  // namespace

CrosshairStyle crosshairStyleForHeight(std::uint32_t height) {
  CrosshairStyle style;
  float scale = float(height) / 720.0f;
  style.armLengthPx = std::max(2, int(std::lround(10.0f * scale)));
  style.thicknessPx = std::max(1, int(std::lround(2.0f * scale)));
  style.gapPx = std::max(1, int(std::lround(3.0f * scale)));
  return style;
}

void drawCrosshair(ImageRGBA8& image, float centerXPx, float centerYPx, const CrosshairStyle& style) {
  if (!std::isfinite(centerXPx) || !std::isfinite(centerYPx)) throw std::invalid_argument("drawCrosshair: non-finite position");
  const int cx = int(std::lround(centerXPx)), cy = int(std::lround(centerYPx));
  const int half = style.thicknessPx / 2, thickness = style.thicknessPx;
  const int inner = style.gapPx, outer = style.gapPx + style.armLengthPx;
  // Arms as rectangles [x0, x1) x [y0, y1): left, right, up, down.
  const int arms[4][4] = {{cx - outer, cy - half, cx - inner, cy - half + thickness},
                          {cx + inner + 1, cy - half, cx + outer + 1, cy - half + thickness},
                          {cx - half, cy - outer, cx - half + thickness, cy - inner},
                          {cx - half, cy + inner + 1, cx - half + thickness, cy + outer + 1}};
  for (const auto& arm : arms) fillRect(image, arm[0] - 1, arm[1] - 1, arm[2] + 1, arm[3] + 1, style.outline);
  for (const auto& arm : arms) fillRect(image, arm[0], arm[1], arm[2], arm[3], style.color);
}

float hudEyeOffsetPx(const stereo::StereoParameters& parameters, float depth, std::uint32_t width, stereo::Eye eye) {
  float parallaxPx = gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, depth) * float(width);
  return eye == stereo::Eye::Left ? -parallaxPx : parallaxPx;
}

}  // namespace s3d::hud
