#pragma once
// One straight-alpha layer over one eye with the HUD pass's per-pixel math (hud_pass_shared.h): the bottom of the
// HUD library, under the overlay's panels (overlay.h) and the layers (hud_layers.h).
#include <cstdint>

#include "s3d/image.h"

namespace s3d::hud {

struct BlendCounts {
  std::uint64_t drawnPixels = 0;  // layer pixels with any opacity that landed in the eye
  std::uint64_t fadedPixels = 0;  // of those, pixels whose opacity the weapon mask reduced
};

// `layer` over `eye` with its top-left pixel at (x, y), clipped to the eye: blendLayer's math (hud_pass_shared.h)
// on the covered pixels; the eye's alpha (the weapon mask) is left as it is.
BlendCounts compositeLayer(ImageRGBA8& eye, const ImageRGBA8& layer, int x, int y, bool behindWeapon);

}  // namespace s3d::hud
