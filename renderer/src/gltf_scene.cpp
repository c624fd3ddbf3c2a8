// glTF 2.0 scenes (scene_file.h): the node tree, meshes, materials, cameras and lights of a parsed model become a
// Scene. tinygltf comes from Debian's libtinygltf-dev, which ships the implementation compiled as libtinygltf.so
// (with stb_image for PNG/JPEG and nlohmann json): this file only includes the declarations, so no
// TINYGLTF_IMPLEMENTATION here (README.Debian of the package).
#include "s3d/renderer/scene_file.h"
#include "s3d/renderer/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "gltf_animation.h"
#include "gltf_draco.h"
#include "gltf_files.h"
#include "gltf_material_extras.h"
#include "gltf_meshopt.h"
#include "gltf_parse.h"
#include "gltf_reader.h"
#include "gltf_webp.h"
#include "mesh_generation.h"
#include "s3d/input_file.h"
#include "scene_description.h"

namespace s3d::renderer {
namespace fs = std::filesystem;
using namespace gltf;

namespace {

// In double precision: the file's values as they are, composed down the hierarchy before one conversion to float.
glm::dmat4 nodeTransform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::dmat4 m;
    std::memcpy(glm::value_ptr(m), node.matrix.data(), sizeof(double) * 16);  // both column-major
    return m;
  }
  glm::dvec3 t(0.0), s(1.0);
  glm::dquat r(1.0, 0.0, 0.0, 0.0);
  if (node.translation.size() == 3) t = {node.translation[0], node.translation[1], node.translation[2]};
  if (node.scale.size() == 3) s = {node.scale[0], node.scale[1], node.scale[2]};
  if (node.rotation.size() == 4) r = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
  return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s);
}

// Whether every entry is finite in single precision (converting a larger double to float is undefined behaviour).
bool fitsFloat(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::abs(m[c][r]) <= double(std::numeric_limits<float>::max()))) return false;
  return true;
}


class SceneBuilder {
 public:
  SceneBuilder(const fs::path& file, const tinygltf::Model& model, SceneMemory& memory)
      : reader_(file, model, memory), model_(model), visited_(model.nodes.size(), false), animation_(reader_, model) {}

  // Why the file's first perspective camera cannot render ("" when it can, or when there is none).
  const std::string& unusableCamera() const { return unusableCamera_; }
  // Why the file's directional lights cannot be the one sun ("" when they can).
  const std::string& secondSun() const { return secondSun_; }

  Scene build() {
    if (model_.scenes.empty()) reader_.corrupt("it has no scene");
    const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (std::size_t(sceneIndex) >= model_.scenes.size()) reader_.corrupt("its default scene does not exist");
    scene_.name = reader_.file().stem().string();
    for (int root : model_.scenes[std::size_t(sceneIndex)].nodes) visit(root, glm::dmat4(1.0), 0);
    if (scene_.objects.empty()) reader_.corrupt("its scene has no triangle meshes");
    if (!hasCamera_) frameTheScene();
    scene_.animation = animation_.finish();
    poseScene(scene_, 0.0);  // a skinned or animated scene starts at its animation's time 0
    return std::move(scene_);
  }

 private:
  // glTF node hierarchies are disjoint strict trees: a node reached a second time (listed by two parents, twice
  // by one, or in a cycle) is refused, so a small file of shared children cannot make the walk exponential.
  void visit(int nodeIndex, const glm::dmat4& parent, int depth) {
    const std::string name = "node " + std::to_string(nodeIndex);
    if (nodeIndex < 0 || std::size_t(nodeIndex) >= model_.nodes.size()) reader_.corrupt(name + " does not exist");
    if (visited_[std::size_t(nodeIndex)])
      reader_.corrupt(name + " is reached twice (glTF node hierarchies are trees: one parent per node, no cycles)");
    visited_[std::size_t(nodeIndex)] = true;
    if (depth > 64) reader_.corrupt("its node hierarchy is deeper than 64 levels");
    const tinygltf::Node& node = model_.nodes[std::size_t(nodeIndex)];
    const glm::dmat4 worldD = parent * nodeTransform(node);
    if (!fitsFloat(worldD))
      reader_.corrupt(name + "'s transform overflows single precision (an entry beyond 3.4e38 after its parents')");
    const glm::mat4 world(worldD);
    // A skinned mesh is placed by its joints, not by its node (glTF 2.0, 3.7.3.3): its vertices are posed in world space.
    const std::size_t firstObject = scene_.objects.size();
    if (node.mesh >= 0) addMesh(node.mesh, node.skin >= 0 ? glm::mat4(1.0f) : world, node.skin, nodeIndex);
    if (node.skin < 0) animation_.addObjects(nodeIndex, std::uint32_t(firstObject), std::uint32_t(scene_.objects.size() - firstObject));
    if (node.camera >= 0) addCamera(node.camera, world);
    if (auto light = node.extensions.find("KHR_lights_punctual"); light != node.extensions.end() && light->second.Has("light"))
      addLight(light->second.Get("light").GetNumberAsInt(), world);
    for (int child : node.children) visit(child, worldD, depth + 1);
  }

