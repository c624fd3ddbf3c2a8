#include "s3d/comfort/view_configuration.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "s3d/json_document.h"

namespace s3d::comfort {
namespace {

constexpr std::uint32_t kMaxEyeSize = 16384;

[[noreturn]] void fail(const std::string& field, const std::string& problem) {
  throw std::invalid_argument(field + " " + problem);
}

void requireOnlyKeys(const nlohmann::json& object, const std::string& where, std::initializer_list<const char*> keys) {
  if (!object.is_object()) fail(where, "must be an object");
  for (auto it = object.begin(); it != object.end(); ++it)
    if (std::find_if(keys.begin(), keys.end(), [&](const char* k) { return it.key() == k; }) == keys.end())
      fail(where + "." + it.key(), "is not a known field");
}

const nlohmann::json& required(const nlohmann::json& object, const std::string& where, const char* key) {
  if (!object.contains(key)) fail(where + "." + key, "is missing");
  return object.at(key);
}

double finiteNumber(const nlohmann::json& value, const std::string& field) {
  if (!value.is_number()) fail(field, "must be a number");
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail(field, "must be finite");
  return number;
}

EyeView eyeFromJson(const nlohmann::json& object, const std::string& where) {
  requireOnlyKeys(object, where, {"position", "angleLeft", "angleRight", "angleUp", "angleDown", "width", "height"});
  EyeView eye;
  const nlohmann::json& position = required(object, where, "position");
  if (!position.is_array() || position.size() != 3) fail(where + ".position", "must be [x, y, z] in metres");
  eye.positionX = finiteNumber(position[0], where + ".position[0]");
  for (int i : {1, 2})
    if (finiteNumber(position[i], where + ".position[" + std::to_string(i) + "]") != 0.0)
      fail(where + ".position[" + std::to_string(i) + "]", "must be 0 (eyes offset along x only)");
  auto angle = [&](const char* key) {
    const double value = finiteNumber(required(object, where, key), where + "." + key);
    if (!(std::abs(value) < std::numbers::pi / 2)) fail(where + "." + key, "must be in (-pi/2, pi/2) radians");
    return value;
  };
  eye.angleLeft = angle("angleLeft");
  eye.angleRight = angle("angleRight");
  eye.angleUp = angle("angleUp");
  eye.angleDown = angle("angleDown");
  if (!(eye.angleLeft < eye.angleRight)) fail(where + ".angleRight", "must be greater than angleLeft");
  if (!(eye.angleDown < eye.angleUp)) fail(where + ".angleUp", "must be greater than angleDown");
  auto size = [&](const char* key) {
    const nlohmann::json& value = required(object, where, key);
    if (!value.is_number_integer() || value.get<std::int64_t>() < 1 || value.get<std::int64_t>() > kMaxEyeSize)
      fail(where + "." + key, "must be an integer in [1, " + std::to_string(kMaxEyeSize) + "]");
    return std::uint32_t(value.get<std::int64_t>());
  };
  eye.width = size("width");
  eye.height = size("height");
  return eye;
}

}  // namespace

ViewConfiguration viewConfigurationFromJson(const nlohmann::json& document) {
  requireOnlyKeys(document, "the document", {"worldScale", "views"});
  ViewConfiguration views;
  if (document.contains("worldScale")) {
    views.worldScale = finiteNumber(document.at("worldScale"), "worldScale");
    if (!(views.worldScale > 0.0)) fail("worldScale", "must be positive");
  }
  const nlohmann::json& eyes = required(document, "the document", "views");
  requireOnlyKeys(eyes, "views", {"left", "right"});
  views.eyes[0] = eyeFromJson(required(eyes, "views", "left"), "views.left");
  views.eyes[1] = eyeFromJson(required(eyes, "views", "right"), "views.right");
  if (!(views.eyes[0].positionX < views.eyes[1].positionX))
    fail("views.right.position[0]", "must be greater than the left eye's (the right eye is to the right)");
  return views;
}

nlohmann::json toJson(const ViewConfiguration& views) {
  auto eye = [](const EyeView& e) {
    return nlohmann::json{{"position", {e.positionX, 0.0, 0.0}}, {"angleLeft", e.angleLeft}, {"angleRight", e.angleRight},
                          {"angleUp", e.angleUp},   {"angleDown", e.angleDown},         {"width", e.width},
                          {"height", e.height}};
  };
  return {{"worldScale", views.worldScale}, {"views", {{"left", eye(views.eyes[0])}, {"right", eye(views.eyes[1])}}}};
}

ViewConfiguration loadViewConfiguration(const std::filesystem::path& file) {
  nlohmann::json document;
  try {
    document = readJsonDocument(file, "views file");
  } catch (const InputFileError& error) {
    throw std::invalid_argument(error.what());
  }
  try {
    return viewConfigurationFromJson(document);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument("views file '" + file.string() + "': " + error.what());
  }
}

CenterView centerViewFor(const ViewConfiguration& views, double nearestDepth) {
  if (!(nearestDepth > 0.0)) throw std::invalid_argument("center view: the nearest depth must be positive");
  CenterView center;
  const double middle = 0.5 * (views.eyes[0].positionX + views.eyes[1].positionX);
  double pitchX = INFINITY, pitchY = INFINITY, largestOffset = 0.0;
  center.tanLeft = center.tanDown = INFINITY;
  center.tanRight = center.tanUp = -INFINITY;
  for (int i = 0; i < 2; ++i) {
    const EyeView& eye = views.eyes[i];
    center.eyeOffset[i] = (eye.positionX - middle) * views.worldScale;
    largestOffset = std::max(largestOffset, std::abs(center.eyeOffset[i]));
    const double l = std::tan(eye.angleLeft), r = std::tan(eye.angleRight);
    const double u = std::tan(eye.angleUp), d = std::tan(eye.angleDown);
    center.tanLeft = std::min(center.tanLeft, l);
    center.tanRight = std::max(center.tanRight, r);
    center.tanUp = std::max(center.tanUp, u);
    center.tanDown = std::min(center.tanDown, d);
    pitchX = std::min(pitchX, (r - l) / eye.width);
    pitchY = std::min(pitchY, (u - d) / eye.height);
  }
  // Guard band: an eye pixel at tangent t shows the center's t + offset / depth, |offset / depth| <= this.
  const double band = largestOffset / nearestDepth;
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

glm::dvec2 centerPixelForEyePixel(const ViewConfiguration& views, const CenterView& center, int eye, glm::dvec2 eyePixel,
                                  double depth) {
  const EyeView& view = views.eyes[std::size_t(eye)];
  const double l = std::tan(view.angleLeft), r = std::tan(view.angleRight);
  const double u = std::tan(view.angleUp), d = std::tan(view.angleDown);
  const double tanX = l + eyePixel.x / view.width * (r - l) + center.eyeOffset[std::size_t(eye)] / depth;
  const double tanY = u - eyePixel.y / view.height * (u - d);  // rows run down
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

}  // namespace s3d::comfort
