#pragma once
// The comfort report's JSON, shared by `s3d render` (report.json "comfort") and `s3d render --sequence`
// (per frame).
#include <nlohmann/json.hpp>

#include "s3d/comfort/comfort_report.h"

namespace s3d::app {

// {"parallaxPx": {"min", "max"}, "parallaxPercent": {...}, "disparityArcmin": {...}, "shareBeyondOneDegree",
//  "shareInFrontOfScreen", "windowViolations": {"pixels", "columns"}}
nlohmann::json comfortJson(const comfort::FrameComfort& comfort);

// {"name", "screenWidthMeters", "viewingDistanceMeters", "interocularMeters", "fieldOfViewDegrees" (HMD only)}
nlohmann::json displayJson(const comfort::DisplayProfile& display);

}  // namespace s3d::app
