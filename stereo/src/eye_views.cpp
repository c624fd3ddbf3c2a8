#include "s3d/stereo/eye_views.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "s3d/number_text.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {
namespace {

// What the kernels cannot place more precisely than: a quarter pixel of mismatch over an eye.
constexpr double kPixelTolerance = 0.25;

// Each eye's offset from the eyes' midpoint, in world units.
std::array<double, 2> eyeOffsets(const ViewConfiguration& views) {
  const double middle = 0.5 * (views.eyes[0].positionX + views.eyes[1].positionX);
  return {(views.eyes[0].positionX - middle) * views.worldScale, (views.eyes[1].positionX - middle) * views.worldScale};
}

struct Tangents {
  double left, right, up, down;
};
Tangents tangentsOf(const EyeView& eye) {
  return {std::tan(eye.angleLeft), std::tan(eye.angleRight), std::tan(eye.angleUp), std::tan(eye.angleDown)};
}

EyeViewsProblem problem(int eye, EyeViewField field, std::string why) { return {eye, field, std::move(why)}; }

// Finite, ordered angles within a half turn, the eye's size the frame's.
std::optional<EyeViewsProblem> eyeProblem(const EyeView& view, int eye, std::uint32_t width, std::uint32_t height) {
  if (!std::isfinite(view.positionX)) return problem(eye, EyeViewField::PositionX, "must be finite (metres)");
  const std::pair<double, EyeViewField> angles[] = {{view.angleLeft, EyeViewField::AngleLeft},
                                                     {view.angleRight, EyeViewField::AngleRight},
                                                     {view.angleUp, EyeViewField::AngleUp},
                                                     {view.angleDown, EyeViewField::AngleDown}};
  for (const auto& [angle, field] : angles)
    if (!(std::abs(angle) < std::numbers::pi / 2))
      return problem(eye, field, numberText(angle) + " must be in (-pi/2, pi/2) radians");
  if (!(view.angleRight > view.angleLeft))
    return problem(eye, EyeViewField::AngleRight,
                   numberText(view.angleRight) + " must be above the eye's left angle " + numberText(view.angleLeft));
  if (!(view.angleUp > view.angleDown))
    return problem(eye, EyeViewField::AngleUp,
                   numberText(view.angleUp) + " must be above the eye's down angle " + numberText(view.angleDown));
  if (view.width != width)
    return problem(eye, EyeViewField::Width, std::to_string(view.width) + " differs from the frame's width " +
                                                 std::to_string(width) + " (the eyes have the center image's size)");
  if (view.height != height)
    return problem(eye, EyeViewField::Height, std::to_string(view.height) + " differs from the frame's height " +
                                                  std::to_string(height) + " (the eyes have the center image's size)");
  return std::nullopt;
}

// Where the two eyes' frusta differ by more than the kernels' row displacement can reproduce.
std::optional<EyeViewsProblem> pairProblem(const ViewConfiguration& views, std::uint32_t width, std::uint32_t height) {
  const Tangents a = tangentsOf(views.eyes[0]), b = tangentsOf(views.eyes[1]);
  const double rows = 0.5 * ((a.up - a.down) + (b.up - b.down)) / double(height);  // tangent per pixel row
  const std::pair<double, EyeViewField> vertical[] = {{b.up - a.up, EyeViewField::AngleUp},
                                                       {b.down - a.down, EyeViewField::AngleDown}};
  for (const auto& [difference, field] : vertical)
    if (std::abs(difference) / rows > kPixelTolerance)
      return problem(1, field, "differs from the left eye's by " + numberText(std::abs(difference) / rows) +
                                   " pixel rows: the stereo frame displaces along rows, so both eyes need one "
                                   "vertical field (within a quarter pixel)");
  const double extentA = a.right - a.left, extentB = b.right - b.left;
  const double columns = 0.5 * (extentA + extentB) / double(width);  // tangent per pixel column
  if (std::abs(extentB - extentA) / columns > kPixelTolerance)
    return problem(1, EyeViewField::AngleRight,
                   "makes the right eye's field " + numberText(extentB) + " tangent units wide, the left eye's " +
                       numberText(extentA) + ": the stereo frame's eyes share one pixel pitch (equal within a "
                                             "quarter pixel over the width)");
  const EyeViewsParallax parallax = eyeViewsParallax(views);
  if (!(parallax.maxSeparation > 0.0f) || !std::isfinite(parallax.zeroParallaxDistance))
    return problem(0, EyeViewField::AngleLeft,
                   "puts the left eye's frustum at or left of the right eye's (centres " + numberText(0.5 * (a.left + a.right)) +
                       " and " + numberText(0.5 * (b.left + b.right)) +
                       " in tangent units): the stereo frame reproduces converging eyes only (a screen's off-axis "
                       "pair); parallel or outward-turned frusta, as a headset's, need a per-eye shift its kernels "
                       "do not have");
  if (parallax.maxSeparation > kMaxSeparationLimit)
    return problem(0, EyeViewField::AngleLeft, "shifts the left eye's frustum by " + numberText(parallax.maxSeparation) +
                                                   " of the width from the center's, above " +
                                                   numberText(kMaxSeparationLimit));
  return std::nullopt;
}

}  // namespace

