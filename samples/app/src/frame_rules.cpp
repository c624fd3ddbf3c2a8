#include "s3d/app/frame_rules.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

#include "s3d/comfort/comfort_report.h"
#include "s3d/hud/crosshair.h"
#include "s3d/hud/overlay.h"

namespace s3d::app {

stereo::StereoParameters pushWeaponUnlessNegativeParallaxAllowed(stereo::StereoParameters parameters,
                                                                 const std::optional<glm::vec2>& weaponDepths,
                                                                 bool allowNegativeParallax) {
  if (!allowNegativeParallax && weaponDepths)
    parameters = comfort::pushWeaponBehindScreen(parameters, weaponDepths->x, weaponDepths->y);
  return parameters;
}

bool holdZeroParallaxAtNearestDepth(stereo::StereoParameters& parameters, const DepthImage& stereoDepth,
                                    bool allowNegativeParallax) {
  if (allowNegativeParallax) return false;
  const std::optional<float> nearest = comfort::nearestDepth(stereoDepth);
  if (!nearest || !(*nearest < parameters.zeroParallaxDistance)) return false;
  parameters.zeroParallaxDistance = *nearest;
  return true;
}

HudFrame drawHud(const HudFrameInput& input, stereo::StereoPair& eyes, ImageRGBA8* center,
                 stereo::StereoPair* reference) {
  if (!input.stereoDepth || !input.firstPersonMask)
    throw std::invalid_argument("drawHud: the center view's depth and weapon mask are needed");
  const std::uint32_t width = eyes.left.width;
  const std::uint32_t height = eyes.left.height;
  const stereo::StereoParameters& parameters = input.parameters;
  // Not in front of the screen plane unless allowed (the plane is never beyond the aimed-at surface).
  auto notInFront = [&](float depth) {
    return input.allowNegativeParallax ? depth : std::max(depth, parameters.zeroParallaxDistance);
  };
  HudFrame hud;
  hud.crosshairDepth = notInFront(input.crosshairDepth);
  const hud::CrosshairStyle crosshairStyle = hud::crosshairStyleForHeight(height);

  struct HudElement {
    std::string name;
    float depth;
    std::function<ImageRGBA8(float offsetPx)> layer;  // the element alone, shifted by offsetPx
  };
  std::vector<HudElement> elements;
  for (const hud::Panel& panel : hud::defaultPanels(width, height))
    elements.push_back({panel.name, notInFront(panel.depth),
                        [&, panel](float offsetPx) { return hud::panelLayer(width, height, panel, offsetPx); }});
  // The crosshair last, on top. Its center in pixel indices ((W - 1) / 2, rounded half up) plus the offset.
  elements.push_back({"crosshair", hud.crosshairDepth, [&](float offsetPx) {
                        ImageRGBA8 layer(width, height);
                        hud::drawCrosshair(layer, 0.5f * float(width - 1) + offsetPx, 0.5f * float(height - 1),
                                           crosshairStyle);
                        return layer;
                      }});
  // The weapon's nearest pushed point: an element deeper than it lies behind the weapon where they overlap.
  const float weaponNearestPushed = input.weaponDepths
                                        ? parameters.weaponDepthOffset + parameters.weaponDepthScale * input.weaponDepths->x
                                        : std::numeric_limits<float>::infinity();
  for (const HudElement& element : elements) {
    HudElementReport entry{element.name, element.depth, element.depth > weaponNearestPushed};
    const ImageRGBA8 centerLayer = element.layer(0.0f);
    entry.conflictPixels =
        hud::countDepthConflicts(centerLayer, element.depth, *input.stereoDepth, *input.firstPersonMask, entry.behindWeapon);
    if (center) (void)hud::blendLayer(*center, centerLayer, entry.behindWeapon);
    for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      const std::size_t side = eye == stereo::Eye::Left ? 0 : 1;
      const ImageRGBA8 layer = element.layer(hud::crosshairEyeOffsetPx(parameters, element.depth, width, eye));
      const hud::BlendCounts counts = hud::blendLayer(side == 0 ? eyes.left : eyes.right, layer, entry.behindWeapon);
      entry.drawnPixels[side] = counts.drawnPixels;
      entry.fadedPixels[side] = counts.fadedPixels;
      if (reference) (void)hud::blendLayer(side == 0 ? reference->left : reference->right, layer, entry.behindWeapon);
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
