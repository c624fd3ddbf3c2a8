// Posing a scene at a time (scene_animation.h): glTF 2.0 animation sampling (appendix C of the specification),
// the node hierarchy's world transforms, and linear blend skinning on the CPU. This is the reference a GPU
// skinning pass would be held to.
#include "s3d/renderer/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace s3d::renderer {
namespace {

glm::quat asQuat(const glm::vec4& v) { return glm::quat(v.w, v.x, v.y, v.z); }
glm::vec4 asVec4(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }

// The cubic Hermite spline between key k and k+1 at s in [0, 1] over an interval of `span` seconds.
glm::vec4 hermite(const AnimationChannel& c, std::size_t k, float s, float span) {
  const glm::vec4& v0 = c.values[3 * k + 1];
  const glm::vec4 b0 = c.values[3 * k + 2] * span;  // out-tangent of key k
  const glm::vec4& v1 = c.values[3 * (k + 1) + 1];
  const glm::vec4 a1 = c.values[3 * (k + 1)] * span;  // in-tangent of key k+1
  const float s2 = s * s, s3 = s2 * s;
  return (2.0f * s3 - 3.0f * s2 + 1.0f) * v0 + (s3 - 2.0f * s2 + s) * b0 + (-2.0f * s3 + 3.0f * s2) * v1 +
         (s3 - s2) * a1;
}

glm::vec4 keyValue(const AnimationChannel& c, std::size_t k) {
  return c.interpolation == Interpolation::CubicSpline ? c.values[3 * k + 1] : c.values[k];
}

glm::mat4 localTransform(const SceneNode& node) {
  if (node.matrix) return *node.matrix;
  return glm::translate(glm::mat4(1.0f), node.translation) * glm::mat4_cast(node.rotation) *
         glm::scale(glm::mat4(1.0f), node.scale);
}

}  // namespace

double SceneAnimation::duration() const {
  double longest = 0.0;
  for (const AnimationChannel& channel : channels)
    if (!channel.times.empty()) longest = std::max(longest, double(channel.times.back()));
  return longest;
}

glm::vec4 sampleChannel(const AnimationChannel& c, float seconds) {
  const std::vector<float>& t = c.times;
  if (t.empty()) throw std::invalid_argument("sampleChannel: the channel has no keys");
  if (seconds <= t.front()) return keyValue(c, 0);
  if (seconds >= t.back()) return keyValue(c, t.size() - 1);
  // The key interval [t[k], t[k+1]) holding `seconds`.
  const std::size_t k = std::size_t(std::upper_bound(t.begin(), t.end(), seconds) - t.begin()) - 1;
  const float span = t[k + 1] - t[k];
  const float s = (seconds - t[k]) / span;
  const bool rotation = c.property == AnimatedProperty::Rotation;
  switch (c.interpolation) {
    case Interpolation::Step: return c.values[k];
    case Interpolation::CubicSpline: {
      const glm::vec4 v = hermite(c, k, s, span);
      return rotation ? asVec4(glm::normalize(asQuat(v))) : v;
    }
    case Interpolation::Linear: break;
  }
  if (rotation) return asVec4(glm::slerp(asQuat(c.values[k]), asQuat(c.values[k + 1]), s));  // shorter arc
  return glm::mix(c.values[k], c.values[k + 1], s);
}

std::vector<glm::mat4> nodeWorldTransforms(const SceneAnimation& animation, double seconds) {
  std::vector<SceneNode> nodes = animation.nodes;  // rest pose, overridden by the channels below
  const double duration = animation.duration();
  const double looped = duration > 0.0 && seconds > 0.0 ? std::fmod(seconds, duration) : 0.0;
  for (const AnimationChannel& channel : animation.channels) {
    SceneNode& node = nodes.at(channel.node);
    const glm::vec4 value = sampleChannel(channel, float(looped));
    switch (channel.property) {
      case AnimatedProperty::Translation: node.translation = glm::vec3(value); break;
      case AnimatedProperty::Rotation: node.rotation = glm::normalize(asQuat(value)); break;
      case AnimatedProperty::Scale: node.scale = glm::vec3(value); break;
    }
  }
  std::vector<glm::mat4> world(nodes.size(), glm::mat4(1.0f));
  for (std::uint32_t n : animation.order) {
    const glm::mat4 local = localTransform(nodes[n]);
    world[n] = nodes[n].parent < 0 ? local : world[std::size_t(nodes[n].parent)] * local;
  }
  return world;
}

Mesh skinMesh(const SceneAnimation& animation, const SkinnedMesh& skinned, const std::vector<glm::mat4>& world) {
  const Skin& skin = animation.skins.at(skinned.skin);
  std::vector<glm::mat4> jointMatrices(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    jointMatrices[j] = world.at(skin.joints[j]) * skin.inverseBindMatrices[j];
  Mesh mesh = skinned.bindPose;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    glm::mat4 blended(0.0f);
    bool weighed = false;
    for (std::size_t i = 0; i < 8; ++i)
      if (skinned.weights[v][i] != 0.0f) {
        blended += skinned.weights[v][i] * jointMatrices[skinned.joints[v][i]];
        weighed = true;
      }
    if (!weighed) blended = world.at(skinned.node);  // no joint weighs it
    Vertex& vertex = mesh.vertices[v];
    vertex.position = glm::vec3(blended * glm::vec4(vertex.position, 1.0f));
    const glm::mat3 linear(blended);
    const glm::vec3 normal = glm::transpose(glm::inverse(linear)) * vertex.normal;
    if (glm::length(normal) > 0.0f && std::isfinite(normal.x + normal.y + normal.z)) vertex.normal = glm::normalize(normal);
    if (!mesh.tangents.empty()) {
      const glm::vec3 tangent = linear * glm::vec3(mesh.tangents[v]);
      if (glm::length(tangent) > 0.0f) mesh.tangents[v] = glm::vec4(glm::normalize(tangent), mesh.tangents[v].w);
    }
  }
  return mesh;
}

void poseScene(Scene& scene, double seconds) {
  if (!scene.animation) return;
  const SceneAnimation& animation = *scene.animation;
  const std::vector<glm::mat4> world = nodeWorldTransforms(animation, seconds);
  for (std::size_t n = 0; n < animation.nodes.size(); ++n)
    for (std::uint32_t object : animation.nodes[n].objects) scene.objects.at(object).transform = world[n];
  for (const SkinnedMesh& skinned : animation.skinnedMeshes) scene.meshes.at(skinned.mesh) = skinMesh(animation, skinned, world);
}

}  // namespace s3d::renderer
