#pragma once
// Per-eye views as OpenXR reports them (XrView: pose position in metres, XrFovf angles in radians;
// XrViewConfigurationView: image size), the center view that covers both eyes plus a guard band, and the
// mapping from an eye pixel to the center-view pixel it is synthesized from (docs/DESIGN.md "View
// configurations"). Eyes are parallel (identity orientation) and offset along x only.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace s3d::comfort {

struct EyeView {
  double positionX = 0.0;  // metres, from the head's origin (XrPosef.position.x)
  double angleLeft = -0.5, angleRight = 0.5, angleUp = 0.4, angleDown = -0.4;  // radians (XrFovf)
  std::uint32_t width = 0, height = 0;  // pixels of this eye's image
};

struct ViewConfiguration {
  std::array<EyeView, 2> eyes;  // left, right
  double worldScale = 1.0;      // world units per metre
};

// { "worldScale": number > 0 (optional, 1), "views": { "left": EYE, "right": EYE } } with EYE =
// { "position": [x, 0, 0] (metres), "angleLeft", "angleRight", "angleUp", "angleDown" (radians, each in
// (-pi/2, pi/2), left < right, down < up), "width", "height" (1..16384) }; the left eye's x below the right's.
// Unknown keys, missing or bad fields: std::invalid_argument naming the field (e.g. "views.left.angleUp").
ViewConfiguration viewConfigurationFromJson(const nlohmann::json& document);
// The inverse (a document viewConfigurationFromJson reads back to the same views).
nlohmann::json toJson(const ViewConfiguration& views);
// The same, each message prefixed by "views file 'FILE': ".
ViewConfiguration loadViewConfiguration(const std::filesystem::path& file);

// The center view: at the midpoint of the eyes, parallel to them, its frustum in tangent space covering the
// union of the eyes' frusta widened by the largest eye offset over the nearest depth (guard band), sampled at
// the finest eye's pitch.
struct CenterView {
  double tanLeft = 0, tanRight = 0, tanUp = 0, tanDown = 0;
  std::uint32_t width = 0, height = 0;
  std::array<double, 2> eyeOffset{};  // world units along x from the center view, left and right
};
CenterView centerViewFor(const ViewConfiguration& views, double nearestDepth);

// The center-view pixel (continuous, pixel centres at +0.5) that eye `eye`'s pixel position (u, v) shows
// when the surface there lies at view depth `depth`: t_c = t_eye + offset / depth (docs/DESIGN.md).
glm::dvec2 centerPixelForEyePixel(const ViewConfiguration& views, const CenterView& center, int eye, glm::dvec2 eyePixel,
                                  double depth);

// Vulkan projection (y down, depth 0..1) of an asymmetric frustum given by its tangents.
glm::dmat4 frustumProjection(double tanLeft, double tanRight, double tanUp, double tanDown, double nearPlane,
                             double farPlane);

}  // namespace s3d::comfort
