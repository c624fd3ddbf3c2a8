#pragma once
// HUD with stereo depth: elements are drawn after stereo synthesis into each eye, displaced by the
// parallax of their assigned depth (the seed's section 4.6.2).
#include <array>
#include <cstdint>

#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::hud {

struct CrosshairStyle {
  int armLengthPx = 10;
  int thicknessPx = 2;
  int gapPx = 3;
  std::array<std::uint8_t, 4> color{60, 255, 90, 255};
  std::array<std::uint8_t, 4> outline{0, 0, 0, 255};
};

// Arms scale with the image height (10 px arms at 720 lines), never below 2 px.
CrosshairStyle crosshairStyleForHeight(std::uint32_t height);

// Four arms around (centerX, centerY) with a 1 px outline, clipped to the image. The center is rounded to
// the nearest pixel: the HUD is drawn pixel-aligned, and both eyes round the same way.
void drawCrosshair(ImageRGBA8& image, float centerXPx, float centerYPx, const CrosshairStyle& style);

// Horizontal offset of a HUD element at linear depth `depth` in one eye, in pixels. The stereo pass shows
// a point of parallax p at x - p*W in the left eye (left(x) = center(x + p)) and at x + p*W in the right
// eye, and the off-axis reference agrees; the HUD uses the same placement.
float hudEyeOffsetPx(const stereo::StereoParameters& parameters, float depth, std::uint32_t width, stereo::Eye eye);

}  // namespace s3d::hud
