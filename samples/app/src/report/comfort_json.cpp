#include "s3d/app/comfort_json.h"

#include "s3d/app/report_json.h"

namespace s3d::app {

nlohmann::json comfortJson(const comfort::FrameComfort& comfort) {
  const comfort::ParallaxStatistics& p = comfort.parallax;
  return {{"parallaxPx", {{"min", finiteOrNull(p.minParallaxPx)}, {"max", finiteOrNull(p.maxParallaxPx)}}},
          {"parallaxPercent", {{"min", finiteOrNull(p.minParallaxPercent)}, {"max", finiteOrNull(p.maxParallaxPercent)}}},
          {"disparityArcmin", {{"min", finiteOrNull(p.minDisparityArcmin)}, {"max", finiteOrNull(p.maxDisparityArcmin)}}},
          {"shareBeyondOneDegree", finiteOrNull(p.shareBeyondOneDegree)},
          {"shareInFrontOfScreen", finiteOrNull(p.shareNegative)},
          {"windowViolations", {{"pixels", comfort.windowViolationPixels}, {"columns", comfort.windowViolationColumns}}}};
}

nlohmann::json displayJson(const comfort::DisplayProfile& display) {
  nlohmann::json json{{"name", display.name},
                      {"screenWidthMeters", tidy(display.screenWidthMeters)},
                      {"viewingDistanceMeters", tidy(display.viewingDistanceMeters)},
                      {"interocularMeters", tidy(display.interocularMeters)}};
  if (display.fieldOfViewDegrees > 0.0f) json["fieldOfViewDegrees"] = tidy(display.fieldOfViewDegrees);
  return json;
}

nlohmann::json disparityMapJson(const comfort::DisparityMapReport& report) {
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

nlohmann::json budgetJson(const comfort::BudgetFrame& frame, const comfort::FrameComfort& comfort) {
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
