#pragma once
// Per-eye views as OpenXR reports them, read from and written to JSON; the views, the center view and the
// eye-to-center mapping are the stereo library's (s3d/stereo/eye_views.h, docs/DESIGN.md "View configurations").
#include <filesystem>

#include <nlohmann/json.hpp>

#include "s3d/stereo/eye_views.h"

namespace s3d::comfort {

using stereo::CenterView;
using stereo::centerPixelForEyePixel;
using stereo::centerViewFor;
using stereo::EyeView;
using stereo::frustumProjection;
using stereo::ViewConfiguration;

// { "worldScale": number > 0 (optional, 1), "views": { "left": EYE, "right": EYE } } with EYE =
// { "position": [x, 0, 0] (metres), "angleLeft", "angleRight", "angleUp", "angleDown" (radians, each in
// (-pi/2, pi/2), left < right, down < up), "width", "height" (1..16384) }; the left eye's x below the right's.
// Unknown keys, missing or bad fields: std::invalid_argument naming the field (e.g. "views.left.angleUp").
ViewConfiguration viewConfigurationFromJson(const nlohmann::json& document);
// The inverse (a document viewConfigurationFromJson reads back to the same views).
nlohmann::json toJson(const ViewConfiguration& views);
// The same, each message prefixed by "views file 'FILE': ".
ViewConfiguration loadViewConfiguration(const std::filesystem::path& file);

}  // namespace s3d::comfort
