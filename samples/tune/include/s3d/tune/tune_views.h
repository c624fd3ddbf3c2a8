#pragma once
// The view modes of `s3d tune` as pure functions of one frame's images: no GPU, no window (unit-tested).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "s3d/comfort/display_profile.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"
#include "s3d/tune/tune_settings.h"

namespace s3d::tune {

// Marked pixels exceed this angular disparity: the 1-degree rule of the comfort report (display_profile.h).
inline constexpr double kComfortLimitArcmin = 60.0;

struct FrameImages {
  stereo::StereoPair eyes;                      // synthesized by the stereo pass, before the HUD (as measured)
  std::optional<stereo::StereoPair> reference;  // the two-pass reference eyes, before the HUD (when rendered)
  // The same with the HUD drawn (app::drawHud), as `s3d render` writes them: the views show these where given;
  // the error heat map never does (as measured).
  std::optional<stereo::StereoPair> eyesWithHud, referenceWithHud;
  DepthImage stereoDepth;                       // the stereo pass's linear depth (weapon pushed)
  stereo::StereoParameters parameters;          // as used for this frame (zero-parallax control and rules applied)
  std::uint32_t cropColumns = 0;
  comfort::DisplayProfile display;
};

// Per pixel the parallax the stereo pass gives it between the eyes, 2 p(depth) W: white on the screen plane,
// towards blue behind it and towards red in front of it, full colour at the parallax of infinity
// (2 maxSeparation W) either way; the sky is at infinity.
ImageRGBA8 makeParallaxHeatMap(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters);

// 1 where the pixel's angular disparity on the display exceeds limitArcmin (either direction).
std::vector<std::uint8_t> comfortViolationMask(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                                               const comfort::DisplayProfile& display,
                                               double limitArcmin = kComfortLimitArcmin);

// The comfort overlay's marks (the rules of `s3d render`'s comfort report), each mixing the anaglyph half-way
// to its colour; a pixel breaking both rules takes the first: a stereo window violation (comfort::frameComfort),
// beyond 1 degree of disparity (kComfortLimitArcmin).
inline constexpr std::array<int, 3> kWindowViolationColor{255, 0, 255};
inline constexpr std::array<int, 3> kBeyondLimitColor{255, 220, 0};

// The image the view area shows. Throws std::invalid_argument for a reference view without reference eyes.
ImageRGBA8 composeView(ViewMode mode, const FrameImages& frame);

}  // namespace s3d::tune
