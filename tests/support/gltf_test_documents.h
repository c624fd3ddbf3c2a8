#pragma once
// glTF documents written by test code: a small curved grid mesh, a builder that lays its data out in one buffer
// (written as NAME.bin beside a .gltf, or as the BIN chunk of a .glb), and the loaded triangles compared
// independently of vertex order (compressors may reorder vertices and rotate triangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::test {
namespace fs = std::filesystem;

// A 5x4 grid bent into a ridge: positions on multiples of 1/4 (so 16-bit integers times a 1/4 node scale hold
// them exactly), unit normals across the ridge, texture coordinates across the grid, tangents along +x.
struct GridMesh {
  static constexpr std::uint32_t kColumns = 5, kRows = 4;
  std::vector<float> positions, normals, texCoords, tangents;
  std::vector<std::uint32_t> indices;
  std::size_t vertexCount() const { return positions.size() / 3; }
};

inline GridMesh gridMesh() {
  GridMesh grid;
  for (std::uint32_t r = 0; r < GridMesh::kRows; ++r)
    for (std::uint32_t c = 0; c < GridMesh::kColumns; ++c) {
      const float x = 0.25f * float(c), y = 0.25f * float(r), z = c == 2 ? 0.25f : 0.0f;
      const glm::vec3 n = glm::normalize(glm::vec3(c < 2 ? -0.5f : c > 2 ? 0.5f : 0.0f, 0.0f, 1.0f));
      grid.positions.insert(grid.positions.end(), {x, y, z});
      grid.normals.insert(grid.normals.end(), {n.x, n.y, n.z});
      grid.texCoords.insert(grid.texCoords.end(), {float(c) / 4.0f, float(r) / 3.0f});
      grid.tangents.insert(grid.tangents.end(), {1.0f, 0.0f, 0.0f, r % 2 == 0 ? 1.0f : -1.0f});
    }
  for (std::uint32_t r = 0; r + 1 < GridMesh::kRows; ++r)
    for (std::uint32_t c = 0; c + 1 < GridMesh::kColumns; ++c) {
      const std::uint32_t a = r * GridMesh::kColumns + c, b = a + 1, d = a + GridMesh::kColumns, e = d + 1;
      grid.indices.insert(grid.indices.end(), {a, b, e, a, e, d});
    }
  return grid;
}

inline std::string bytesOf(const void* data, std::size_t size) { return {static_cast<const char*>(data), size}; }
template <typename T>
std::string bytesOf(const std::vector<T>& values) { return bytesOf(values.data(), values.size() * sizeof(T)); }

