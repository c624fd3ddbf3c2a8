#include "s3d/app/budget_frame.h"

#include "s3d/app/eye_comparison.h"

#include <limits>

namespace s3d::app {

BudgetFrame applyDisparityBudget(vk::Context& context, const stereo::DepthRangePass& pass,
                                 comfort::DisparityBudgetController* controller, const vk::Image& linearDepth,
                                 const BudgetFrameHints& hints, float seconds, stereo::StereoParameters& parameters) {
  BudgetFrame frame;
  if (!controller) return frame;
  frame.rule = comfort::DisparityBudgetRule::OneDegree;
  frame.budget = controller->budget();
  frame.imageWidth = linearDepth.width;
  const stereo::TimedDepthRange reduced = stereo::reduceDepthRangeTimed(context, pass, linearDepth);
  frame.depth = reduced.range;
  frame.reductionGpuMs = reduced.gpuMs;
  if (!frame.depth.hasFinite() && frame.depth.skyPixels == 0) return frame;  // nothing valid: keep the parameters
  comfort::BudgetFrameInput input;
  input.nearest = frame.depth.hasFinite() ? frame.depth.nearest : std::numeric_limits<float>::infinity();
  input.farthest = frame.depth.farthestShown();
  input.crosshairDepth = hints.crosshairDepth;
  input.weaponNearestPushed = hints.weaponNearestPushed;
  input.anticipatedNearest = hints.anticipatedNearest;
  input.histogram = &frame.depth.bins;
  input.cut = hints.cut;
  frame.choice = controller->update(input, seconds);
  parameters.maxSeparation = frame.choice.parameters.maxSeparation;
  parameters.zeroParallaxDistance = frame.choice.parameters.zeroParallaxDistance;
  return frame;
}

std::optional<float> weaponNearestPushed(const stereo::StereoParameters& parameters,
                                         const std::optional<glm::vec2>& weaponDepths) {
  if (!weaponDepths || !(weaponDepths->x > 0.0f)) return std::nullopt;
  return parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponDepths->x;
}

nlohmann::json budgetJson(const BudgetFrame& frame, const comfort::FrameComfort& comfort) {
  const std::uint32_t width = frame.imageWidth;
  const double shareOutside = comfort.parallax.shareBeyondOneDegree;
  if (frame.rule == comfort::DisparityBudgetRule::Off)
    return {{"rule", "off"}, {"shareOutside", finiteOrNull(shareOutside)}};
  auto parameters = [](const comfort::BudgetParameters& p) {
    return nlohmann::json{{"maxSeparation", finiteOrNull(tidy(p.maxSeparation))},
                          {"zeroParallaxDistance", finiteOrNull(tidy(p.zeroParallaxDistance))}};
  };
  const bool any = frame.depth.finitePixels() + frame.depth.skyPixels > 0;
  auto depthAt = [&](double share) { return any ? finiteOrNull(frame.depth.percentile(share)) : nlohmann::json(); };
  return {{"rule", comfort::disparityBudgetRuleName(frame.rule)},
          {"limitArcmin", frame.budget.limitArcmin},
          {"budgetPx", {{"crossed", tidy(float(frame.budget.crossedPx(width)))},
                        {"uncrossed", tidy(float(frame.budget.uncrossedPx(width)))}}},
          {"chosen", parameters(frame.choice.parameters)},
          {"target", parameters(frame.choice.target)},
          {"usedShare", finiteOrNull(frame.choice.usedShare)},
          {"shareOutside", finiteOrNull(shareOutside)},
          {"cut", frame.choice.cut},
          {"forced", frame.choice.forced},
          {"depth", {{"nearest", frame.depth.hasFinite() ? finiteOrNull(frame.depth.nearest) : nlohmann::json()},
                     {"farthest", finiteOrNull(frame.depth.farthestShown())},
                     {"p01", depthAt(0.01)}, {"p50", depthAt(0.5)}, {"p99", depthAt(0.99)}}},
          {"reductionGpuMs", optionalMs(frame.reductionGpuMs)}};
}

}  // namespace s3d::app
