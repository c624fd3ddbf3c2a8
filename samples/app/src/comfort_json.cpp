#include "s3d/app/comfort_json.h"

#include "s3d/app/eye_comparison.h"

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

}  // namespace s3d::app
