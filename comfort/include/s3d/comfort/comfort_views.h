#pragma once
// Comfort as images, for a tool's or a host's debug view: the parallax each pixel gets and the pixels that break
// the comfort report's rules (comfort_report.h) marked over a view.
#include <array>
#include <cstdint>
#include <vector>

#include "s3d/comfort/display_profile.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

// Marked pixels exceed this angular disparity: the 1-degree rule of the comfort report (display_profile.h).
inline constexpr double kComfortLimitArcmin = 60.0;

// Per pixel the parallax the stereo pass gives it between the eyes, 2 p(depth) W: white on the screen plane,
// towards blue behind it and towards red in front of it, full colour at the parallax of infinity
// (2 maxSeparation W) either way; the sky is at infinity.
ImageRGBA8 makeParallaxHeatMap(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters);

// 1 where the pixel's angular disparity on the display exceeds limitArcmin (either direction).
std::vector<std::uint8_t> comfortViolationMask(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                                               const DisplayProfile& display,
                                               double limitArcmin = kComfortLimitArcmin);

// The comfort overlay's marks (the rules of `s3d render`'s comfort report), each mixing the anaglyph half-way
// to its colour; a pixel breaking both rules takes the first: a stereo window violation (frameComfort),
// beyond 1 degree of disparity (kComfortLimitArcmin).
inline constexpr std::array<int, 3> kWindowViolationColor{255, 0, 255};
inline constexpr std::array<int, 3> kBeyondLimitColor{255, 220, 0};

// Mixes each marked pixel of `image` (the view, e.g. the anaglyph; the depth's size) half-way to its mark's colour.
void markComfortViolations(ImageRGBA8& image, const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                           const DisplayProfile& display);

}  // namespace s3d::comfort
