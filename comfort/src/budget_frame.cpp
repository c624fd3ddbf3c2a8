#include "s3d/comfort/budget_frame.h"

#include "s3d/comfort/comfort_report.h"

namespace s3d::comfort {

BudgetFrame applyDisparityBudget(vk::Context& context, const stereo::DepthRangePass& pass,
                                 DisparityBudgetController* controller, const vk::Image& linearDepth,
                                 const BudgetFrameHints& hints, float seconds, stereo::StereoParameters& parameters) {
  BudgetFrame frame;
  if (!controller) return frame;
  frame.rule = DisparityBudgetRule::OneDegree;
  frame.budget = controller->budget();
  frame.imageWidth = linearDepth.width;
  frame.spanFraction = frame.budget.uncrossedFraction +
                       (controller->allowsNegativeParallax() ? frame.budget.crossedFraction : 0.0);
  const stereo::TimedDepthRange reduced = stereo::reduceDepthRangeTimed(context, pass, linearDepth);
  frame.depth = reduced.range;
  frame.reductionGpuMs = reduced.gpuMs;
  BudgetFrameInput input;
  input.crosshairDepth = hints.crosshairDepth;
  input.weaponNearestPushed = hints.weaponNearestPushed;
  input.anticipatedNearest = hints.anticipatedNearest;
  input.cut = hints.cut;
  input.receding = hints.receding;
  // The library's per-frame call, as a host makes it (frameComfortState's budget).
  const std::optional<BudgetChoice> choice = controller->update(frame.depth, input, seconds);
  if (!choice) return frame;  // nothing valid: keep the parameters
  frame.choice = *choice;
  parameters.maxSeparation = frame.choice.parameters.maxSeparation;
  parameters.zeroParallaxDistance = frame.choice.parameters.zeroParallaxDistance;
  return frame;
}

DisparityMapReport FrameDisparityMapper::apply(vk::Context& context, const vk::Image& linearDepth,
                                               const stereo::StereoParameters& parameters) const {
  DisparityMapReport report;
  report.mapping = parameters.disparityMapping;
  if (parameters.disparityMapping == stereo::DisparityMapping::Linear) return report;
  const stereo::DepthRange range = stereo::reduceDepthRangeTimed(context, reduction_, linearDepth).range;
  report.map = stereo::nonlinearDisparityMap(range, parameters.zeroParallaxDistance);
  report.gpuMs = stereo::mapDepthTimed(context, pass_, linearDepth, report.map);
  report.referenceLayers = std::uint32_t(stereo::disparityMapSegments(report.map).size());
  return report;
}

std::optional<float> weaponNearestPushed(const stereo::StereoParameters& parameters,
                                         const std::optional<glm::vec2>& weaponDepths) {
  if (!weaponDepths || !(weaponDepths->x > 0.0f)) return std::nullopt;
  return parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponDepths->x;
}

WeaponMaskStats weaponMaskStats(const std::optional<glm::vec2>& weaponDepths) {
  if (!weaponDepths) return {};
  return {1, weaponDepths->x, weaponDepths->y};
}

stereo::StereoParameters pushWeaponUnlessNegativeParallaxAllowed(stereo::StereoParameters parameters,
                                                                 const std::optional<glm::vec2>& weaponDepths,
                                                                 bool allowNegativeParallax) {
  return weaponPushForFrame(parameters, weaponMaskStats(weaponDepths), allowNegativeParallax);
}

bool holdZeroParallaxAtNearestDepth(stereo::StereoParameters& parameters, const DepthImage& stereoDepth,
                                    bool allowNegativeParallax) {
  return holdZeroParallax(parameters, nearestDepth(stereoDepth), allowNegativeParallax);
}

}  // namespace s3d::comfort
