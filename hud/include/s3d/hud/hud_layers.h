#pragma once
// HUD elements as layers (seed 4.6.2): each element is a small straight-alpha RGBA8 image placed in the center
// view, shown in each eye shifted by the parallax of its depth and blended over the eye after stereo synthesis.
// The C++ reference of the HUD pass (hud_pass.h): the GPU composites the same layers at the same origins with the
// same per-pixel math (hud_pass_shared.h), and s3d's own tools draw their HUD through these functions.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "s3d/hud/crosshair.h"
#include "s3d/hud/layer_blend.h"
#include "s3d/hud/overlay.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::hud {

// Where a layer sits: its pixel (pivotX, pivotY) lands on the eye pixel nearest (anchorX, anchorY) plus the eye's
// offset, rounded half up (floor(v + 0.5), as drawCrosshair and panelLayer round). Anchor in center-view pixel
// indices (pixel x covers [x - 0.5, x + 0.5]).
struct HudPlacement {
  float anchorX = 0.0f;
  float anchorY = 0.0f;
  int pivotX = 0;
  int pivotY = 0;
};

struct HudLayer {
  std::string name;
  ImageRGBA8 pixels;  // straight alpha; alpha 0 draws nothing
  HudPlacement placement;
};

// An element's state in one frame: frame_comfort_state.h's HudElementState gives parallaxPx and fadesBehindWeapon.
struct HudElementFrame {
  float parallaxPx = 0.0f;         // the right eye's offset in pixels; the left eye's is minus this
  bool fadesBehindWeapon = false;  // blend with the weapon mask (the eye's alpha) fading the element out
  bool hidden = false;             // not drawn this frame
};

// The top-left eye pixel of a layer shifted by offsetPx (the eye's signed parallax). Throws std::invalid_argument
// for a non-finite offset.
struct LayerOrigin {
  int x = 0;
  int y = 0;
};
LayerOrigin layerOrigin(const HudPlacement& placement, float offsetPx);
// The eye's offset for an element: -parallaxPx in the left eye, +parallaxPx in the right.
float eyeOffsetPx(float parallaxPx, stereo::Eye eye);

// The built-in elements, cropped to the pixels they draw (at least 1 x 1). A panel's anchor is its top-left
// corner; the crosshair's is the image center ((W - 1) / 2, (H - 1) / 2), as s3d render draws them.
HudLayer panelHudLayer(const Panel& panel);
HudLayer crosshairHudLayer(std::uint32_t width, std::uint32_t height, const CrosshairStyle& style);
// defaultPanels(width, height) then the crosshair (crosshairStyleForHeight), in drawing order (later on top).
std::vector<HudLayer> builtInHudLayers(std::uint32_t width, std::uint32_t height);

// The layer alone in a transparent eye-sized image, top-left at (x, y) (for countDepthConflicts).
ImageRGBA8 placedLayer(std::uint32_t width, std::uint32_t height, const ImageRGBA8& layer, int x, int y);

// Every visible element over one eye in order, each at its origin for the eye: what the HUD pass writes.
// Throws std::invalid_argument when the spans differ in length.
BlendCounts compositeHud(ImageRGBA8& eye, stereo::Eye side, std::span<const HudLayer> layers,
                         std::span<const HudElementFrame> frames);

}  // namespace s3d::hud
