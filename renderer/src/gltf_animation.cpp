// glTF 2.0 skins and animation read into a SceneAnimation (gltf_animation.h). Only the file's first animation is
// read; channels animating morph target weights are skipped (morph targets themselves are refused).
#include "gltf_animation.h"

#include <cmath>
#include <cstring>
#include <string>

#include <glm/gtc/type_ptr.hpp>

namespace s3d::renderer::gltf {
namespace {

std::string nodeName(int index, const tinygltf::Model& model) {
  return "node " + std::to_string(index) + named(model.nodes[std::size_t(index)].name);
}

}  // namespace

AnimationBuilder::AnimationBuilder(const GltfReader& reader, const tinygltf::Model& model)
    : reader_(reader), model_(model), objects_(model.nodes.size()) {}

void AnimationBuilder::addObjects(int node, std::uint32_t first, std::uint32_t count) {
  for (std::uint32_t i = 0; i < count; ++i) objects_.at(std::size_t(node)).push_back(first + i);
}

void AnimationBuilder::addSkinnedPrimitive(int skin, int node, int meshIndex, std::size_t primitiveIndex,
                                           const tinygltf::Primitive& primitive, std::uint32_t sceneMesh,
                                           const Mesh& bindPose) {
  const std::string where = "mesh " + std::to_string(meshIndex) + named(model_.meshes[std::size_t(meshIndex)].name) +
                            " primitive " + std::to_string(primitiveIndex) + "'s ";
  if (skin < 0 || std::size_t(skin) >= model_.skins.size()) reader_.corrupt("skin " + std::to_string(skin) + " does not exist");
  const std::size_t jointCount = model_.skins[std::size_t(skin)].joints.size();
  const std::size_t vertexCount = bindPose.vertices.size();
  // The bind pose kept beside the posed mesh, and eight joints and weights per vertex.
  reader_.allocationFor<unsigned char>(vertexCount * (sizeof(Vertex) + 64) + bindPose.indices.size() * 4 +
                                           bindPose.texCoords.size() * sizeof(glm::vec2) +
                                           bindPose.tangents.size() * sizeof(glm::vec4),
                                       where + "skinning");
  SkinnedMesh skinned{sceneMesh, std::uint32_t(skin), std::uint32_t(node), bindPose, {}, {}};
  skinned.joints.assign(vertexCount, {});
  skinned.weights.assign(vertexCount, {});
  for (int set = 0; set < 2; ++set) {
    const std::string jointsName = "JOINTS_" + std::to_string(set), weightsName = "WEIGHTS_" + std::to_string(set);
    const auto joints = primitive.attributes.find(jointsName), weights = primitive.attributes.find(weightsName);
    if (joints == primitive.attributes.end() && weights == primitive.attributes.end() && set > 0) break;
    if (joints == primitive.attributes.end() || weights == primitive.attributes.end())
      reader_.corrupt(where + jointsName + " and " + weightsName + " are not both present (its node has skin " +
                      std::to_string(skin) + ")");
    const std::vector<std::uint32_t> j = reader_.readUnsigned(joints->second, TINYGLTF_TYPE_VEC4, where + jointsName);
    const std::vector<float> w = reader_.readFloats(weights->second, TINYGLTF_TYPE_VEC4, (where + weightsName).c_str());
    if (j.size() != 4 * vertexCount || w.size() != 4 * vertexCount)
      reader_.corrupt(where + jointsName + " or " + weightsName + " has a different vertex count than POSITION");
    for (std::size_t v = 0; v < vertexCount; ++v)
      for (std::size_t i = 0; i < 4; ++i) {
        if (j[4 * v + i] >= jointCount)
          reader_.corrupt(where + jointsName + " names joint " + std::to_string(j[4 * v + i]) + " at vertex " +
                          std::to_string(v) + ", but skin " + std::to_string(skin) + " has " +
                          std::to_string(jointCount) + " joints");
        if (!(w[4 * v + i] >= 0.0f))
          reader_.corrupt(where + weightsName + " has a negative weight at vertex " + std::to_string(v));
        skinned.joints[v][4 * std::size_t(set) + i] = j[4 * v + i];
        skinned.weights[v][4 * std::size_t(set) + i] = w[4 * v + i];
      }
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    float sum = 0.0f;
    for (float weight : skinned.weights[v]) sum += weight;
    if (!std::isfinite(sum)) reader_.corrupt(where + "weights at vertex " + std::to_string(v) + " sum past float's range");
    if (sum == 0.0f) continue;  // no joint moves it (exporters leave such vertices): it follows its node (skinMesh)
    for (float& weight : skinned.weights[v]) weight /= sum;
  }
  skinnedMeshes_.push_back(std::move(skinned));
}

std::shared_ptr<const SceneAnimation> AnimationBuilder::finish() {
  if (model_.animations.empty() && skinnedMeshes_.empty()) return nullptr;
  readNodes();
  readSkins();
  readAnimation();
  animation_->skinnedMeshes = std::move(skinnedMeshes_);
  return std::move(animation_);
}

void AnimationBuilder::readNodes() {
  std::vector<SceneNode>& nodes = animation_->nodes;
  nodes.resize(model_.nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const tinygltf::Node& source = model_.nodes[n];
    SceneNode& node = nodes[n];
    node.name = source.name;
    node.objects = objects_[n];
    const std::string where = nodeName(int(n), model_) + "'s ";
    if (source.matrix.size() == 16) {
      glm::mat4 m;
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = reader_.toFloat(source.matrix[std::size_t(i)], where + "matrix");
      node.matrix = m;
    }
    if (source.translation.size() == 3)
      for (int i = 0; i < 3; ++i) node.translation[i] = reader_.toFloat(source.translation[std::size_t(i)], where + "translation");
    if (source.scale.size() == 3)
      for (int i = 0; i < 3; ++i) node.scale[i] = reader_.toFloat(source.scale[std::size_t(i)], where + "scale");
    if (source.rotation.size() == 4) {
      glm::vec4 q;
      for (int i = 0; i < 4; ++i) q[i] = reader_.toFloat(source.rotation[std::size_t(i)], where + "rotation");
      node.rotation = glm::quat(q.w, q.x, q.y, q.z);
    }
    for (int child : source.children) {
      if (child < 0 || std::size_t(child) >= nodes.size()) reader_.corrupt("node " + std::to_string(child) + " does not exist");
      if (nodes[std::size_t(child)].parent >= 0)
        reader_.corrupt(nodeName(child, model_) + " has two parents (glTF node hierarchies are trees)");
      nodes[std::size_t(child)].parent = std::int32_t(n);
    }
  }
  // Parents before children: from every root down. A node never reached lies on a cycle.
  std::vector<std::uint32_t>& order = animation_->order;
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (nodes[n].parent < 0) order.push_back(std::uint32_t(n));
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int child : model_.nodes[order[i]].children) order.push_back(std::uint32_t(child));
  if (order.size() != nodes.size()) reader_.corrupt("its node hierarchy has a cycle");
}

