#pragma once
// A glTF file's node hierarchy, skins, skinned primitives and first animation as a SceneAnimation
// (scene_animation.h). The scene builder reports which objects each node produced and hands over skinned
// primitives; finish() reads the rest and checks it, every error naming the file and the element.
#include <cstdint>
#include <memory>
#include <vector>

#include <tiny_gltf.h>

#include "gltf_reader.h"
#include "s3d/renderer/scene_animation.h"

namespace s3d::renderer::gltf {

class AnimationBuilder {
 public:
  AnimationBuilder(const GltfReader& reader, const tinygltf::Model& model);

  // Scene objects [first, first + count) came from `node`'s mesh (their transforms follow the node).
  void addObjects(int node, std::uint32_t first, std::uint32_t count);

  // Primitive `primitive` of mesh `meshIndex`, placed by a node with skin `skin`, became Scene::meshes[sceneMesh]
  // with vertices `bindPose` (in the skin's bind space): reads its JOINTS_n and WEIGHTS_n.
  void addSkinnedPrimitive(int skin, int node, int meshIndex, std::size_t primitiveIndex, const tinygltf::Primitive& primitive,
                           std::uint32_t sceneMesh, const Mesh& bindPose);

  // Null for a file without skins and animations (a static scene); else the hierarchy, skins and animation.
  std::shared_ptr<const SceneAnimation> finish();

 private:
  void readNodes();
  void readSkins();
  void readAnimation();
  AnimationChannel readChannel(const tinygltf::Animation& animation, std::size_t c);

  const GltfReader& reader_;
  const tinygltf::Model& model_;
  std::vector<std::vector<std::uint32_t>> objects_;  // per node
  std::vector<SkinnedMesh> skinnedMeshes_;
  std::unique_ptr<SceneAnimation> animation_ = std::make_unique<SceneAnimation>();
};

}  // namespace s3d::renderer::gltf
