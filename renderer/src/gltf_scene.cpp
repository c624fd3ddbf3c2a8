// glTF 2.0 scenes (scene_file.h). tinygltf comes from Debian's libtinygltf-dev, which ships the implementation
// compiled as libtinygltf.so (with stb_image for PNG/JPEG and nlohmann json): this file only includes the
// declarations, so no TINYGLTF_IMPLEMENTATION here (README.Debian of the package).
#include "s3d/renderer/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <functional>
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
#include <stb/stb_image.h>  // the header only: stbi_info_from_memory sizes a texture before tinygltf decodes it
#include <tiny_gltf.h>

#include "s3d/image_limits.h"
#include "s3d/input_file.h"
#include "s3d/json_document.h"
#include "s3d/number_text.h"


namespace s3d::renderer {
namespace fs = std::filesystem;

namespace {

// What a scene takes in memory as it is loaded (decoded textures, vertices, indices): each allocation is counted
// before it is made, so a small file cannot declare its way past the limit (scene_file.h, kMaxSceneBytes).
struct SceneMemory {
  std::uint64_t limit = kMaxSceneBytes;
  std::uint64_t used = 0;

  std::string limitText() const {
    return limit >= (1u << 20) ? std::to_string(limit >> 20) + " MiB" : std::to_string(limit) + " bytes";
  }
  // False when `bytes` more do not fit; else counts them.
  bool reserve(std::uint64_t bytes) {
    if (bytes > limit - used) return false;
    used += bytes;
    return true;
  }
};

// Every error names the file it comes from.
class GltfReader {
 public:
  GltfReader(const fs::path& file, const tinygltf::Model& model, SceneMemory& memory)
      : file_(file), model_(model), memory_(memory) {}

  [[noreturn]] void corrupt(const std::string& what) const {
    throw std::runtime_error("glTF file '" + file_.string() + "' is corrupt: " + what);
  }
  [[noreturn]] void unsupported(const std::string& what) const { refuse(what + " is not supported"); }
  [[noreturn]] void refuse(const std::string& why) const {
    throw std::invalid_argument("glTF file '" + file_.string() + "': " + why);
  }