void AnimationBuilder::readSkins() {
  for (std::size_t s = 0; s < model_.skins.size(); ++s) {
    const tinygltf::Skin& source = model_.skins[s];
    const std::string name = "skin " + std::to_string(s) + named(source.name);
    Skin skin;
    skin.skeleton = source.skeleton;
    if (source.joints.empty()) reader_.corrupt(name + " has no joints");
    for (int joint : source.joints) {
      if (joint < 0 || std::size_t(joint) >= model_.nodes.size())
        reader_.corrupt(name + "'s joint node " + std::to_string(joint) + " does not exist");
      skin.joints.push_back(std::uint32_t(joint));
    }
    skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
    if (source.inverseBindMatrices >= 0) {
      const std::string what = name + "'s inverseBindMatrices";
      const std::vector<float> m = reader_.readFloats(source.inverseBindMatrices, TINYGLTF_TYPE_MAT4, what.c_str());
      if (m.size() != 16 * skin.joints.size())
        reader_.corrupt(what + " hold " + std::to_string(m.size() / 16) + " matrices for its " +
                        std::to_string(skin.joints.size()) + " joints");
      for (std::size_t j = 0; j < skin.joints.size(); ++j)
        std::memcpy(glm::value_ptr(skin.inverseBindMatrices[j]), &m[16 * j], sizeof(float) * 16);  // column-major
    }
    animation_->skins.push_back(std::move(skin));
  }
}