  void addMesh(int meshIndex, const glm::mat4& world, int skin, int nodeIndex) {
    if (std::size_t(meshIndex) >= model_.meshes.size()) reader_.corrupt("mesh " + std::to_string(meshIndex) + " does not exist");
    // A mirroring transform turns counter-clockwise triangles clockwise: those instances get flipped meshes.
    const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
    const std::vector<tinygltf::Primitive>& primitives = model_.meshes[std::size_t(meshIndex)].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const auto key = std::make_tuple(meshIndex, p, mirrored);
      auto cached = meshes_.find(key);
      if (skin < 0 && cached == meshes_.end()) cached = meshes_.emplace(key, addPrimitive(primitives[p], mirrored)).first;
      Object object;
      object.mesh = skin < 0 ? cached->second : addPrimitive(primitives[p], false);  // skinned: its own, re-posed
      if (skin >= 0) animation_.addSkinnedPrimitive(skin, nodeIndex, meshIndex, p, primitives[p], object.mesh, scene_.meshes[object.mesh]);
      object.material = material(primitives[p].material);
      const Mesh& mesh = scene_.meshes[object.mesh];
      if ((object.material.baseColorTexture != kNoTexture || object.material.normalTexture != kNoTexture) &&
          mesh.texCoords.empty())
        reader_.corrupt("a textured primitive of mesh " + std::to_string(meshIndex) + " has no TEXCOORD_0");
      object.transform = world;
      scene_.objects.push_back(object);
      for (const Vertex& v : mesh.vertices) {
        const glm::vec3 position(world * glm::vec4(v.position, 1.0f));
        if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
          reader_.corrupt("mesh " + std::to_string(meshIndex) + " placed by its node lies beyond single precision's range");
        boundsMin_ = glm::min(boundsMin_, position);
        boundsMax_ = glm::max(boundsMax_, position);
      }
    }
  }

  std::uint32_t addPrimitive(const tinygltf::Primitive& primitive, bool mirrored) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      reader_.unsupported("a primitive of points or lines (mode " + std::to_string(mode) + ")");
    if (!primitive.targets.empty()) reader_.unsupported("morph targets");
    auto attribute = [&](const char* name) {
      auto it = primitive.attributes.find(name);
      return it == primitive.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) reader_.corrupt("a primitive has no POSITION attribute");
    Mesh mesh;
    const std::vector<float> positions = reader_.readFloats(attribute("POSITION"), TINYGLTF_TYPE_VEC3, "POSITION");
    mesh.vertices.resize(positions.size() / 3);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      mesh.vertices[v].position = {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
    auto perVertex = [&](const std::vector<float>& values, std::size_t components, const char* name) {
      if (values.size() != mesh.vertices.size() * components)
        reader_.corrupt(std::string(name) + " has a different vertex count than POSITION");
    };
    if (attribute("NORMAL") >= 0) {
      const std::vector<float> normals = reader_.readFloats(attribute("NORMAL"), TINYGLTF_TYPE_VEC3, "NORMAL");
      perVertex(normals, 3, "NORMAL");
      for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::vec3 n(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
        mesh.vertices[v].normal = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 1.0f, 0.0f);
      }
    }
    if (attribute("TEXCOORD_0") >= 0) {
      const std::vector<float> uv = reader_.readFloats(attribute("TEXCOORD_0"), TINYGLTF_TYPE_VEC2, "TEXCOORD_0");
      perVertex(uv, 2, "TEXCOORD_0");
      for (std::size_t v = 0; v < mesh.vertices.size(); ++v) mesh.texCoords.push_back({uv[2 * v], uv[2 * v + 1]});
    }
    if (attribute("TANGENT") >= 0) {
      const std::vector<float> t = reader_.readFloats(attribute("TANGENT"), TINYGLTF_TYPE_VEC4, "TANGENT");
      perVertex(t, 4, "TANGENT");
      for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        mesh.tangents.push_back({t[4 * v], t[4 * v + 1], t[4 * v + 2], t[4 * v + 3] < 0.0f ? -1.0f : 1.0f});
    }

    std::vector<std::uint32_t> order;
    if (primitive.indices >= 0) {
      order = reader_.readIndices(primitive.indices);
    } else {
      order.resize(mesh.vertices.size());
      for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    }
    for (std::uint32_t index : order)
      if (index >= mesh.vertices.size()) reader_.corrupt("a primitive's index " + std::to_string(index) + " is out of range");
    // Strips and fans become lists, every triangle counter-clockwise (clockwise in the file when mirrored).
    auto addTriangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (mirrored) std::swap(b, c);
      mesh.indices.insert(mesh.indices.end(), {a, b, c});
    };
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < order.size(); ++i)
        i % 2 == 0 ? addTriangle(order[i], order[i + 1], order[i + 2]) : addTriangle(order[i + 1], order[i], order[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (std::size_t i = 1; i + 1 < order.size(); ++i) addTriangle(order[0], order[i], order[i + 1]);
    } else {
      for (std::size_t i = 0; i + 2 < order.size(); i += 3) addTriangle(order[i], order[i + 1], order[i + 2]);
    }
    if (mesh.indices.empty()) reader_.corrupt("a primitive has no triangles");
    if (attribute("NORMAL") < 0) generateNormals(mesh);
    const tinygltf::Material* gltfMaterial =
        primitive.material >= 0 && std::size_t(primitive.material) < model_.materials.size()
            ? &model_.materials[std::size_t(primitive.material)]
            : nullptr;
    if (gltfMaterial && gltfMaterial->normalTexture.index >= 0 && mesh.tangents.empty() && !mesh.texCoords.empty())
      generateTangents(mesh);
    if (mirrored)  // the mirrored transform flips cross(normal, tangent): keep the bitangent on its side
      for (glm::vec4& tangent : mesh.tangents) tangent.w = -tangent.w;
    reader_.allocationFor<unsigned char>(mesh.vertices.size() * sizeof(Vertex) + mesh.indices.size() * 4 +
                                             mesh.texCoords.size() * sizeof(glm::vec2) +
                                             mesh.tangents.size() * sizeof(glm::vec4),
                                         "mesh");
    scene_.meshes.push_back(std::move(mesh));
    return std::uint32_t(scene_.meshes.size() - 1);
  }

  // glTF metallic-roughness -> albedo / F0 / glossiness (scene_file.h, docs/DESIGN.md).
  Material material(int index) {
    Material m;
    const tinygltf::Material defaults;  // glTF's default material: white, metallic 1, roughness 1
    if (index >= 0 && std::size_t(index) >= model_.materials.size()) reader_.corrupt("material " + std::to_string(index) + " does not exist");
    const tinygltf::Material& source = index >= 0 ? model_.materials[std::size_t(index)] : defaults;
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    const std::vector<double>& factor = pbr.baseColorFactor;
    const std::string where = "material " + std::to_string(index) + "'s ";
    glm::vec4 base(1.0f);
    if (factor.size() == 4)
      for (int c = 0; c < 4; ++c) base[c] = reader_.toFloat(factor[std::size_t(c)], where + "baseColorFactor");
    const float metallic = glm::clamp(reader_.toFloat(pbr.metallicFactor, where + "metallicFactor"), 0.0f, 1.0f);
    m.albedo = glm::vec3(base) * (1.0f - metallic);
    m.specularColor = glm::mix(glm::vec3(0.04f), glm::vec3(base), metallic);
    m.glossiness = glossinessFromRoughness(reader_.toFloat(pbr.roughnessFactor, where + "roughnessFactor"));
    readMaterialExtras(reader_, source, "material " + std::to_string(index) + named(source.name), base.a, m);
    if (source.alphaMode == "BLEND") {
      m.alphaBlend = true;
      m.opacity = glm::clamp(base.a, 1e-3f, 1.0f);
    }
    if (pbr.baseColorTexture.index >= 0) {
      if (pbr.baseColorTexture.texCoord != 0) reader_.unsupported("a base color texture on TEXCOORD_" + std::to_string(pbr.baseColorTexture.texCoord));
      m.baseColorTexture = texture(pbr.baseColorTexture.index, Texture::Encoding::Srgb);
      m.baseColorTransform = readTextureTransform(reader_, pbr.baseColorTexture.extensions,
                                                  "material " + std::to_string(index) + named(source.name), "base color");
    }
    if (source.normalTexture.index >= 0) {
      if (source.normalTexture.texCoord != 0) reader_.unsupported("a normal texture on TEXCOORD_" + std::to_string(source.normalTexture.texCoord));
      m.normalTexture = texture(source.normalTexture.index, Texture::Encoding::Linear);
      m.normalScale = reader_.toFloat(source.normalTexture.scale, where + "normalTexture.scale");
      m.normalTransform = readTextureTransform(reader_, source.normalTexture.extensions,
                                               "material " + std::to_string(index) + named(source.name), "normal");
    }
    return m;
  }

  std::int32_t texture(int textureIndex, Texture::Encoding encoding) {
    if (textureIndex < 0 || std::size_t(textureIndex) >= model_.textures.size())
      reader_.corrupt("texture " + std::to_string(textureIndex) + " does not exist");
    const int source = textureImage(model_.textures[std::size_t(textureIndex)]);
    if (source < 0 || std::size_t(source) >= model_.images.size())
      reader_.unsupported("texture " + std::to_string(textureIndex) + " without a PNG, JPEG or WebP image source");
    const auto key = std::make_pair(source, encoding);
    if (auto cached = textures_.find(key); cached != textures_.end()) return cached->second;
    const tinygltf::Image& image = model_.images[std::size_t(source)];
    if (image.width <= 0 || image.height <= 0 || image.image.empty())
      reader_.corrupt("image " + std::to_string(source) + " ('" + image.uri + "') could not be decoded");
    if (image.component != 4 || (image.bits != 8 && image.bits != 16))
      reader_.unsupported("image " + std::to_string(source) + " with " + std::to_string(image.component) + " channels of " +
                          std::to_string(image.bits) + " bits");
    Texture texture;
    texture.width = std::uint32_t(image.width);
    texture.height = std::uint32_t(image.height);
    texture.encoding = encoding;
    const std::size_t count = std::size_t(image.width) * std::size_t(image.height) * 4;
    if (image.image.size() != count * std::size_t(image.bits / 8)) reader_.corrupt("image " + std::to_string(source) + " has the wrong size");
    texture.rgba.resize(reader_.allocationFor<std::uint8_t>(count, "image " + std::to_string(source)));
    for (std::size_t i = 0; i < count; ++i)  // 16-bit channels keep their high byte
      texture.rgba[i] = image.bits == 8 ? image.image[i] : image.image[2 * i + 1];
    scene_.textures.push_back(std::move(texture));
    const auto index = std::int32_t(scene_.textures.size() - 1);
    textures_.emplace(key, index);
    return index;
  }

  void addCamera(int cameraIndex, const glm::mat4& world) {
    if (std::size_t(cameraIndex) >= model_.cameras.size()) reader_.corrupt("camera " + std::to_string(cameraIndex) + " does not exist");
    const tinygltf::Camera& camera = model_.cameras[std::size_t(cameraIndex)];
    if (hasCamera_ || camera.type != "perspective") return;  // the first perspective camera is the scene's
    const tinygltf::PerspectiveCamera& p = camera.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.14) || !(p.znear > 0.0) || (p.zfar != 0.0 && !(p.zfar > p.znear)))
      reader_.corrupt("camera " + std::to_string(cameraIndex) + " has an invalid field of view or depth range");
    const double far = p.zfar > 0.0 ? p.zfar : std::max(1000.0, 1e4 * p.znear);  // infinite: far
    // Unusable unless NAME.scene.json gives the scene its own camera (loadGltfScene decides); framed meanwhile.
    if (const std::string problem = depthRangeProblem(p.znear, far); !problem.empty()) {
      unusableCamera_ = "camera " + std::to_string(cameraIndex) + ": " + problem;
      return;
    }
    scene_.camera.position = glm::vec3(world[3]);
    scene_.camera.verticalFovRadians = float(p.yfov);
    scene_.camera.nearPlane = float(p.znear);
    scene_.camera.farPlane = float(far);
    // The renderer's camera has yaw and pitch, no roll: the node's -Z axis gives both.
    const glm::vec3 forward = glm::normalize(-glm::vec3(world[2]));
    scene_.camera.yawRadians = std::atan2(-forward.x, -forward.z);
    scene_.camera.pitchRadians = std::asin(glm::clamp(forward.y, -1.0f, 1.0f));
    hasCamera_ = true;
  }

  void addLight(int lightIndex, const glm::mat4& world) {
    if (lightIndex < 0 || std::size_t(lightIndex) >= model_.lights.size()) reader_.corrupt("light " + std::to_string(lightIndex) + " does not exist");
    const tinygltf::Light& light = model_.lights[std::size_t(lightIndex)];
    // Intensities become the renderer's linear radiance scale as they are (lux / candela taken at exposure 1).
    const std::string where = "light " + std::to_string(lightIndex) + "'s ";
    glm::vec3 color(1.0f);
    if (light.color.size() >= 3)
      for (int c = 0; c < 3; ++c) color[c] = reader_.toFloat(light.color[std::size_t(c)], where + "color");
    color *= reader_.toFloat(light.intensity, where + "intensity");
    if (light.type == "directional") {
      addDirectionalLight(lightIndex, glm::normalize(glm::vec3(world[2])), color);  // it shines down its node's -Z
    } else if (light.type == "point") {
      PointLight point;
      point.position = glm::vec3(world[3]);
      point.color = color;
      // Without a range: where its falloff leaves under 1/200 of unit radiance.
      const float peak = std::max({color.r, color.g, color.b, 1e-6f});
      point.radius = light.range > 0.0 ? reader_.toFloat(light.range, where + "range") : std::sqrt(peak * 200.0f);
      scene_.pointLights.push_back(point);
    } else {
      reader_.unsupported("the " + light.type + " light " + std::to_string(lightIndex) + named(light.name) +
                          " (only directional and point lights)");
    }
  }

  // The renderer has one sun: directional lights from one direction add up into it (exact: a light placed by two
  // nodes counts twice); one from another direction makes the file unusable unless NAME.scene.json gives the sun.
  void addDirectionalLight(int lightIndex, const glm::vec3& directionToSun, const glm::vec3& color) {
    if (!hasSun_) {
      scene_.sun.directionToSun = directionToSun;
      scene_.sun.color = color;
      hasSun_ = true;
    } else if (glm::dot(scene_.sun.directionToSun, directionToSun) > 0.99999f) {
      scene_.sun.color += color;
    } else if (secondSun_.empty()) {
      secondSun_ = "directional light " + std::to_string(lightIndex) + " shines from another direction than the first " +
                   "(the renderer has one sun)";
    }
  }

  // Without a camera in the file: look down -Z at the whole scene from in front of its bounds.
  void frameTheScene() {
    const glm::vec3 centre = 0.5f * (boundsMin_ + boundsMax_);
    const float radius = std::max(0.5f * glm::length(boundsMax_ - boundsMin_), 1e-3f);
    Camera& camera = scene_.camera;
    camera.verticalFovRadians = 0.8f;
    const float distance = 1.2f * radius / std::tan(0.5f * camera.verticalFovRadians);
    camera.position = centre + glm::vec3(0.0f, 0.0f, distance);
    camera.yawRadians = camera.pitchRadians = 0.0f;
    camera.nearPlane = std::max(1e-3f, 0.01f * radius);
    camera.farPlane = distance + 4.0f * radius;
  }

  GltfReader reader_;
  const tinygltf::Model& model_;
  std::vector<bool> visited_;  // per node
  Scene scene_;
  std::map<std::tuple<int, std::size_t, bool>, std::uint32_t> meshes_;  // (mesh, primitive, mirrored) -> mesh
  std::map<std::pair<int, Texture::Encoding>, std::int32_t> textures_;  // (image, encoding) -> texture
  AnimationBuilder animation_;  // nodes, skins and the first animation
  bool hasCamera_ = false;
  std::string unusableCamera_;  // why the file's camera cannot render, when it cannot
  bool hasSun_ = false;
  std::string secondSun_;  // why the file's directional lights cannot be one sun, when they cannot
  glm::vec3 boundsMin_{1e30f}, boundsMax_{-1e30f};
};

}  // namespace