CenterView centerViewFor(const ViewConfiguration& views, double nearestDepth) {
  if (!(nearestDepth > 0.0)) throw std::invalid_argument("center view: the nearest depth must be positive");
  CenterView center;
  center.eyeOffset = eyeOffsets(views);
  double pitchX = INFINITY, pitchY = INFINITY;
  center.tanLeft = center.tanDown = INFINITY;
  center.tanRight = center.tanUp = -INFINITY;
  for (const EyeView& eye : views.eyes) {
    const Tangents t = tangentsOf(eye);
    center.tanLeft = std::min(center.tanLeft, t.left);
    center.tanRight = std::max(center.tanRight, t.right);
    center.tanUp = std::max(center.tanUp, t.up);
    center.tanDown = std::min(center.tanDown, t.down);
    pitchX = std::min(pitchX, (t.right - t.left) / eye.width);
    pitchY = std::min(pitchY, (t.up - t.down) / eye.height);
  }
  // Guard band: an eye pixel at tangent t shows the center's t + offset / depth, |offset / depth| <= this.
  const double band = std::max(std::abs(center.eyeOffset[0]), std::abs(center.eyeOffset[1])) / nearestDepth;
  center.tanLeft -= band;
  center.tanRight += band;
  center.width = std::uint32_t(std::ceil((center.tanRight - center.tanLeft) / pitchX - 1e-9));
  center.height = std::uint32_t(std::ceil((center.tanUp - center.tanDown) / pitchY - 1e-9));
  // Widen the frustum to whole pixels at the pitch, about its middle, so the pitch is exact.
  const double extraX = center.width * pitchX - (center.tanRight - center.tanLeft);
  center.tanLeft -= extraX / 2, center.tanRight += extraX / 2;
  const double extraY = center.height * pitchY - (center.tanUp - center.tanDown);
  center.tanDown -= extraY / 2, center.tanUp += extraY / 2;
  return center;
}

CenterView sharedCenterView(const ViewConfiguration& views) {
  const Tangents a = tangentsOf(views.eyes[0]), b = tangentsOf(views.eyes[1]);
  CenterView center;
  center.tanLeft = 0.5 * (a.left + b.left);
  center.tanRight = 0.5 * (a.right + b.right);
  center.tanUp = 0.5 * (a.up + b.up);
  center.tanDown = 0.5 * (a.down + b.down);
  center.width = views.eyes[0].width;
  center.height = views.eyes[0].height;
  center.eyeOffset = eyeOffsets(views);
  return center;
}

glm::dvec2 centerPixelForEyePixel(const ViewConfiguration& views, const CenterView& center, int eye, glm::dvec2 eyePixel,
                                  double depth) {
  const EyeView& view = views.eyes[std::size_t(eye)];
  const Tangents t = tangentsOf(view);
  const double tanX = t.left + eyePixel.x / view.width * (t.right - t.left) + center.eyeOffset[std::size_t(eye)] / depth;
  const double tanY = t.up - eyePixel.y / view.height * (t.up - t.down);  // rows run down
  return {(tanX - center.tanLeft) / (center.tanRight - center.tanLeft) * center.width,
          (center.tanUp - tanY) / (center.tanUp - center.tanDown) * center.height};
}

glm::dmat4 frustumProjection(double tanLeft, double tanRight, double tanUp, double tanDown, double nearPlane,
                             double farPlane) {
  glm::dmat4 p(0.0);
  p[0][0] = 2.0 / (tanRight - tanLeft);
  p[2][0] = (tanRight + tanLeft) / (tanRight - tanLeft);  // x_ndc = P00 X / d - P20 with z = -d
  p[1][1] = -2.0 / (tanUp - tanDown);                     // Vulkan: y down
  p[2][1] = -(tanUp + tanDown) / (tanUp - tanDown);
  p[2][2] = farPlane / (nearPlane - farPlane);
  p[2][3] = -1.0;
  p[3][2] = -(farPlane * nearPlane) / (farPlane - nearPlane);
  return p;
}

std::optional<EyeViewsProblem> eyeViewsProblem(const ViewConfiguration& views, std::uint32_t width,
                                                std::uint32_t height) {
  if (!(std::isfinite(views.worldScale) && views.worldScale > 0.0))
    return problem(-1, EyeViewField::WorldScale, numberText(views.worldScale) + " must be finite and above 0 (world "
                                                                                "units per metre)");
  for (int eye = 0; eye < 2; ++eye)
    if (auto found = eyeProblem(views.eyes[std::size_t(eye)], eye, width, height)) return found;
  if (!(views.eyes[1].positionX > views.eyes[0].positionX))
    return problem(1, EyeViewField::PositionX, numberText(views.eyes[1].positionX) +
                                                   " must be right of the left eye's " +
                                                   numberText(views.eyes[0].positionX) + " (metres)");
  return pairProblem(views, width, height);
}

std::string fieldName(const EyeViewsProblem& problem) {
  static constexpr const char* kNames[] = {"positionX", "angleLeft", "angleRight", "angleUp",
                                           "angleDown", "width",     "height",     "worldScale"};
  const std::string member = kNames[int(problem.field)];
  return problem.eye < 0 ? member : "eyes[" + std::to_string(problem.eye) + "]." + member;
}

EyeViewsParallax eyeViewsParallax(const ViewConfiguration& views) {
  const CenterView center = sharedCenterView(views);
  const Tangents left = tangentsOf(views.eyes[0]);
  const double shift = 0.5 * (left.left + left.right) - 0.5 * (center.tanLeft + center.tanRight);
  const double maxSeparation = shift / (center.tanRight - center.tanLeft);
  const double zeroParallaxDistance = -center.eyeOffset[0] / shift;
  const bool fits = std::abs(zeroParallaxDistance) <= double(std::numeric_limits<float>::max());
  return {float(maxSeparation), fits ? float(zeroParallaxDistance) : INFINITY};
}

}  // namespace s3d::stereo
