#include "scene_description.h"

#include <algorithm>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "s3d/json_document.h"

namespace s3d::renderer {
namespace fs = std::filesystem;

namespace {

class DescriptionReader {
 public:
  explicit DescriptionReader(fs::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("scene description '" + file_.string() + "': " + what);
  }

  void onlyKeys(const nlohmann::json& object, const std::string& where, std::initializer_list<const char*> keys) const {
    if (!object.is_object()) fail(where + " must be an object");
    for (const auto& item : object.items())
      if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return item.key() == k; })) {
        std::string choices;
        for (const char* k : keys) choices += (choices.empty() ? "" : ", ") + std::string(k);
        fail("unknown key '" + item.key() + "' in " + where + " (choices: " + choices + ")");
      }
  }

  float number(const nlohmann::json& value, const std::string& where, float lo, float hi) const {
    if (!value.is_number()) fail(where + " must be a number");
    const double v = value.get<double>();
    if (!(v >= lo && v <= hi)) fail(where + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return float(v);
  }

  glm::vec3 vec3(const nlohmann::json& value, const std::string& where, float lo = -1e7f, float hi = 1e7f) const {
    if (!value.is_array() || value.size() != 3) fail(where + " must be an array of 3 numbers");
    return {number(value[0], where, lo, hi), number(value[1], where, lo, hi), number(value[2], where, lo, hi)};
  }

  Camera camera(const nlohmann::json& object, const std::string& where, Camera camera) const {
    onlyKeys(object, where, {"position", "yawDegrees", "pitchDegrees", "verticalFovDegrees", "near", "far"});
    if (object.contains("position")) camera.position = vec3(object["position"], where + ".position");
    if (object.contains("yawDegrees")) camera.yawRadians = glm::radians(number(object["yawDegrees"], where + ".yawDegrees", -720, 720));
    if (object.contains("pitchDegrees"))
      camera.pitchRadians = glm::radians(number(object["pitchDegrees"], where + ".pitchDegrees", -89.9f, 89.9f));
    if (object.contains("verticalFovDegrees"))
      camera.verticalFovRadians = glm::radians(number(object["verticalFovDegrees"], where + ".verticalFovDegrees", 1, 179));
    if (object.contains("near")) camera.nearPlane = number(object["near"], where + ".near", 1e-5f, 1e6f);
    if (object.contains("far")) camera.farPlane = number(object["far"], where + ".far", 1e-4f, 1e9f);
    if (!(camera.farPlane > camera.nearPlane)) fail(where + ": far must be greater than near");
    if (const std::string problem = depthRangeProblem(camera.nearPlane, camera.farPlane); !problem.empty())
      fail(where + ": " + problem);
    return camera;
  }

  DescribedParts apply(Scene& scene) const {
    nlohmann::json doc = readJsonDocument(file_, "scene description");
    onlyKeys(doc, "the document",
             {"sun", "ambient", "pointLights", "sky", "camera", "cameraPath", "exposure", "ambientOcclusion",
              "ambientOcclusionRadius", "crosshairDistance"});
    if (doc.contains("sun")) {
      onlyKeys(doc["sun"], "sun", {"directionToSun", "color", "castsShadows", "shadowDistance"});
      if (doc["sun"].contains("directionToSun")) {
        const glm::vec3 d = vec3(doc["sun"]["directionToSun"], "sun.directionToSun");
        if (glm::length(d) < 1e-6f) fail("sun.directionToSun must not be zero");
        scene.sun.directionToSun = glm::normalize(d);
      }
      if (doc["sun"].contains("color")) scene.sun.color = vec3(doc["sun"]["color"], "sun.color", 0.0f, 1e6f);
      if (doc["sun"].contains("castsShadows")) {  // glTF has no shadow flag: a file's sun is unshadowed
        if (!doc["sun"]["castsShadows"].is_boolean()) fail("sun.castsShadows must be true or false");
        scene.sun.castsShadows = doc["sun"]["castsShadows"].get<bool>();
      }
      if (doc["sun"].contains("shadowDistance"))
        scene.sun.shadowDistance = number(doc["sun"]["shadowDistance"], "sun.shadowDistance", 1e-3f, 1e7f);
    }
    if (doc.contains("ambient")) scene.ambientColor = vec3(doc["ambient"], "ambient", 0.0f, 1e6f);
    if (doc.contains("pointLights")) {  // replaces the file's point lights
      if (!doc["pointLights"].is_array()) fail("pointLights must be an array");
      scene.pointLights.clear();
      for (std::size_t i = 0; i < doc["pointLights"].size(); ++i) {
        const std::string where = "pointLights[" + std::to_string(i) + "]";
        const nlohmann::json& light = doc["pointLights"][i];
        onlyKeys(light, where, {"position", "color", "radius"});
        PointLight point;
        if (light.contains("position")) point.position = vec3(light["position"], where + ".position");
        if (light.contains("color")) point.color = vec3(light["color"], where + ".color", 0.0f, 1e6f);
        if (light.contains("radius")) point.radius = number(light["radius"], where + ".radius", 1e-4f, 1e6f);
        scene.pointLights.push_back(point);
      }
    }
    if (doc.contains("sky")) {
      onlyKeys(doc["sky"], "sky", {"zenith", "horizon", "ground"});
      if (doc["sky"].contains("zenith")) scene.sky.zenithColor = vec3(doc["sky"]["zenith"], "sky.zenith", 0.0f, 1e6f);
      if (doc["sky"].contains("horizon")) scene.sky.horizonColor = vec3(doc["sky"]["horizon"], "sky.horizon", 0.0f, 1e6f);
      if (doc["sky"].contains("ground")) scene.sky.groundColor = vec3(doc["sky"]["ground"], "sky.ground", 0.0f, 1e6f);
    }
    if (doc.contains("camera")) scene.camera = camera(doc["camera"], "camera", scene.camera);
    if (doc.contains("cameraPath")) {  // each entry starts from the camera and changes what it names
      if (!doc["cameraPath"].is_array() || doc["cameraPath"].empty()) fail("cameraPath must be a non-empty array");
      scene.cameraPath.clear();
      for (std::size_t i = 0; i < doc["cameraPath"].size(); ++i)
        scene.cameraPath.push_back(camera(doc["cameraPath"][i], "cameraPath[" + std::to_string(i) + "]", scene.camera));
      scene.camera = scene.cameraPath.front();
    }
    if (doc.contains("exposure")) scene.exposure = number(doc["exposure"], "exposure", 1e-6f, 1e6f);
    if (doc.contains("ambientOcclusion")) {
      if (!doc["ambientOcclusion"].is_boolean()) fail("ambientOcclusion must be true or false");
      scene.ambientOcclusion = doc["ambientOcclusion"].get<bool>();
    }
    if (doc.contains("ambientOcclusionRadius"))
      scene.ambientOcclusionRadius = number(doc["ambientOcclusionRadius"], "ambientOcclusionRadius", 1e-4f, 1e3f);
    if (doc.contains("crosshairDistance"))
      scene.crosshairDistance = number(doc["crosshairDistance"], "crosshairDistance", 1e-3f, 1e7f);
    return {doc.contains("camera") || doc.contains("cameraPath"), doc.contains("sun")};
  }

 private:
  fs::path file_;
};

}  // namespace

DescribedParts applySceneDescription(const fs::path& file, Scene& scene) { return DescriptionReader(file).apply(scene); }

}  // namespace s3d::renderer
