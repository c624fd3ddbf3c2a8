#include "s3d/frame/frame_hud.h"

#include <stdexcept>
#include <utility>

#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/hud/crosshair.h"
#include "s3d/hud/hud_layers.h"
#include "s3d/hud/overlay.h"

namespace s3d::frame {
namespace {

// The HUD's layers and their states by the comfort rules: the panels, then the crosshair on top.
struct HudLayers {
  comfort::HudElementState crosshair;
  std::vector<comfort::HudElementState> states;
  std::vector<hud::HudLayer> layers;
};

HudLayers hudLayers(const HudFrameInput& input, std::uint32_t width, std::uint32_t height) {
  // Depth (not in front of the screen plane unless allowed) and fade behind the weapon: the library's rule.
  const comfort::WeaponMaskStats weapon = comfort::weaponMaskStats(input.weaponDepths);
  auto state = [&](const std::string& name, float depth) {
    return comfort::hudElementState(name, depth, input.parameters, weapon, width, input.allowNegativeParallax,
                                    input.disparityMap);
  };
  HudLayers hud{state("crosshair", input.crosshairDepth), {}, {}};
  if (!input.draw) return hud;
  for (const hud::Panel& panel : hud::defaultPanels(width, height)) {
    hud.states.push_back(state(panel.name, panel.depth));
    hud.layers.push_back(hud::panelHudLayer(panel));
  }
  hud.states.push_back(hud.crosshair);
  hud.layers.push_back(hud::crosshairHudLayer(width, height, hud::crosshairStyleForHeight(height)));
  return hud;
}

// The weapon mask (the images' alpha) has served the HUD: every image it was drawn into is made opaque.
void makeOpaque(ImageRGBA8* center, stereo::StereoPair* eyes) {
  for (ImageRGBA8* image : {center, eyes ? &eyes->left : nullptr, eyes ? &eyes->right : nullptr})
    if (image) hud::makeOpaque(*image);
}

hud::LayerOrigin eyeOrigin(const hud::HudLayer& layer, const comfort::HudElementState& state, stereo::Eye eye) {
  return hud::layerOrigin(layer.placement, hud::eyeOffsetPx(state.parallaxPx, eye));
}

}  // namespace

HudFrame drawHud(const HudFrameInput& input, stereo::StereoPair& eyes) {
  if (!input.stereoDepth || !input.firstPersonMask)
    throw std::invalid_argument("the HUD needs the center view's depth and weapon mask");
  const std::uint32_t width = eyes.left.width;
  const std::uint32_t height = eyes.left.height;
  const HudLayers layers = hudLayers(input, width, height);
  HudFrame hud;
  hud.crosshairDepth = layers.crosshair.depth;
  for (std::size_t i = 0; i < layers.layers.size(); ++i) {
    const hud::HudLayer& layer = layers.layers[i];
    const comfort::HudElementState& state = layers.states[i];
    HudElementReport entry{state.name, state.depth, state.fadesBehindWeapon};
    const hud::LayerOrigin still = hud::layerOrigin(layer.placement, 0.0f);
    const ImageRGBA8 centerLayer = hud::placedLayer(width, height, layer.pixels, still.x, still.y);
    entry.conflictPixels =
        hud::countDepthConflicts(centerLayer, entry.depth, *input.stereoDepth, *input.firstPersonMask, entry.behindWeapon);
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      const std::size_t side = eye == stereo::Eye::Left ? 0 : 1;
      const hud::LayerOrigin origin = eyeOrigin(layer, state, eye);
      const hud::BlendCounts counts = hud::compositeLayer(side == 0 ? eyes.left : eyes.right, layer.pixels, origin.x,
                                                          origin.y, entry.behindWeapon);
      entry.drawnPixels[side] = counts.drawnPixels;
      entry.fadedPixels[side] = counts.fadedPixels;
    }
    hud.conflictPixels += entry.conflictPixels;
    hud.elements.push_back(std::move(entry));
  }
  makeOpaque(nullptr, &eyes);
  return hud;
}

void drawHudOver(const HudFrameInput& input, ImageRGBA8* center, stereo::StereoPair* eyes) {
  const ImageRGBA8* sized = center ? center : eyes ? &eyes->left : nullptr;
  if (!sized) return;
  const HudLayers layers = hudLayers(input, sized->width, sized->height);
  for (std::size_t i = 0; i < layers.layers.size(); ++i) {
    const hud::HudLayer& layer = layers.layers[i];
    const comfort::HudElementState& state = layers.states[i];
    if (center) {
      const hud::LayerOrigin still = hud::layerOrigin(layer.placement, 0.0f);
      (void)hud::blendLayer(*center, hud::placedLayer(center->width, center->height, layer.pixels, still.x, still.y),
                            state.fadesBehindWeapon);
    }
    for (const stereo::Eye eye : eyes ? std::vector{stereo::Eye::Left, stereo::Eye::Right} : std::vector<stereo::Eye>{}) {
      const hud::LayerOrigin origin = eyeOrigin(layer, state, eye);
      (void)hud::compositeLayer(eye == stereo::Eye::Left ? eyes->left : eyes->right, layer.pixels, origin.x, origin.y,
                                state.fadesBehindWeapon);
    }
  }
  makeOpaque(center, eyes);
}

}  // namespace s3d::frame