  // An accessor's elements as floats (components per element), normalized integers mapped to [0, 1] / [-1, 1].
  std::vector<float> readFloats(int accessorIndex, int type, const char* what) const {
    const tinygltf::Accessor& accessor = accessorAt(accessorIndex, what);
    if (accessor.type != type) corrupt(std::string(what) + " accessor has the wrong element type");
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(type));
    const Span span = spanOf(accessor, components, what);
    std::vector<float> values(allocationFor<float>(accessor.count * std::size_t(components), what));
    forEachComponent(span, accessor.count, components, [&](std::size_t i, const unsigned char* p) {
      switch (accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&values[i], p, 4); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: values[i] = float(*p) / 255.0f; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          values[i] = float(v) / 65535.0f;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: values[i] = std::max(float(std::int8_t(*p)) / 127.0f, -1.0f); break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
          std::int16_t v;
          std::memcpy(&v, p, 2);
          values[i] = std::max(float(v) / 32767.0f, -1.0f);
          break;
        }
        default: corrupt(std::string(what) + " accessor has an invalid component type");
      }
    });
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !accessor.normalized)
      unsupported(std::string(what) + " stored as unnormalized integers");
    for (float v : values)
      if (!std::isfinite(v)) corrupt(std::string(what) + " contains a non-finite value");
    return values;
  }

  std::vector<std::uint32_t> readIndices(int accessorIndex) const {
    const tinygltf::Accessor& accessor = accessorAt(accessorIndex, "index");
    if (accessor.type != TINYGLTF_TYPE_SCALAR) corrupt("index accessor is not scalar");
    const Span span = spanOf(accessor, 1, "index");
    std::vector<std::uint32_t> indices(allocationFor<std::uint32_t>(accessor.count, "index"));
    forEachComponent(span, accessor.count, 1, [&](std::size_t i, const unsigned char* p) {
      switch (accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = *p; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          indices[i] = v;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&indices[i], p, 4); break;
        default: corrupt("index accessor has an invalid component type");
      }
    });
    return indices;
  }

  const fs::path& file() const { return file_; }

  // A number of the file as a float: refused past float's range (converting it would be undefined behaviour).
  float toFloat(double value, const std::string& what) const {
    if (!(std::abs(value) <= double(std::numeric_limits<float>::max())))
      corrupt(what + " " + numberText(value) + " is not a number within single precision");
    return float(value);
  }

  // Counts `count` elements of T against the scene's memory before they are allocated; returns `count`.
  template <typename T>
  std::size_t allocationFor(std::size_t count, const std::string& what) const {
    if (!memory_.reserve(std::uint64_t(count) * sizeof(T)))
      refuse("its " + what + " data would take the scene past the " + memory_.limitText() +
             " a scene may take in memory");
    return count;
  }

 private:
  const tinygltf::Accessor& accessorAt(int index, const char* what) const {
    if (index < 0 || std::size_t(index) >= model_.accessors.size())
      corrupt(std::string(what) + " accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(index)];
    if (accessor.sparse.isSparse) unsupported(std::string("a sparse ") + what + " accessor");
    return accessor;
  }

  // Where an accessor's elements lie: checked to lie inside its buffer view and buffer before anything is
  // allocated for them (a count of 2^32 in a small file must not allocate first).
  struct Span {
    const unsigned char* begin = nullptr;
    std::size_t stride = 0, componentSize = 0;
  };

  Span spanOf(const tinygltf::Accessor& accessor, int components, const char* what) const {
    if (accessor.count == 0) return {};
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= model_.bufferViews.size())
      corrupt(std::string(what) + " accessor has no buffer view");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(accessor.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
      corrupt(std::string(what) + " buffer view refers to a missing buffer");
    const std::vector<unsigned char>& data = model_.buffers[std::size_t(view.buffer)].data;
    const int componentSize = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    const int stride = accessor.ByteStride(view);
    if (componentSize <= 0 || stride <= 0) corrupt(std::string(what) + " accessor has an invalid layout");
    const std::size_t elementSize = std::size_t(componentSize) * std::size_t(components);
    // In overflow-free steps (every offset and count is the file's): the view lies in the buffer, and
    // accessor.byteOffset + stride * (count - 1) + elementSize lies in the view.
    if (view.byteOffset > data.size()) corrupt(std::string(what) + " buffer view starts past the end of its buffer");
    const std::size_t viewBytes = std::min(view.byteLength, data.size() - view.byteOffset);
    if (accessor.byteOffset > viewBytes || viewBytes - accessor.byteOffset < elementSize ||
        (accessor.count - 1) > (viewBytes - accessor.byteOffset - elementSize) / std::size_t(stride))
      corrupt(std::string(what) + " accessor reads past the end of its buffer");
    const std::size_t begin = view.byteOffset + accessor.byteOffset;
    return {data.data() + begin, std::size_t(stride), std::size_t(componentSize)};
  }

  // Calls visit(component index, bytes) for every component of a span checked by spanOf.
  static void forEachComponent(const Span& span, std::size_t count, int components,
                               const std::function<void(std::size_t, const unsigned char*)>& visit) {
    for (std::size_t element = 0; element < count; ++element)
      for (int c = 0; c < components; ++c)
        visit(element * std::size_t(components) + std::size_t(c),
              span.begin + element * span.stride + std::size_t(c) * span.componentSize);
  }

  fs::path file_;
  const tinygltf::Model& model_;
  SceneMemory& memory_;
};

// " ('name')" after an index, or nothing for an unnamed element: files name few of their nodes and materials.
std::string named(const std::string& name) { return name.empty() ? "" : " ('" + name + "')"; }

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


// Smooth per-vertex normals from the triangles (area-weighted), for primitives without NORMAL.
void generateNormals(Mesh& mesh) {
  for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    Vertex& a = mesh.vertices[mesh.indices[t]];
    Vertex& b = mesh.vertices[mesh.indices[t + 1]];
    Vertex& c = mesh.vertices[mesh.indices[t + 2]];
    const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
    a.normal += n;
    b.normal += n;
    c.normal += n;
  }
  for (Vertex& v : mesh.vertices) v.normal = glm::length(v.normal) > 0.0f ? glm::normalize(v.normal) : glm::vec3(0, 1, 0);
}

