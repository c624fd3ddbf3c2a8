#pragma once
// HUD with stereo depth (the seed's section 4.6.2): HUD elements are drawn after stereo synthesis into each
// eye, displaced by the parallax of the depth they are given, so they sit at that depth in 3D.
#include <array>
#include <cstdint>

#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::hud {

struct CrosshairStyle {
  int armLengthPx = 10;  // length of each of the four arms
  int thicknessPx = 2;   // width of an arm across its length
  int gapPx = 3;         // clear pixels between the center pixel and each arm
  std::array<std::uint8_t, 4> color{40, 255, 80, 255};
  std::array<std::uint8_t, 4> outline{0, 0, 0, 255};  // 1 px around every arm, so it reads on any background
};

// The default style at 720 lines, scaled with the image height (rounded, never below 2 px arms, 1 px
// thickness and 1 px gap).
CrosshairStyle crosshairStyleForHeight(std::uint32_t height);

// Four arms around the pixel nearest (centerXPx, centerYPx) with a 1 px outline, clipped to the image (any
// position, even far outside, is safe). Coordinates are pixel indices (pixel x covers [x - 0.5, x + 0.5]);
// they are rounded half up (floor(v + 0.5)), so both eyes round alike. The center pixel stays clear.
void drawCrosshair(ImageRGBA8& image, float centerXPx, float centerYPx, const CrosshairStyle& style);

// Horizontal displacement, in pixels, of a HUD element at linear view depth `depth` in one eye of a
// `width`-pixel image. With p = gpu::parallaxFromDepth(maxSeparation, zeroParallaxDistance, depth):
//   left eye  -p * width,   right eye  +p * width.
// Why: the stereo pass writes left(x) = center(x + p W), so a center-view point at xc shows in the left eye
// at x = xc - p W, and right(x) = center(x - p W) puts it at xc + p W. The off-axis reference agrees
// (x_ndc(left) = x_ndc(center) - 2 p). Behind the zero-parallax plane (p > 0) the eyes' images move apart
// (uncrossed), in front (p < 0) they cross. Throws std::invalid_argument for a depth that is not positive.
float crosshairEyeOffsetPx(const stereo::StereoParameters& parameters, float crosshairDepth, std::uint32_t width,
                           stereo::Eye eye);

}  // namespace s3d::hud
