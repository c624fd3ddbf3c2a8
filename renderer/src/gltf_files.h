#pragma once
// The files a glTF scene reads: its JSON checked before tinygltf parses it, URIs and file callbacks held to the
// scene's folder, images held to the readers' limits and the scene's memory.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

namespace s3d::renderer::gltf {

std::string lowercase(std::string text);

// Largest glTF file, .bin buffer or image file a scene may name (a .gltf embeds its buffers as base64 text).
constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(2) << 30;

// A URI with its %XX escapes decoded.
std::string decodedUri(const std::string& uri);

// The JSON part of a .gltf or .glb, parsed with the nesting limit (s3d/json_document.h) before tinygltf's
// recursive reader sees it; null when a .glb's container is broken (tinygltf then reports why). Throws
// InputFileError naming the file when it cannot be read, is not JSON or nests too deep.
nlohmann::json gltfJson(const std::filesystem::path& file, bool binary);

// Names a required extension the renderer does not read before tinygltf parses the file: it reports their
// effects instead (a meshopt-compressed file's fallback buffer fails as "Invalid 'byteLength'").
void requireSupportedExtensions(const std::filesystem::path& file, const nlohmann::json& json);

// The extensions the file uses but does not require that the renderer does not read (safe to ignore, per glTF).
std::vector<std::string> ignoredExtensions(const nlohmann::json& json);

// Refuses buffer and image URIs that are absolute, climb out with "..", or lead out through a link.
void requireUrisInsideFolder(const std::filesystem::path& file, const std::filesystem::path& folder,
                             const nlohmann::json& json);

struct SceneFolderSandbox {
  std::filesystem::path folder;
};

// tinygltf file callbacks that read only regular files inside `sandbox`'s folder and write nothing.
tinygltf::FsCallbacks sandboxedFileCallbacks(SceneFolderSandbox& sandbox);

// tinygltf's image loader held to the readers' size limits and to the scene's memory (`memory`: SceneMemory*).
bool loadImageWithinLimits(tinygltf::Image* image, int index, std::string* error, std::string* warning,
                           int requestedWidth, int requestedHeight, const unsigned char* bytes, int size, void* memory);

}  // namespace s3d::renderer::gltf
