#include "gltf_material_extras.h"

#include <cmath>

namespace s3d::renderer::gltf {
namespace {

// A number of an extension object, or `fallback` when the key is absent.
double numberOr(const GltfReader& reader, const tinygltf::Value& object, const char* key, double fallback,
                const std::string& what) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsNumber()) reader.corrupt(what + " is not a number");
  return value.GetNumberAsDouble();
}

// A two-number array of an extension object, or `fallback` when the key is absent.
glm::vec2 pairOr(const GltfReader& reader, const tinygltf::Value& object, const char* key, glm::vec2 fallback,
                 const std::string& what) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsArray() || value.ArrayLen() != 2 || !value.Get(0).IsNumber() || !value.Get(1).IsNumber())
    reader.corrupt(what + " is not an array of two numbers");
  return {reader.toFloat(value.Get(0).GetNumberAsDouble(), what), reader.toFloat(value.Get(1).GetNumberAsDouble(), what)};
}

}  // namespace

TextureTransform readTextureTransform(const GltfReader& reader, const tinygltf::ExtensionMap& extensions,
                                      const std::string& where, const std::string& role) {
  TextureTransform transform;
  const auto found = extensions.find("KHR_texture_transform");
  if (found == extensions.end()) return transform;
  const tinygltf::Value& object = found->second;
  const std::string what = where + "'s " + role + " texture transform";
  if (!object.IsObject()) reader.corrupt(what + " is not an object");
  transform.offset = pairOr(reader, object, "offset", transform.offset, what + " offset");
  transform.scale = pairOr(reader, object, "scale", transform.scale, what + " scale");
  transform.rotation = reader.toFloat(numberOr(reader, object, "rotation", 0.0, what + " rotation"), what + " rotation");
  // texCoord overrides the texture's set: only TEXCOORD_0 exists in the renderer's meshes.
  const double texCoord = numberOr(reader, object, "texCoord", 0.0, what + " texCoord");
  if (texCoord != 0.0) reader.unsupported(what + " on TEXCOORD_" + std::to_string(std::llround(texCoord)));
  return transform;
}

void readMaterialExtras(const GltfReader& reader, const tinygltf::Material& source, const std::string& where,
                        float baseAlpha, Material& material) {
  if (source.alphaMode == "MASK") {
    // glTF: alphaCutoff >= 0 (default 0.5). A cutoff of 0 keeps every fragment, as the renderer's "none" does.
    const float cutoff = reader.toFloat(source.alphaCutoff, where + "'s alphaCutoff");
    if (!(cutoff >= 0.0f)) reader.corrupt(where + "'s alphaCutoff " + std::to_string(cutoff) + " is negative");
    // Above 1 no coverage alpha passes: the same as 1 for alphas in 0..1 below it, i.e. almost nothing drawn.
    material.alphaCutoff = std::fmin(cutoff, 1.0f);
    material.cutoutAlpha = std::fmin(std::fmax(baseAlpha, 0.0f), 1.0f);
  }
  material.doubleSided = source.doubleSided;
  glm::vec3 emissive(0.0f);
  if (source.emissiveFactor.size() == 3)
    for (int c = 0; c < 3; ++c)
      emissive[c] = reader.toFloat(source.emissiveFactor[std::size_t(c)], where + "'s emissiveFactor");
  float strength = 1.0f;
  if (const auto found = source.extensions.find("KHR_materials_emissive_strength"); found != source.extensions.end())
    strength = reader.toFloat(numberOr(reader, found->second, "emissiveStrength", 1.0, where + "'s emissiveStrength"),
                              where + "'s emissiveStrength");
  emissive *= strength;
  for (int c = 0; c < 3; ++c)
    if (!(emissive[c] >= 0.0f && std::isfinite(emissive[c])))
      reader.corrupt(where + "'s emission (emissiveFactor x emissiveStrength) is negative or not finite");
  material.emissive = emissive;
}

}  // namespace s3d::renderer::gltf
