#pragma once
// The view modes of `s3d tune` as pure functions of one frame's images: no GPU, no window (unit-tested).
#include <cstdint>
#include <optional>
#include <vector>

#include "s3d/comfort/display_profile.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"
#include "s3d/tune/tune_settings.h"

namespace s3d::tune {

struct FrameImages {
  stereo::StereoPair eyes;                      // synthesized by the stereo pass, before the HUD (as measured)
  std::optional<stereo::StereoPair> reference;  // the two-pass reference eyes, before the HUD (when rendered)
  // The same with the HUD drawn (frame::drawHud), as `s3d render` writes them: the views show these where given;
  // the error heat map never does (as measured).
  std::optional<stereo::StereoPair> eyesWithHud, referenceWithHud;
  DepthImage stereoDepth;                       // the stereo pass's linear depth (weapon pushed)
  stereo::StereoParameters parameters;          // as used for this frame (zero-parallax control and rules applied)
  std::uint32_t cropColumns = 0;
  comfort::DisplayProfile display;
};

// The image the view area shows. Throws std::invalid_argument for a reference view without reference eyes.
ImageRGBA8 composeView(ViewMode mode, const FrameImages& frame);

}  // namespace s3d::tune
