#include "s3d/comfort/frame_comfort_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "s3d/number_text.h"

namespace s3d::comfort {

stereo::StereoParameters weaponPushForFrame(stereo::StereoParameters parameters, const WeaponMaskStats& weapon,
                                            bool allowNegativeParallax) {
  if (!allowNegativeParallax && weapon.pixels > 0)
    parameters = pushWeaponBehindScreen(parameters, weapon.nearestDepth, weapon.farthestDepth);
  return parameters;
}

bool holdZeroParallax(stereo::StereoParameters& parameters, std::optional<float> nearest, bool allowNegativeParallax) {
  if (allowNegativeParallax || !nearest || !(*nearest < parameters.zeroParallaxDistance)) return false;
  parameters.zeroParallaxDistance = *nearest;
  return true;
}

HudElementState hudElementState(const std::string& name, float depth, const stereo::StereoParameters& parameters,
                                const WeaponMaskStats& weapon, std::uint32_t width, bool allowNegativeParallax,
                                const gpu::DisparityMapConstants& disparityMap) {
  if (!(depth > 0.0f)) throw std::invalid_argument("HUD element '" + name + "': depth must be positive");
  HudElementState state{name, allowNegativeParallax ? depth : std::max(depth, parameters.zeroParallaxDistance)};
  state.parallaxPx = gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance,
                                            gpu::mappedDepth(disparityMap, state.depth)) *
                     float(width);
  const float weaponNearestPushed = weapon.pixels > 0
                                        ? parameters.weaponDepthOffset + parameters.weaponDepthScale * weapon.nearestDepth
                                        : std::numeric_limits<float>::infinity();
  state.fadesBehindWeapon = state.depth > weaponNearestPushed;
  return state;
}

FrameComfortState frameComfortState(const FrameComfortInput& input) {
  if (input.width == 0) throw std::invalid_argument("frameComfortState: the eyes' width is 0");
  FrameComfortState state;
  state.parameters = weaponPushForFrame(input.parameters, input.weapon, input.allowNegativeParallax);
  state.weaponPushed = state.parameters.weaponDepthOffset != input.parameters.weaponDepthOffset ||
                       state.parameters.weaponDepthScale != input.parameters.weaponDepthScale;
  std::optional<float> nearest = input.stereoDepth ? nearestDepth(*input.stereoDepth) : input.nearestWorldDepth;
  if (!input.stereoDepth && input.weapon.pixels > 0) {  // the weapon as the stereo pass will see it
    const float pushed = state.parameters.weaponDepthOffset + state.parameters.weaponDepthScale * input.weapon.nearestDepth;
    nearest = nearest ? std::min(*nearest, pushed) : pushed;
  }
  state.zeroParallaxLimited = holdZeroParallax(state.parameters, nearest, input.allowNegativeParallax);

  const CrosshairPlacement placement =
      placeCrosshairAlongAim(input.rayCast, input.camera, input.crosshairDistance, input.crosshairMargin);
  if (input.budget) {
    const FrameBudget& budget = *input.budget;
    if (!budget.controller || !budget.depth)
      throw std::invalid_argument("frameComfortState: the disparity budget needs its controller and the depth range");
    if (budget.controller->allowsNegativeParallax() != input.allowNegativeParallax)
      throw std::invalid_argument(
          "frameComfortState: the disparity budget controller and the frame disagree on negative parallax");
    BudgetFrameInput hints;
    hints.crosshairDepth = placement.depth;
    if (input.weapon.pixels > 0)
      hints.weaponNearestPushed =
          state.parameters.weaponDepthOffset + state.parameters.weaponDepthScale * input.weapon.nearestDepth;
    hints.anticipatedNearest = budget.anticipatedNearest;
    hints.receding = budget.receding;
    hints.cut = budget.cut;
    state.budget = budget.controller->update(*budget.depth, hints, budget.seconds);
    if (state.budget) {  // the weapon push stays valid: the controller keeps Z at or before the pushed weapon
      state.parameters.maxSeparation = state.budget->parameters.maxSeparation;
      state.parameters.zeroParallaxDistance = state.budget->parameters.zeroParallaxDistance;
    }
  }
  state.crosshair = hudElementState("crosshair", placement.depth, state.parameters, input.weapon, input.width,
                                    input.allowNegativeParallax, input.disparityMap);
  state.crosshairDepth = state.crosshair.depth;
  state.crosshairHitWorld = placement.hitWorld;
  for (const HudElementDepth& element : input.hud)
    state.hud.push_back(hudElementState(element.name, element.depth, state.parameters, input.weapon, input.width,
                                        input.allowNegativeParallax, input.disparityMap));
  if (input.stereoDepth && input.display)
    state.statistics = frameComfort(*input.stereoDepth, state.parameters, *input.display);
  return state;
}

}  // namespace s3d::comfort