float glossinessFromRoughness(float roughness) {
  const float r = std::max(glm::clamp(roughness, 0.0f, 1.0f), 0.02f);  // a = r^2 >= 4e-4 keeps the exponent finite
  const float a = r * r;
  const float exponent = std::max(2.0f / (a * a) - 2.0f, 2.0f);
  return glm::clamp((std::log2(exponent) - 1.0f) / 10.0f, 0.0f, 1.0f);  // inverse of blinnPhongExponent
}

bool isSceneFile(const std::string& scene) {
  const std::string extension = lowercase(fs::path(scene).extension().string());
  return extension == ".gltf" || extension == ".glb";
}

fs::path sceneDescriptionPath(const fs::path& gltfFile) {
  fs::path description = gltfFile;
  description.replace_extension(".scene.json");
  return description;
}

Scene loadGltfScene(const fs::path& file, std::uint64_t memoryLimit) {
  std::error_code error;
  if (const std::string problem = inputFileProblem(file); !problem.empty())
    throw std::runtime_error("glTF file '" + file.string() + "' " + problem);
  const bool binary = lowercase(file.extension().string()) == ".glb";
  SceneFolderSandbox sandbox{fs::weakly_canonical(fs::absolute(file).parent_path(), error)};
  const nlohmann::json json = gltfJson(file, binary);
  if (json.is_object()) {
    requireSupportedExtensions(file, json);
    requireUrisInsideFolder(file, sandbox.folder, json);
  }
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(sandboxedFileCallbacks(sandbox));
  SceneMemory memory{memoryLimit};
  loader.SetImageLoader(loadImageWithinLimits, &memory);
  tinygltf::Model model;
  std::string errors, warnings;
  const bool loaded = parseGltf(loader, model, errors, warnings, file, binary, json);
  if (!loaded) {
    std::string reason = errors.empty() ? "tinygltf could not parse it" : errors;
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw std::runtime_error("glTF file '" + file.string() + "' cannot be loaded: " + reason);
  }
  decodeMeshoptViews(file, model, memory);
  decodeDracoPrimitives(file, model, memory);
  SceneBuilder builder(file, model, memory);
  Scene scene = builder.build();
  if (json.is_object())  // a required one was refused above
    for (const std::string& extension : ignoredExtensions(json))
      scene.warnings.push_back("glTF file '" + file.string() + "' uses the extension '" + extension +
                               "', which s3d does not read; the file does not require it, so it renders without it");
  const fs::path description = sceneDescriptionPath(file);
  const DescribedParts described =
      fs::exists(description, error) ? applySceneDescription(description, scene) : DescribedParts{};
  const std::string where = "glTF file '" + file.string() + "': ";
  if (!builder.unusableCamera().empty() && !described.camera)
    throw std::invalid_argument(where + builder.unusableCamera() + " (or give the scene a camera in " +
                                description.filename().string() + ")");
  if (!builder.secondSun().empty() && !described.sun)
    throw std::invalid_argument(where + builder.secondSun() + " (or give the scene its sun in " +
                                description.filename().string() + ")");
  return scene;
}

std::vector<fs::path> sceneFileInputs(const fs::path& file) {
  const bool binary = lowercase(file.extension().string()) == ".glb";
  nlohmann::json json;
  try {
    json = gltfJson(file, binary);
  } catch (const InputFileError&) {  // loadGltfScene names the problem
  }
  std::vector<fs::path> inputs{file};
  std::error_code error;
  if (fs::exists(sceneDescriptionPath(file), error)) inputs.push_back(sceneDescriptionPath(file));
  if (!json.is_object()) return inputs;
  for (const char* kind : {"buffers", "images"}) {
    const auto list = json.find(kind);
    if (list == json.end() || !list->is_array()) continue;
    for (const nlohmann::json& entry : *list)
      if (entry.is_object() && entry.contains("uri") && entry["uri"].is_string() &&
          entry["uri"].get<std::string>().rfind("data:", 0) != 0)
        inputs.push_back(file.parent_path() / decodedUri(entry["uri"].get<std::string>()));
  }
  return inputs;
}

Scene loadScene(const std::string& scene) { return isSceneFile(scene) ? loadGltfScene(scene) : makeBuiltInScene(scene); }

}  // namespace s3d::renderer