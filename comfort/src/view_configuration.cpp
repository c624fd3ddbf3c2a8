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

}  // namespace s3d::comfort