// Per-vertex tangents from the texture-coordinate gradients of the triangles around each vertex (Lengyel's
// method), for normal-mapped primitives without TANGENT. glTF normal maps point green up the image, towards -v
// (v = 0 is the top row): the handedness puts the bitangent on the side of -v.
void generateTangents(Mesh& mesh) {
  std::vector<glm::vec3> tangent(mesh.vertices.size(), glm::vec3(0.0f)), bitangent(mesh.vertices.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::vec3 e1 = mesh.vertices[i1].position - mesh.vertices[i0].position;
    const glm::vec3 e2 = mesh.vertices[i2].position - mesh.vertices[i0].position;
    const glm::vec2 d1 = mesh.texCoords[i1] - mesh.texCoords[i0];
    const glm::vec2 d2 = mesh.texCoords[i2] - mesh.texCoords[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-12f) continue;  // degenerate texture mapping: no direction to contribute
    const glm::vec3 du = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 dv = (e2 * d1.x - e1 * d2.x) / det;
    for (std::uint32_t i : {i0, i1, i2}) {
      tangent[i] += du;
      bitangent[i] += dv;
    }
  }
  mesh.tangents.resize(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const glm::vec3 n = mesh.vertices[v].normal;
    glm::vec3 t = tangent[v] - n * glm::dot(n, tangent[v]);
    if (glm::length(t) < 1e-12f) t = glm::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
    t = glm::normalize(t);
    const float handedness = glm::dot(glm::cross(n, t), -bitangent[v]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[v] = glm::vec4(t, handedness);
  }
}

class SceneBuilder {
 public:
  SceneBuilder(const fs::path& file, const tinygltf::Model& model, SceneMemory& memory)
      : reader_(file, model, memory), model_(model), visited_(model.nodes.size(), false) {}

  Scene build() {
    if (model_.scenes.empty()) reader_.corrupt("it has no scene");
    const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (std::size_t(sceneIndex) >= model_.scenes.size()) reader_.corrupt("its default scene does not exist");
    scene_.name = reader_.file().stem().string();
    for (int root : model_.scenes[std::size_t(sceneIndex)].nodes) visit(root, glm::dmat4(1.0), 0);
    if (scene_.objects.empty()) reader_.corrupt("its scene has no triangle meshes");
    if (!hasCamera_) frameTheScene();
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
    if (node.skin >= 0) reader_.unsupported("skinning (" + name + named(node.name) + ")");
    if (node.mesh >= 0) addMesh(node.mesh, world);
    if (node.camera >= 0) addCamera(node.camera, world);
    if (auto light = node.extensions.find("KHR_lights_punctual"); light != node.extensions.end() && light->second.Has("light"))
      addLight(light->second.Get("light").GetNumberAsInt(), world);
    for (int child : node.children) visit(child, worldD, depth + 1);
  }

  void addMesh(int meshIndex, const glm::mat4& world) {
    if (std::size_t(meshIndex) >= model_.meshes.size()) reader_.corrupt("mesh " + std::to_string(meshIndex) + " does not exist");
    // A mirroring transform turns counter-clockwise triangles clockwise: those instances get flipped meshes.
    const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
    const std::vector<tinygltf::Primitive>& primitives = model_.meshes[std::size_t(meshIndex)].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const auto key = std::make_tuple(meshIndex, p, mirrored);
      auto cached = meshes_.find(key);
      if (cached == meshes_.end()) cached = meshes_.emplace(key, addPrimitive(primitives[p], mirrored)).first;
      Object object;
      object.mesh = cached->second;
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
    if (source.alphaMode == "MASK")
      reader_.unsupported("alphaMode MASK (alpha cut-outs) in material " + std::to_string(index) + named(source.name));
    if (source.alphaMode == "BLEND") {
      m.alphaBlend = true;
      m.opacity = glm::clamp(base.a, 1e-3f, 1.0f);
    }
    if (pbr.baseColorTexture.index >= 0) {
      if (pbr.baseColorTexture.texCoord != 0) reader_.unsupported("a base color texture on TEXCOORD_" + std::to_string(pbr.baseColorTexture.texCoord));
      m.baseColorTexture = texture(pbr.baseColorTexture.index, Texture::Encoding::Srgb);
    }
    if (source.normalTexture.index >= 0) {
      if (source.normalTexture.texCoord != 0) reader_.unsupported("a normal texture on TEXCOORD_" + std::to_string(source.normalTexture.texCoord));
      m.normalTexture = texture(source.normalTexture.index, Texture::Encoding::Linear);
      m.normalScale = reader_.toFloat(source.normalTexture.scale, where + "normalTexture.scale");
    }
    return m;
  }

  std::int32_t texture(int textureIndex, Texture::Encoding encoding) {
    if (textureIndex < 0 || std::size_t(textureIndex) >= model_.textures.size())
      reader_.corrupt("texture " + std::to_string(textureIndex) + " does not exist");
    const int source = model_.textures[std::size_t(textureIndex)].source;
    if (source < 0 || std::size_t(source) >= model_.images.size())
      reader_.unsupported("texture " + std::to_string(textureIndex) + " without a PNG/JPEG image source");
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
    if (const std::string problem = depthRangeProblem(p.znear, far); !problem.empty())
      reader_.refuse("camera " + std::to_string(cameraIndex) + ": " + problem);
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
      if (hasSun_) reader_.unsupported("more than one directional light");
      scene_.sun.directionToSun = glm::normalize(glm::vec3(world[2]));  // the light shines down its node's -Z
      scene_.sun.color = color;
      hasSun_ = true;
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
  bool hasCamera_ = false;
  bool hasSun_ = false;
  glm::vec3 boundsMin_{1e30f}, boundsMax_{-1e30f};
};

// ---- NAME.scene.json ----

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

  void apply(Scene& scene) const {
    nlohmann::json doc = readJsonDocument(file_, "scene description");
    onlyKeys(doc, "the document",
             {"sun", "ambient", "pointLights", "sky", "camera", "cameraPath", "exposure", "ambientOcclusion",
              "ambientOcclusionRadius", "crosshairDistance"});
    if (doc.contains("sun")) {
      onlyKeys(doc["sun"], "sun", {"directionToSun", "color"});
      if (doc["sun"].contains("directionToSun")) {
        const glm::vec3 d = vec3(doc["sun"]["directionToSun"], "sun.directionToSun");
        if (glm::length(d) < 1e-6f) fail("sun.directionToSun must not be zero");
        scene.sun.directionToSun = glm::normalize(d);
      }
      if (doc["sun"].contains("color")) scene.sun.color = vec3(doc["sun"]["color"], "sun.color", 0.0f, 1e6f);
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
  }

 private:
  fs::path file_;
};

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

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

namespace {

// A scene file may read only files inside its own folder: URIs that are absolute, climb out with "..", or
// lead out through a link are refused before tinygltf follows them, and the file callbacks refuse anything
// outside the folder (tinygltf also searches the working directory).
std::string decodedUri(const std::string& uri) {
  std::string decoded;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return decoded;
}

bool isInside(const fs::path& folder, const fs::path& path) {
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(path, error);
  if (error) return false;
  const fs::path relative = resolved.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

// Largest glTF file, .bin buffer or image file a scene may name (a .gltf embeds its buffers as base64 text).
constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(2) << 30;

// The JSON part of a .gltf or .glb, parsed with the nesting limit (s3d/json_document.h) before tinygltf's
// recursive reader sees it; null when a .glb's container is broken (tinygltf then reports why). Throws
// InputFileError naming the file when it cannot be read, is not JSON or nests too deep.
nlohmann::json gltfJson(const fs::path& file, bool binary) {
  std::string bytes = readInputFile(file, "glTF file", kMaxSceneFileBytes);
  if (binary) {
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return nullptr;
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    if (length > bytes.size() - 20) return nullptr;
    bytes = bytes.substr(20, length);
  }
  return parseJsonDocument(bytes, "glTF file '" + file.string() + "'");
}

// Extensions the renderer needs but does not read, named before tinygltf parses the file: it reports their effects
// instead (a meshopt-compressed file's fallback buffer fails as "Invalid 'byteLength'").
constexpr const char* kReadExtensions[] = {"KHR_lights_punctual"};

void requireSupportedExtensions(const fs::path& file, const nlohmann::json& json) {
  const auto required = json.find("extensionsRequired");
  if (required == json.end() || !required->is_array()) return;
  for (const nlohmann::json& extension : *required) {
    if (!extension.is_string()) continue;
    const std::string name = extension.get<std::string>();
    if (std::find(std::begin(kReadExtensions), std::end(kReadExtensions), name) == std::end(kReadExtensions))
      throw std::invalid_argument("glTF file '" + file.string() + "': the required extension '" + name +
                                  "' is not supported (s3d reads KHR_lights_punctual)");
  }
}

void requireUrisInsideFolder(const fs::path& file, const fs::path& folder, const nlohmann::json& json) {
  for (const char* kind : {"buffers", "images"}) {
    const auto list = json.find(kind);
    if (list == json.end() || !list->is_array()) continue;
    for (std::size_t index = 0; index < list->size(); ++index) {
      const nlohmann::json& entry = (*list)[index];
      if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
      const std::string uri = entry["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::string decoded = decodedUri(uri);
      const bool hasScheme = decoded.find(':') != std::string::npos;
      std::string problem;
      if (decoded.empty()) problem = "is empty";
      else if (decoded.front() == '/' || decoded.front() == '\\' || hasScheme) problem = "is an absolute path";
      else if (const fs::path normal = fs::path(decoded).lexically_normal(); !normal.empty() && *normal.begin() == "..")
        problem = "climbs out of the scene's folder";
      else if (!isInside(folder, folder / decoded)) problem = "leads out of the scene's folder through a link";
      if (!problem.empty())
        throw std::invalid_argument("glTF file '" + file.string() + "': " + std::string(kind).substr(0, std::strlen(kind) - 1) +
                                    " " + std::to_string(index) + " URI '" + uri + "' " + problem +
                                    "; a scene may only use files in its own folder");
    }
  }
}

struct SceneFolderSandbox {
  fs::path folder;
};

bool fileExistsInside(const std::string& path, void* sandbox) {
  std::error_code error;
  return isInside(static_cast<SceneFolderSandbox*>(sandbox)->folder, path) && fs::is_regular_file(path, error);
}

std::string expandNothing(const std::string& path, void*) { return path; }  // no "~" or shell expansion

bool readWholeFileInside(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* sandbox) {
  if (!fileExistsInside(path, sandbox)) {
    if (error) *error += "file '" + path + "' is not in the scene's folder\n";
    return false;
  }
  try {
    const std::string bytes = readInputFile(path, "file", kMaxSceneFileBytes);
    if (bytes.empty()) {  // tinygltf indexes the first bytes without checking
      if (error) *error += "file '" + path + "' is empty\n";
      return false;
    }
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputFileError& failure) {
    if (error) *error += std::string(failure.what()) + "\n";
    return false;
  }
}

bool writeNothing(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
  if (error) *error += "scene loading writes no files\n";
  return false;
}

// Every texture is held to the readers' size limits (s3d/image_limits.h) before it is decoded: a PNG of a few
// hundred bytes can declare 20000x20000 pixels, 1.6 GB decoded (6 GB was measured through the renderer).
// The decoded pixels count against the scene's memory (SceneMemory) the same way, before decoding.
bool loadImageWithinLimits(tinygltf::Image* image, const int index, std::string* error, std::string* warning,
                           int requestedWidth, int requestedHeight, const unsigned char* bytes, int size, void* memory) {
  int width = 0, height = 0, channels = 0;
  if (stbi_info_from_memory(bytes, size, &width, &height, &channels) != 0 &&
      (std::uint32_t(width) > kMaxImageSide || std::uint32_t(height) > kMaxImageSide ||
       std::uint64_t(width) * std::uint64_t(height) > kMaxImagePixels)) {
    if (error)
      *error += "image " + std::to_string(index) + " is " + std::to_string(width) + "x" + std::to_string(height) +
                ", beyond the readers' limit of " + std::to_string(kMaxImageSide) + " pixels a side and " +
                std::to_string(kMaxImagePixels) + " pixels in all\n";
    return false;
  }
  auto& sceneMemory = *static_cast<SceneMemory*>(memory);
  const std::uint64_t bytesPerChannel = stbi_is_16_bit_from_memory(bytes, size) ? 2 : 1;
  if (!sceneMemory.reserve(std::uint64_t(width) * std::uint64_t(height) * 4 * bytesPerChannel)) {
    if (error)
      *error += "image " + std::to_string(index) + " would take the scene past the " + sceneMemory.limitText() +
                " a scene may take in memory\n";
    return false;
  }
  return tinygltf::LoadImageData(image, index, error, warning, requestedWidth, requestedHeight, bytes, size, nullptr);
}

}  // namespace

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
  loader.SetFsCallbacks({fileExistsInside, expandNothing, readWholeFileInside, writeNothing, &sandbox});
  SceneMemory memory{memoryLimit};
  loader.SetImageLoader(loadImageWithinLimits, &memory);
  tinygltf::Model model;
  std::string errors, warnings;
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &errors, &warnings, file.string())
                             : loader.LoadASCIIFromFile(&model, &errors, &warnings, file.string());
  if (!loaded) {
    std::string reason = errors.empty() ? "tinygltf could not parse it" : errors;
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw std::runtime_error("glTF file '" + file.string() + "' cannot be loaded: " + reason);
  }
  Scene scene = SceneBuilder(file, model, memory).build();
  const fs::path description = sceneDescriptionPath(file);
  if (fs::exists(description, error)) DescriptionReader(description).apply(scene);
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
