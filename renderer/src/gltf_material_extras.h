#pragma once
// The parts of a glTF material beyond metallic-roughness that the renderer draws: alpha cut-outs (alphaMode
// MASK), doubleSided, KHR_texture_transform on the base-colour and normal textures, and emission
// (emissiveFactor x KHR_materials_emissive_strength). Errors name the file and the material.
#include <string>

#include <tiny_gltf.h>

#include "gltf_reader.h"
#include "s3d/renderer/scene.h"

namespace s3d::renderer::gltf {

// Reads those fields of `source` into `material`. `where` names the material ("material 3 ('leaves')");
// `baseAlpha` is its baseColorFactor's alpha.
void readMaterialExtras(const GltfReader& reader, const tinygltf::Material& source, const std::string& where,
                        float baseAlpha, Material& material);

// A textureInfo's KHR_texture_transform (the identity without one). `role` names the texture ("base color").
TextureTransform readTextureTransform(const GltfReader& reader, const tinygltf::ExtensionMap& extensions,
                                      const std::string& where, const std::string& role);

}  // namespace s3d::renderer::gltf
