#pragma once
// Per-eye views as OpenXR reports them (XrView: pose position in metres, XrFovf angles in radians;
// XrViewConfigurationView: image size), the center view that covers both eyes, and the mapping from an eye pixel
// to the center-view pixel it is synthesized from (docs/DESIGN.md "View configurations"). Eyes are parallel
// (identity orientation) and offset along x only. comfort/view_configuration.h reads them from JSON; the stereo
// frame (stereo_frame.h) takes them in place of maxSeparation and zeroParallaxDistance.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace s3d::stereo {

struct EyeView {
  double positionX = 0.0;  // metres, from the head's origin (XrPosef.position.x)
  double angleLeft = -0.5, angleRight = 0.5, angleUp = 0.4, angleDown = -0.4;  // radians (XrFovf)
  std::uint32_t width = 0, height = 0;  // pixels of this eye's image
};

struct ViewConfiguration {
  std::array<EyeView, 2> eyes;  // left, right
  double worldScale = 1.0;      // world units per metre
};

// A center view: parallel to the eyes at their midpoint, its frustum in tangent space, its size, and where each
// eye sits from it.
struct CenterView {
  double tanLeft = 0, tanRight = 0, tanUp = 0, tanDown = 0;
  std::uint32_t width = 0, height = 0;
  std::array<double, 2> eyeOffset{};  // world units along x from the center view, left and right
};

// The views job's center view: the union of the eyes' frusta widened by the largest eye offset over the nearest
// depth (guard band), sampled at the finest eye's pitch.
CenterView centerViewFor(const ViewConfiguration& views, double nearestDepth);

// The stereo frame's center view: the eyes' size, the mean of their frusta (tangents), no guard band. The host
// renders its center image with this frustum from the eyes' midpoint.
CenterView sharedCenterView(const ViewConfiguration& views);

// The center-view pixel (continuous, pixel centres at +0.5) that eye `eye`'s pixel position (u, v) shows
// when the surface there lies at view depth `depth`: t_c = t_eye + offset / depth (docs/DESIGN.md).
glm::dvec2 centerPixelForEyePixel(const ViewConfiguration& views, const CenterView& center, int eye, glm::dvec2 eyePixel,
                                  double depth);

// Vulkan projection (y down, depth 0..1) of an asymmetric frustum given by its tangents.
glm::dmat4 frustumProjection(double tanLeft, double tanRight, double tanUp, double tanDown, double nearPlane,
                             double farPlane);

// A rule eye views break for the stereo frame: the eye (0 left, 1 right; -1 for worldScale), the field, and why.
// Each API names the field in its own spelling.
enum class EyeViewField { PositionX, AngleLeft, AngleRight, AngleUp, AngleDown, Width, Height, WorldScale };
struct EyeViewsProblem {
  int eye = -1;
  EyeViewField field = EyeViewField::WorldScale;
  std::string problem;
};

// The stereo frame's kernels displace each eye by one mirrored parallax m (1 - zpd / d) along rows of an image of
// the center's size. That is exactly the views' mapping on sharedCenterView when both eyes have one vertical field
// and one horizontal extent (each within a quarter pixel over a width x height eye) and their frusta converge
// (the left eye's shifted right of the right eye's: a screen's off-axis pair), by at most a quarter of the width.
// Finite angles in (-pi/2, pi/2), left < right, down < up, the left eye's x below the right's, worldScale > 0,
// each eye width x height. Parallel or outward-turned frusta (a headset's) have no such m and are refused.
std::optional<EyeViewsProblem> eyeViewsProblem(const ViewConfiguration& views, std::uint32_t width,
                                                std::uint32_t height);
// "eyes[1].angleUp", "worldScale": the field as the C++ structs spell it.
std::string fieldName(const EyeViewsProblem& problem);

// The kernels' parameters for views without a problem: maxSeparation m = the left eye's frustum shift from the
// center's over the center's tangent width, zeroParallaxDistance = the left eye's offset over that shift (the depth
// whose parallax the shift cancels).
struct EyeViewsParallax {
  float maxSeparation = 0.0f;
  float zeroParallaxDistance = 0.0f;  // world units
};
EyeViewsParallax eyeViewsParallax(const ViewConfiguration& views);

}  // namespace s3d::stereo
