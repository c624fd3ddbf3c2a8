#pragma once
// A tiny skinned, animated glTF written by test code: a two-bone arm. A strip in the XY plane from x = 0 to 2
// (y = +-0.1, normal +Z); the shoulder joint at the origin, the elbow joint at x = 1 (its child). Vertices at x = 0
// follow the shoulder, at x = 2 the elbow, at x = 1 both by half. The first animation:
//   elbow rotation, LINEAR: 0 s identity, 1 s 90 degrees about +Z, 2 s identity;
//   shoulder translation, CUBICSPLINE: 0 s and 2 s at the origin, out-tangent (0, 1, 0) at 0 s and in-tangent
//     (0, -1, 0) at 2 s: y(t) = 2 s (1 - s) with s = t / 2 (the Hermite curve);
//   shoulder scale, STEP: 1 until 1.5 s, then 0.5.
// Bad-data tests edit the arrays before writing.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace s3d::test {

struct SkinnedArm {
  std::vector<float> positions{0, -0.1f, 0, 0, 0.1f, 0, 1, -0.1f, 0, 1, 0.1f, 0, 2, -0.1f, 0, 2, 0.1f, 0};
  std::vector<float> normals = std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  std::vector<std::uint8_t> joints{0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  std::vector<float> weights{1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  std::vector<std::uint16_t> indices{0, 2, 1, 1, 2, 3, 2, 4, 3, 3, 4, 5};
  // Column-major: the shoulder's identity, the elbow's translation by (-1, 0, 0).
  std::vector<float> inverseBindMatrices{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                         1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1};
  std::vector<float> rotationTimes{0, 1, 2};
  std::vector<float> rotations{0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f, 0, 0, 0, 1};  // x, y, z, w
  std::vector<float> translationTimes{0, 2};
  std::vector<float> translations{0, 0, 0, 0, 0, 0, 0, 1, 0,    // key 0: in, value, out
                                  0, -1, 0, 0, 0, 0, 0, 0, 0};  // key 1
  std::vector<float> scaleTimes{0, 1.5f};
  std::vector<float> scales{1, 1, 1, 0.5f, 0.5f, 0.5f};

  // Writes NAME.gltf and NAME.bin into `folder`; returns the .gltf.
  std::filesystem::path write(const std::filesystem::path& folder, const std::string& name = "arm") const {
    std::vector<unsigned char> bin;
    nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array();
    auto add = [&](const auto& values, int componentType, const char* type, std::size_t components) {
      while (bin.size() % 4) bin.push_back(0);
      const std::size_t offset = bin.size(), bytes = values.size() * sizeof(values[0]);
      bin.resize(offset + bytes);
      std::memcpy(bin.data() + offset, values.data(), bytes);
      views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
      accessors.push_back({{"bufferView", views.size() - 1}, {"componentType", componentType},
                           {"count", values.size() / components}, {"type", type}});
      return int(accessors.size() - 1);
    };
    const int position = add(positions, 5126, "VEC3", 3);
    accessors[std::size_t(position)]["min"] = {0, -0.1, 0};
    accessors[std::size_t(position)]["max"] = {2, 0.1, 0};
    const int normal = add(normals, 5126, "VEC3", 3), joint = add(joints, 5121, "VEC4", 4);
    const int weight = add(weights, 5126, "VEC4", 4), index = add(indices, 5123, "SCALAR", 1);
    const int ibm = add(inverseBindMatrices, 5126, "MAT4", 16);
    auto sampler = [&](const std::vector<float>& times, const std::vector<float>& values, const char* type,
                       std::size_t components, const char* interpolation) {
      const int input = add(times, 5126, "SCALAR", 1);
      return nlohmann::json{{"input", input}, {"output", add(values, 5126, type, components)},
                            {"interpolation", interpolation}};
    };
    nlohmann::json samplers = {sampler(rotationTimes, rotations, "VEC4", 4, "LINEAR"),
                               sampler(translationTimes, translations, "VEC3", 3, "CUBICSPLINE"),
                               sampler(scaleTimes, scales, "VEC3", 3, "STEP")};
    nlohmann::json channels = {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}},
                               {{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}},
                               {{"sampler", 2}, {"target", {{"node", 1}, {"path", "scale"}}}}};
    nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1}}}}},
        {"nodes",
         {{{"name", "arm"}, {"mesh", 0}, {"skin", 0}},
          {{"name", "shoulder"}, {"children", {2}}},
          {{"name", "elbow"}, {"translation", {1, 0, 0}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"JOINTS_0", joint},
                                                        {"WEIGHTS_0", weight}}},
                                      {"indices", index}}}}}}},
        {"skins", {{{"name", "arm skin"}, {"joints", {1, 2}}, {"inverseBindMatrices", ibm}, {"skeleton", 1}}}},
        {"animations", {{{"name", "wave"}, {"samplers", samplers}, {"channels", channels}}}},
        {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}},
        {"bufferViews", views},
        {"accessors", accessors}};
    std::ofstream(folder / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    std::ofstream(folder / (name + ".gltf"), std::ios::binary) << gltf.dump(1);
    return folder / (name + ".gltf");
  }
};

}  // namespace s3d::test
