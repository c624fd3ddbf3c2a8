#pragma once
// The comfort report's JSON and the frame rules' (budget, disparity mapping), shared by `s3d render`
// (report.json), `s3d render --sequence` (per frame), `s3d convert` and `s3d tune`.
#include <nlohmann/json.hpp>

#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/comfort_report.h"

namespace s3d::app {

// {"parallaxPx": {"min", "max"}, "parallaxPercent": {...}, "disparityArcmin": {...}, "shareBeyondOneDegree",
//  "shareInFrontOfScreen", "windowViolations": {"pixels", "columns"}}
nlohmann::json comfortJson(const comfort::FrameComfort& comfort);

// {"name", "screenWidthMeters", "viewingDistanceMeters", "interocularMeters", "fieldOfViewDegrees" (HMD only)}
nlohmann::json displayJson(const comfort::DisplayProfile& display);

// report.json "disparityMapping": {"mapping", "knots": [{"depth", "mappedDepth"}] (depths as linear depth,
// +inf as null), "gpuMs", "referenceLayers", "unresolvedPixels": {"left", "right"}}.
nlohmann::json disparityMapJson(const comfort::DisparityMapReport& report);

// report.json "disparityBudget": {"rule", "limitArcmin", "budgetPx": {"crossed", "uncrossed"}, "chosen":
// {"maxSeparation", "zeroParallaxDistance"}, "target": {...}, "usedShare", "shareOutside" (pixels beyond the
// rule, from the comfort report), "bulkShare" (the span of the 5th to 95th percentile of the parallax of the
// pixels with finite depth over the budget's usable span, from the comfort report: the depth impression the
// bulk of the scene keeps),
// "cut", "forced", "depth": {"nearest", "farthest", "p01", "p50", "p99"},
// "reductionGpuMs"}; just {"rule": "off", "shareOutside"} when off.
nlohmann::json budgetJson(const comfort::BudgetFrame& frame, const comfort::FrameComfort& comfort);

}  // namespace s3d::app