void AnimationBuilder::readAnimation() {
  if (model_.animations.empty()) return;
  const tinygltf::Animation& animation = model_.animations.front();
  animation_->animationName = animation.name;
  for (std::size_t c = 0; c < animation.channels.size(); ++c) {
    const std::string& path = animation.channels[c].target_path;
    if (path == "weights") continue;  // morph target weights: meshes with morph targets are refused
    if (animation.channels[c].target_node < 0) continue;  // a target given by an extension this reader skips
    animation_->channels.push_back(readChannel(animation, c));
  }
}

AnimationChannel AnimationBuilder::readChannel(const tinygltf::Animation& animation, std::size_t c) {
  const tinygltf::AnimationChannel& source = animation.channels[c];
  const std::string name = "animation 0" + named(animation.name) + " channel " + std::to_string(c);
  AnimationChannel channel;
  if (std::size_t(source.target_node) >= model_.nodes.size())
    reader_.corrupt(name + " targets node " + std::to_string(source.target_node) + ", which does not exist");
  channel.node = std::uint32_t(source.target_node);
  if (model_.nodes[channel.node].matrix.size() == 16)
    reader_.corrupt(name + " animates " + nodeName(source.target_node, model_) + ", which is given as a matrix");
  int type = TINYGLTF_TYPE_VEC3;
  if (source.target_path == "translation") channel.property = AnimatedProperty::Translation;
  else if (source.target_path == "scale") channel.property = AnimatedProperty::Scale;
  else if (source.target_path == "rotation") channel.property = AnimatedProperty::Rotation, type = TINYGLTF_TYPE_VEC4;
  else reader_.unsupported(name + "'s target path '" + source.target_path + "'");
  if (source.sampler < 0 || std::size_t(source.sampler) >= animation.samplers.size())
    reader_.corrupt(name + "'s sampler " + std::to_string(source.sampler) + " does not exist");
  const tinygltf::AnimationSampler& sampler = animation.samplers[std::size_t(source.sampler)];
  const std::string samplerName = "animation 0" + named(animation.name) + " sampler " + std::to_string(source.sampler);
  if (sampler.interpolation == "LINEAR") channel.interpolation = Interpolation::Linear;
  else if (sampler.interpolation == "STEP") channel.interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE") channel.interpolation = Interpolation::CubicSpline;
  else reader_.corrupt(samplerName + "'s interpolation '" + sampler.interpolation + "' is not LINEAR, STEP or CUBICSPLINE");
  channel.times = reader_.readFloats(sampler.input, TINYGLTF_TYPE_SCALAR, (samplerName + "'s input").c_str());
  if (channel.times.empty()) reader_.corrupt(samplerName + "'s input has no key times");
  for (std::size_t k = 1; k < channel.times.size(); ++k)
    if (!(channel.times[k] > channel.times[k - 1]))
      reader_.corrupt(samplerName + "'s input times do not increase at key " + std::to_string(k));
  const std::vector<float> values = reader_.readFloats(sampler.output, type, (samplerName + "'s output").c_str());
  const std::size_t components = type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
  const std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
  if (values.size() != channel.times.size() * perKey * components)
    reader_.corrupt(samplerName + "'s output holds " + std::to_string(values.size() / components) + " values for " +
                    std::to_string(channel.times.size()) + " key times" + (perKey == 3 ? " (CUBICSPLINE: 3 per key)" : ""));
  for (std::size_t i = 0; i < values.size() / components; ++i) {
    glm::vec4 value(0.0f);
    for (std::size_t k = 0; k < components; ++k) value[int(k)] = values[components * i + k];
    if (channel.property == AnimatedProperty::Rotation && perKey * (i / perKey) + perKey / 2 == i &&
        !(glm::length(value) > 0.0f))
      reader_.corrupt(samplerName + "'s output rotation " + std::to_string(i / perKey) + " is not a unit quaternion");
    channel.values.push_back(value);
  }
  return channel;
}

}  // namespace s3d::renderer::gltf
