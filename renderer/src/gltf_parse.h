#pragma once
// Parsing a glTF file with tinygltf, after rewriting what tinygltf 2.7 cannot take as written: EXT_meshopt_compression's
// fallback buffers that hold no data (their views are decoded from another buffer, gltf_meshopt.h), draco-compressed
// primitives' index accessors without a buffer view (gltf_draco.h) and WebP images in data: URIs (tinygltf decodes
// only the MIME types it knows).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

namespace s3d::renderer::gltf {

// Parses `file` (`json`: its JSON part as gltfJson read it, null when unreadable) into `model`; false with
// tinygltf's `errors` when it cannot, or when an image's buffer view is not one of the file's or does not lie
// inside its buffer.
bool parseGltf(tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& errors, std::string& warnings,
               const std::filesystem::path& file, bool binary, const nlohmann::json& json);

}  // namespace s3d::renderer::gltf
