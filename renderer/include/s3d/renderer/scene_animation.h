#pragma once
// What poses a scene at a time t: the node hierarchy at rest, one animation's channels, skins, and the skinned
// meshes' bind-pose vertices with their joints and weights (glTF 2.0 skins and animations). Scene::animation
// holds it; scenes without it (every built-in scene, every static glTF file) are never touched by poseScene.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// A node of the hierarchy. Its local transform is translation * rotation * scale, or `matrix` when the file gave
// one (glTF forbids animating such a node).
struct SceneNode {
  std::string name;
  std::int32_t parent = -1;  // index into SceneAnimation::nodes, -1 for a root
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};
  std::optional<glm::mat4> matrix;
  std::vector<std::uint32_t> objects;  // the Scene::objects this node's mesh produced (not skinned ones)
};

enum class Interpolation : std::uint32_t { Linear, Step, CubicSpline };
enum class AnimatedProperty : std::uint32_t { Translation, Rotation, Scale };

// One animated property of one node. `times` strictly increase; `values` has one entry per time (vec3 in xyz or a
// quaternion as x, y, z, w), or three for CubicSpline: in-tangent, value, out-tangent.
struct AnimationChannel {
  std::uint32_t node = 0;
  AnimatedProperty property = AnimatedProperty::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // seconds
  std::vector<glm::vec4> values;
};

struct Skin {
  std::vector<std::uint32_t> joints;               // node indices
  std::vector<glm::mat4> inverseBindMatrices;      // one per joint
  std::int32_t skeleton = -1;                      // the file's skeleton root node (informative), -1: none
};

// A skinned mesh: Scene::meshes[mesh] is rewritten from `bindPose` each time the scene is posed, in world space
// (its object's transform is the identity). Up to eight joint influences per vertex, weights summing to 1.
struct SkinnedMesh {
  std::uint32_t mesh = 0;
  std::uint32_t skin = 0;
  std::uint32_t node = 0;  // the node the mesh hangs on: vertices no joint weighs follow it, as if unskinned
  Mesh bindPose;
  std::vector<std::array<std::uint32_t, 8>> joints;  // indices into the skin's joints (JOINTS_0, then JOINTS_1)
  std::vector<std::array<float, 8>> weights;         // WEIGHTS_0, WEIGHTS_1 (zeros where absent), normalized or all 0
};

struct SceneAnimation {
  std::vector<SceneNode> nodes;
  std::vector<std::uint32_t> order;  // every node after its parent: the order world transforms are composed in
  std::string animationName;
  std::vector<AnimationChannel> channels;  // the file's first animation (empty: the rest pose only)
  std::vector<Skin> skins;
  std::vector<SkinnedMesh> skinnedMeshes;

  // The animation's length: its channels' last key time (0 without channels). Time loops over it.
  double duration() const;
};

// A channel's value at `seconds` (not looped): before the first key the first value, after the last the last;
// Linear rotations are slerped along the shorter arc, CubicSpline ones normalized (glTF 2.0, appendix C).
glm::vec4 sampleChannel(const AnimationChannel& channel, float seconds);

// Every node's world transform at `seconds` (looped over the duration: seconds mod duration), parents first.
std::vector<glm::mat4> nodeWorldTransforms(const SceneAnimation& animation, double seconds);

// Linear blend skinning of one skinned mesh with the nodes' world transforms: positions by the blended matrix,
// normals by its inverse transpose, tangents' xyz by it (w kept), directions renormalized.
Mesh skinMesh(const SceneAnimation& animation, const SkinnedMesh& skinned, const std::vector<glm::mat4>& world);

// Poses `scene` at `seconds`: objects' transforms from their nodes, skinned meshes re-skinned. Frame N of a
// sequence is at N / frames-per-second. A scene without Scene::animation is left as it is, at no cost.
void poseScene(Scene& scene, double seconds);

}  // namespace s3d::renderer