inline std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t group = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) group |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) group |= std::uint8_t(bytes[i + 2]);
    const std::size_t present = std::min<std::size_t>(3, bytes.size() - i);
    for (std::size_t k = 0; k < 4; ++k) out += k <= present ? digits[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// A document whose binary data all lies in buffer 0, appended view by view (4-byte aligned).
class GltfBuilder {
 public:
  GltfBuilder() {
    doc = {{"asset", {{"version", "2.0"}}}, {"buffers", nlohmann::json::array({nlohmann::json::object()})},
           {"bufferViews", nlohmann::json::array()}, {"accessors", nlohmann::json::array()}};
  }

  // A view of `bytes` in buffer 0; returns its index.
  int view(const std::string& bytes, std::size_t stride = 0) {
    data_ += std::string((4 - data_.size() % 4) % 4, '\0');
    nlohmann::json entry = {{"buffer", 0}, {"byteOffset", data_.size()}, {"byteLength", bytes.size()}};
    if (stride) entry["byteStride"] = stride;
    data_ += bytes;
    doc["bufferViews"].push_back(entry);
    return int(doc["bufferViews"].size() - 1);
  }
  // Bytes in buffer 0 that no view covers (a view's compressed data); returns their offset.
  std::size_t append(const std::string& bytes) {
    data_ += std::string((4 - data_.size() % 4) % 4, '\0');
    data_ += bytes;
    return data_.size() - bytes.size();
  }

  int accessor(int view, int componentType, std::size_t count, const char* type, bool normalized = false) {
    nlohmann::json entry = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (view >= 0) entry["bufferView"] = view;
    if (normalized) entry["normalized"] = true;
    doc["accessors"].push_back(entry);
    return int(doc["accessors"].size() - 1);
  }

  // One mesh of one primitive under one node (scaled by `scale`), the scene's only node.
  void primitive(const nlohmann::json& primitive, float scale = 1.0f) {
    doc["meshes"] = {{{"primitives", {primitive}}}};
    doc["nodes"] = {{{"mesh", 0}}};
    if (scale != 1.0f) doc["nodes"][0]["scale"] = {scale, scale, scale};
    doc["scenes"] = {{{"nodes", {0}}}};
  }

  void uses(const std::string& extension, bool required = true) {
    doc["extensionsUsed"].push_back(extension);
    if (required) doc["extensionsRequired"].push_back(extension);
  }

  // NAME.gltf with buffer 0 in NAME.bin beside it.
  fs::path writeGltf(const fs::path& file) const {
    nlohmann::json out = doc;
    const fs::path bin = fs::path(file).replace_extension(".bin");
    out["buffers"][0]["uri"] = bin.filename().string();
    out["buffers"][0]["byteLength"] = data_.size();
    std::ofstream(bin, std::ios::binary) << data_;
    std::ofstream(file, std::ios::binary) << out.dump();
    return file;
  }

  // A self-contained .glb: buffer 0 is its BIN chunk.
  fs::path writeGlb(const fs::path& file) const {
    nlohmann::json out = doc;
    out["buffers"][0]["byteLength"] = data_.size();
    std::string json = out.dump(), bin = data_;
    json += std::string((4 - json.size() % 4) % 4, ' ');
    bin += std::string((4 - bin.size() % 4) % 4, '\0');
    auto word = [](std::uint32_t value) { return bytesOf(&value, 4); };
    const std::string glb = "glTF" + word(2) + word(std::uint32_t(28 + json.size() + bin.size())) +
                            word(std::uint32_t(json.size())) + "JSON" + json + word(std::uint32_t(bin.size())) +
                            std::string("BIN\0", 4) + bin;
    std::ofstream(file, std::ios::binary) << glb;
    return file;
  }

  nlohmann::json doc;

 private:
  std::string data_;
};

// The grid as plain floats and 32-bit indices: the reference the compressed variants are held to.
inline nlohmann::json plainGridPrimitive(GltfBuilder& builder, const GridMesh& grid) {
  const std::size_t n = grid.vertexCount();
  return {{"attributes",
           {{"POSITION", builder.accessor(builder.view(bytesOf(grid.positions)), 5126, n, "VEC3")},
            {"NORMAL", builder.accessor(builder.view(bytesOf(grid.normals)), 5126, n, "VEC3")},
            {"TEXCOORD_0", builder.accessor(builder.view(bytesOf(grid.texCoords)), 5126, n, "VEC2")},
            {"TANGENT", builder.accessor(builder.view(bytesOf(grid.tangents)), 5126, n, "VEC4")}}},
          {"indices", builder.accessor(builder.view(bytesOf(grid.indices)), 5125, grid.indices.size(), "SCALAR")}};
}

// One triangle corner of a loaded scene's first object, its position in world space.
struct Corner {
  glm::vec3 position, normal;
  glm::vec2 texCoord{0.0f};
  glm::vec4 tangent{0.0f};
};
using Triangle = std::array<Corner, 3>;

// The first object's triangles, each rotated to start at its lowest corner (by position, to 1/100: grid points
// lie 1/4 apart), sorted: the same list for any vertex order or triangle rotation.
inline std::vector<Triangle> trianglesOf(const renderer::Scene& scene) {
  const renderer::Object& object = scene.objects.at(0);
  const renderer::Mesh& mesh = scene.meshes.at(object.mesh);
  auto key = [](const Corner& c) {
    return std::make_tuple(std::lround(c.position.x * 100), std::lround(c.position.y * 100), std::lround(c.position.z * 100));
  };
  std::vector<Triangle> triangles;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    Triangle t;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[i + k];
      t[k].position = glm::vec3(object.transform * glm::vec4(mesh.vertices[v].position, 1.0f));
      t[k].normal = mesh.vertices[v].normal;
      if (!mesh.texCoords.empty()) t[k].texCoord = mesh.texCoords[v];
      if (!mesh.tangents.empty()) t[k].tangent = mesh.tangents[v];
    }
    const auto lowest = std::min_element(t.begin(), t.end(), [&](const Corner& a, const Corner& b) { return key(a) < key(b); });
    std::rotate(t.begin(), lowest, t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end(), [&](const Triangle& a, const Triangle& b) {
    return std::make_tuple(key(a[0]), key(a[1]), key(a[2])) < std::make_tuple(key(b[0]), key(b[1]), key(b[2]));
  });
  return triangles;
}

struct Tolerances {
  float position = 0.0f, normal = 0.0f, texCoord = 0.0f, tangent = 0.0f;
};

inline float largestDifference(const glm::vec4& a, const glm::vec4& b) {
  const glm::vec4 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z, d.w});
}

// Every corner of `actual` within `tolerance` of `expected`'s, triangle by triangle.
inline void expectSameTriangles(const renderer::Scene& expected, const renderer::Scene& actual, const Tolerances& tolerance) {
  const std::vector<Triangle> a = trianglesOf(expected), b = trianglesOf(actual);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t t = 0; t < a.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Corner &x = a[t][k], &y = b[t][k];
      EXPECT_LE(largestDifference(glm::vec4(x.position, 0), glm::vec4(y.position, 0)), tolerance.position) << t << "/" << k;
      EXPECT_LE(largestDifference(glm::vec4(x.normal, 0), glm::vec4(y.normal, 0)), tolerance.normal) << t << "/" << k;
      EXPECT_LE(largestDifference(glm::vec4(x.texCoord, 0, 0), glm::vec4(y.texCoord, 0, 0)), tolerance.texCoord) << t << "/" << k;
      EXPECT_LE(largestDifference(x.tangent, y.tangent), tolerance.tangent) << t << "/" << k;
    }
}

}  // namespace s3d::test
