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
  frame.spanFraction = frame.budget.uncrossedFraction +
                       (controller->allowsNegativeParallax() ? frame.budget.crossedFraction : 0.0);
  const stereo::TimedDepthRange reduced = stereo::reduceDepthRangeTimed(context, pass, linearDepth);
  frame.depth = reduced.range;
  frame.reductionGpuMs = reduced.gpuMs;
  comfort::BudgetFrameInput input;
  input.crosshairDepth = hints.crosshairDepth;
  input.weaponNearestPushed = hints.weaponNearestPushed;
  input.anticipatedNearest = hints.anticipatedNearest;
  input.cut = hints.cut;
  input.receding = hints.receding;
  // The library's per-frame call, as a host makes it (comfort::frameComfortState's budget).
  const std::optional<comfort::BudgetChoice> choice = controller->update(frame.depth, input, seconds);
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

nlohmann::json disparityMapJson(const DisparityMapReport& report) {
  nlohmann::json knots = nlohmann::json::array();
  for (int i = 0; i < report.map.knotCount; ++i) {
    auto depthOf = [](float inverse) { return inverse > 0.0f ? finiteOrNull(tidy(1.0f / inverse)) : nlohmann::json(); };
    knots.push_back({{"depth", depthOf(report.map.inverseDepth[i])}, {"mappedDepth", depthOf(report.map.mapped[i])}});
  }
  return {{"mapping", stereo::disparityMappingName(report.mapping)},
          {"knots", knots},
          {"gpuMs", optionalMs(report.gpuMs)},
          {"referenceLayers", report.referenceLayers},
          {"unresolvedPixels", {{"left", report.unresolvedPixels[0]}, {"right", report.unresolvedPixels[1]}}}};
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
          {"bulkShare", finiteOrNull((comfort.parallax.p95ParallaxPx - comfort.parallax.p05ParallaxPx) /
                                     (frame.spanFraction * double(width)))},
          {"cut", frame.choice.cut},
          {"forced", frame.choice.forced},
          {"depth", {{"nearest", frame.depth.hasFinite() ? finiteOrNull(frame.depth.nearest) : nlohmann::json()},
                     {"farthest", finiteOrNull(frame.depth.farthestShown())},
                     {"p01", depthAt(0.01)}, {"p50", depthAt(0.5)}, {"p99", depthAt(0.99)}}},
          {"reductionGpuMs", optionalMs(frame.reductionGpuMs)}};
}

}  // namespace s3d::app
