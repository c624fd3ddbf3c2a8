#pragma once
// The JSON form of measured numbers and eye errors, shared by every report.json and bench.json so all tools
// report the same numbers the same way.
#include <optional>

#include <nlohmann/json.hpp>

#include "s3d/frame/hybrid_stereo.h"
#include "s3d/stereo/eye_comparison.h"
#include "s3d/stereo/metrics.h"

namespace s3d::app {

// Shortest decimal that round-trips the float (0.02f is reported as 0.02, not 0.019999999552965164).
double tidy(float value);
nlohmann::json finiteOrNull(double value);
nlohmann::json optionalMs(const std::optional<double>& value);  // null when absent or not finite
// {"displacement", "classification" (with "classify", "threshold", "mask"), "eyeGeometry" (with "baseDepth"),
// "frontSpan", "maskedShading", "eyeRenders", "composite", "total"}: ms or null; "concurrentEyes": whether the eyes
// rendered at once; "surfaces": "raycast" or "raster".
nlohmann::json toJson(const frame::HybridTimings& timings);
// {"psnrDb", "ssim", "meanAbsoluteError", "shareAbove8", "pixelCount"}: every ErrorStats field, non-finite as null.
nlohmann::json statsJson(const stereo::ErrorStats& stats);
// {"psnrDb", "ssim", "meanAbsoluteError", "pixelCount"}.
nlohmann::json statsJson(const stereo::HdrErrorStats& stats);
// The whole cropped area at the top level, the regions ("halo", "disocclusion", "transparent", "foliage", "rest") below
// it, and "hdr" (the same layout in linear HDR) when measured.
nlohmann::json errorJson(const stereo::EyeError& error);

}  // namespace s3d::app
