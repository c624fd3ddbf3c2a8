#pragma once
// HUD overlay with stereo depth (seed 4.6.2): panels with text (stb_easy_font) and the crosshair, each drawn
// after stereo synthesis into each eye at the parallax of its assigned depth, and faded out where the
// weapon mask covers an element that lies behind the weapon (the seed's blend mode).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "s3d/hud/layer_blend.h"
#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::hud {

using Color = std::array<std::uint8_t, 4>;  // RGBA, straight alpha

// A static HUD panel: a filled rectangle with a 1 px border and a line of text, placed in the center view.
struct Panel {
  std::string name;                    // "health", "ammo"
  int x = 0, y = 0;                    // top-left corner in center-view pixels
  int width = 0, height = 0;
  float depth = 2.5f;                  // linear view depth it is shown at (world units)
  Color fill{20, 30, 40, 160};
  Color border{200, 220, 255, 255};
  std::string text;
  Color textColor{255, 255, 255, 255};
  int textScale = 1;                   // stb_easy_font's glyphs are about 7 px tall at scale 1
};

// Health bottom-left and ammo bottom-right, sized for the image height (the layout at 720 lines, scaled).
std::vector<Panel> defaultPanels(std::uint32_t width, std::uint32_t height, float depth = 2.5f);

// One HUD element's pixels in a transparent layer of the eye's size (alpha 0 where it draws nothing).
ImageRGBA8 panelLayer(std::uint32_t width, std::uint32_t height, const Panel& panel, float offsetPx);
// Text with stb_easy_font, top-left at (x, y), each font unit `scale` pixels; clipped to the image.
void drawText(ImageRGBA8& layer, int x, int y, const std::string& text, const Color& color, int scale);

// The weapon mask travels in the eyes' alpha channel (tonemap writes 0 on the first-person layer, 1 elsewhere;
// the stereo pass carries it into both eyes). Blends `layer` over `eye` (RGB only); when the element lies
// behind the weapon, its opacity is multiplied by the eye's alpha there, so it fades out where the weapon
// covers it (seed 4.6.2: "a blend mode is used that fades out, and hence occludes pixels that are covered by
// the weapon mask"). The eye's alpha is left as it is (the mask is still needed by later elements).
BlendCounts blendLayer(ImageRGBA8& eye, const ImageRGBA8& layer, bool behindWeapon);

// HUD pixels whose parallax puts them behind the scene surface they cover: layer pixels (at the center view,
// offset 0) with depth greater than the stereo pass's depth there, where the element is visible (weapon
// pixels hide an element behind the weapon, so they do not count then). Parallax grows with depth, so
// comparing depths compares parallaxes.
std::uint64_t countDepthConflicts(const ImageRGBA8& centerLayer, float elementDepth, const DepthImage& stereoDepth,
                                  const std::vector<std::uint8_t>& weaponMask, bool behindWeapon);

// Every eye pixel's alpha set to 255: the mask has served the HUD, the outputs are opaque.
void makeOpaque(ImageRGBA8& image);

}  // namespace s3d::hud
