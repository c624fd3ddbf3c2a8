#include "s3d/app/frame_rules.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/hud/crosshair.h"
#include "s3d/hud/hud_layers.h"
#include "s3d/hud/overlay.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::app {
HudMode parseHudMode(const std::string& name) {
  if (name == "auto") return HudMode::Auto;
  if (name == "game") return HudMode::Game;
  if (name == "none") return HudMode::None;
  throw std::invalid_argument("unknown HUD '" + name + "' (choices: auto, game, none)");
}

const char* hudModeName(HudMode mode) {
  switch (mode) {
    case HudMode::Auto: return "auto";
    case HudMode::Game: return "game";
    case HudMode::None: return "none";
  }
  return "auto";
}

HudMode resolveHudMode(HudMode mode, const std::string& scene) {
  if (mode != HudMode::Auto) return mode;
  return renderer::isSceneFile(scene) ? HudMode::None : HudMode::Game;
}

void requirePackableEyes(std::uint32_t width, std::uint32_t height, bool writesSideBySide, stereo::PackingMode sideBySide,
                         bool writesTopBottom, stereo::PackingMode topBottom, bool outputsSelectable) {
  auto require = [&](bool squeezed, std::uint32_t size, const char* option, const char* across, const char* units,
                     const char* file) {
    if (!squeezed || size >= 2) return;
    throw std::invalid_argument(std::string(option) + " half squeezes each eye to half its " + across +
                                ", which needs at least 2 " + units + " (the " + across + " is " + std::to_string(size) +
                                "): use " + option + " full" +
                                (outputsSelectable ? std::string(" or leave ") + file + " out of --outputs" : ""));
  };
  require(writesSideBySide && sideBySide == stereo::PackingMode::Half, width, "--sbs", "width", "columns", "sbs.png");
  require(writesTopBottom && topBottom == stereo::PackingMode::Half, height, "--tab", "height", "rows", "tab.png");
}

HudFrame drawHud(const HudFrameInput& input, stereo::StereoPair& eyes, ImageRGBA8* center,
                 stereo::StereoPair* reference) {
  if (!input.stereoDepth || !input.firstPersonMask)
    throw std::invalid_argument("drawHud: the center view's depth and weapon mask are needed");
  const std::uint32_t width = eyes.left.width;
  const std::uint32_t height = eyes.left.height;
  const stereo::StereoParameters& parameters = input.parameters;
  // Depth (not in front of the screen plane unless allowed) and fade behind the weapon: the library's rule.
  const comfort::WeaponMaskStats weapon = comfort::weaponMaskStats(input.weaponDepths);
  auto state = [&](const std::string& name, float depth) {
    return comfort::hudElementState(name, depth, parameters, weapon, width, input.allowNegativeParallax,
                                    input.disparityMap);
  };
  HudFrame hud;
  const comfort::HudElementState crosshair = state("crosshair", input.crosshairDepth);
  hud.crosshairDepth = crosshair.depth;
  if (!input.draw) {
    for (ImageRGBA8* image : {center, &eyes.left, &eyes.right, reference ? &reference->left : nullptr,
                              reference ? &reference->right : nullptr})
      if (image) hud::makeOpaque(*image);
    return hud;
  }
  // The library's layers (what hud::HudPass composites on the GPU): the panels, then the crosshair on top.
  std::vector<comfort::HudElementState> states;
  std::vector<hud::HudLayer> layers;
  for (const hud::Panel& panel : hud::defaultPanels(width, height)) {
    states.push_back(state(panel.name, panel.depth));
    layers.push_back(hud::panelHudLayer(panel));
  }
  states.push_back(crosshair);
  layers.push_back(hud::crosshairHudLayer(width, height, hud::crosshairStyleForHeight(height)));
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const hud::HudLayer& layer = layers[i];
    HudElementReport entry{states[i].name, states[i].depth, states[i].fadesBehindWeapon};
    const hud::LayerOrigin still = hud::layerOrigin(layer.placement, 0.0f);
    const ImageRGBA8 centerLayer = hud::placedLayer(width, height, layer.pixels, still.x, still.y);
    entry.conflictPixels =
        hud::countDepthConflicts(centerLayer, entry.depth, *input.stereoDepth, *input.firstPersonMask, entry.behindWeapon);
    if (center) (void)hud::blendLayer(*center, centerLayer, entry.behindWeapon);
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      const std::size_t side = eye == stereo::Eye::Left ? 0 : 1;
      const hud::LayerOrigin origin = hud::layerOrigin(layer.placement, hud::eyeOffsetPx(states[i].parallaxPx, eye));
      const hud::BlendCounts counts = hud::compositeLayer(side == 0 ? eyes.left : eyes.right, layer.pixels, origin.x,
                                                          origin.y, entry.behindWeapon);
      entry.drawnPixels[side] = counts.drawnPixels;
      entry.fadedPixels[side] = counts.fadedPixels;
      if (reference)
        (void)hud::compositeLayer(side == 0 ? reference->left : reference->right, layer.pixels, origin.x, origin.y,
                                  entry.behindWeapon);
    }
    hud.conflictPixels += entry.conflictPixels;
    hud.elements.push_back(std::move(entry));
  }
  // The weapon mask has served the HUD: every image it was drawn into is opaque.
  for (ImageRGBA8* image : {center, &eyes.left, &eyes.right, reference ? &reference->left : nullptr,
                            reference ? &reference->right : nullptr})
    if (image) hud::makeOpaque(*image);
  return hud;
}

}  // namespace s3d::app
