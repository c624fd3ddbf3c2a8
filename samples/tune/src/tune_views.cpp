#include "s3d/tune/tune_views.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "s3d/comfort/comfort_views.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::tune {
ImageRGBA8 composeView(ViewMode mode, const FrameImages& frame) {
  auto requireReference = [&]() -> const stereo::StereoPair& {
    if (!frame.reference)
      throw std::invalid_argument(std::string("the ") + viewModeName(mode) + " view needs the two-pass reference eyes");
    return *frame.reference;
  };
  const stereo::StereoPair& eyes = frame.eyesWithHud ? *frame.eyesWithHud : frame.eyes;  // as shown
  switch (mode) {
    case ViewMode::Anaglyph: return stereo::makeAnaglyphDubois(eyes.left, eyes.right);
    case ViewMode::SideBySide: return stereo::makeSideBySide(eyes.left, eyes.right, stereo::PackingMode::Half);
    case ViewMode::Left: return eyes.left;
    case ViewMode::Right: return eyes.right;
    case ViewMode::Reference: {
      const stereo::StereoPair& reference = requireReference();
      const stereo::StereoPair& shown = frame.referenceWithHud ? *frame.referenceWithHud : reference;
      return stereo::makeAnaglyphDubois(shown.left, shown.right);
    }
    case ViewMode::ErrorHeatMap: {  // as measured: without the HUD, border strips black
      const stereo::StereoPair& reference = requireReference();
      return stereo::makeSideBySide(stereo::makeErrorHeatMap(frame.eyes.left, reference.left, frame.cropColumns),
                                    stereo::makeErrorHeatMap(frame.eyes.right, reference.right, frame.cropColumns),
                                    stereo::PackingMode::Half);
    }
    case ViewMode::ParallaxHeatMap: return comfort::makeParallaxHeatMap(frame.stereoDepth, frame.parameters);
    case ViewMode::ComfortOverlay: {
      ImageRGBA8 image = stereo::makeAnaglyphDubois(eyes.left, eyes.right);
      comfort::markComfortViolations(image, frame.stereoDepth, frame.parameters, frame.display);
      return image;
    }
  }
  throw std::invalid_argument("unknown view mode");
}

}  // namespace s3d::tune
