#include "gltf_files.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include <stb/stb_image.h>  // the header only: stbi_info_from_memory sizes a texture before tinygltf decodes it

#include "gltf_reader.h"
#include "gltf_webp.h"
#include "s3d/image_limits.h"
#include "s3d/input_file.h"
#include "s3d/json_document.h"
#include "s3d/png_chunks.h"

namespace s3d::renderer::gltf {
namespace fs = std::filesystem;

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// A scene file may read only files inside its own folder: URIs that are absolute, climb out with "..", or
// lead out through a link are refused before tinygltf follows them, and the file callbacks refuse anything
// outside the folder (tinygltf also searches the working directory).
std::string decodedUri(const std::string& uri) {
  std::string decoded;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return decoded;
}

namespace {

bool isInside(const fs::path& folder, const fs::path& path) {
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(path, error);
  if (error) return false;
  const fs::path relative = resolved.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

}  // namespace

nlohmann::json gltfJson(const fs::path& file, bool binary) {
  std::string bytes = readInputFile(file, "glTF file", kMaxSceneFileBytes);
  if (binary) {
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return nullptr;
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    if (length > bytes.size() - 20) return nullptr;
    bytes = bytes.substr(20, length);
  }
  return parseJsonDocument(bytes, "glTF file '" + file.string() + "'");
}

namespace {

// Extensions the renderer reads; any other required one is refused by name.
constexpr const char* kReadExtensions[] = {"KHR_lights_punctual", "KHR_mesh_quantization", "EXT_meshopt_compression",
                                          "KHR_draco_mesh_compression", "EXT_texture_webp", "KHR_texture_transform",
                                          "KHR_materials_emissive_strength"};

}  // namespace

void requireSupportedExtensions(const fs::path& file, const nlohmann::json& json) {
  const auto required = json.find("extensionsRequired");
  if (required == json.end() || !required->is_array()) return;
  for (const nlohmann::json& extension : *required) {
    if (!extension.is_string()) continue;
    const std::string name = extension.get<std::string>();
    if (std::find(std::begin(kReadExtensions), std::end(kReadExtensions), name) != std::end(kReadExtensions)) continue;
    std::string read;
    for (const char* known : kReadExtensions) read += (read.empty() ? "" : ", ") + std::string(known);
    throw std::invalid_argument("glTF file '" + file.string() + "': the required extension '" + name +
                                "' is not supported (s3d reads " + read + ")");
  }
}

std::vector<std::string> ignoredExtensions(const nlohmann::json& json) {
  std::vector<std::string> ignored;
  const auto used = json.find("extensionsUsed");
  if (used == json.end() || !used->is_array()) return ignored;
  for (const nlohmann::json& extension : *used)
    if (extension.is_string() &&
        std::find(std::begin(kReadExtensions), std::end(kReadExtensions), extension.get<std::string>()) ==
            std::end(kReadExtensions))
      ignored.push_back(extension.get<std::string>());
  return ignored;
}

void requireUrisInsideFolder(const fs::path& file, const fs::path& folder, const nlohmann::json& json) {
  for (const char* kind : {"buffers", "images"}) {
    const auto list = json.find(kind);
    if (list == json.end() || !list->is_array()) continue;
    for (std::size_t index = 0; index < list->size(); ++index) {
      const nlohmann::json& entry = (*list)[index];
      if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
      const std::string uri = entry["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::string decoded = decodedUri(uri);
      const bool hasScheme = decoded.find(':') != std::string::npos;
      std::string problem;
      if (decoded.empty()) problem = "is empty";
      else if (decoded.front() == '/' || decoded.front() == '\\' || hasScheme) problem = "is an absolute path";
      else if (const fs::path normal = fs::path(decoded).lexically_normal(); !normal.empty() && *normal.begin() == "..")
        problem = "climbs out of the scene's folder";
      else if (!isInside(folder, folder / decoded)) problem = "leads out of the scene's folder through a link";
      if (!problem.empty())
        throw std::invalid_argument("glTF file '" + file.string() + "': " + std::string(kind).substr(0, std::strlen(kind) - 1) +
                                    " " + std::to_string(index) + " URI '" + uri + "' " + problem +
                                    "; a scene may only use files in its own folder");
    }
  }
}

namespace {

bool fileExistsInside(const std::string& path, void* sandbox) {
  std::error_code error;
  return isInside(static_cast<SceneFolderSandbox*>(sandbox)->folder, path) && fs::is_regular_file(path, error);
}

std::string expandNothing(const std::string& path, void*) { return path; }  // no "~" or shell expansion

bool readWholeFileInside(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* sandbox) {
  if (!fileExistsInside(path, sandbox)) {
    if (error) *error += "file '" + path + "' is not in the scene's folder\n";
    return false;
  }
  try {
    const std::string bytes = readInputFile(path, "file", kMaxSceneFileBytes);
    if (bytes.empty()) {  // tinygltf indexes the first bytes without checking
      if (error) *error += "file '" + path + "' is empty\n";
      return false;
    }
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputFileError& failure) {
    if (error) *error += std::string(failure.what()) + "\n";
    return false;
  }
}

bool writeNothing(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
  if (error) *error += "scene loading writes no files\n";
  return false;
}

// Why stb_image must not decode a texture that is not WebP (empty when it may). glTF textures are PNG or JPEG:
// stb_image's other decoders (GIF, PSD, PIC, TGA, ...) are code a scene has no use for, so hostile bytes never
// reach them. A PNG's chunks must fit in its bytes (s3d/png_chunks.h: stb_image allocates what they declare first).
std::string stbTextureProblem(std::string_view bytes) {
  if (hasPngSignature(bytes)) {
    const auto overrun = pngChunkOverrun(bytes);
    return overrun ? "is a corrupt PNG: " + overrun->describe("image") : "";
  }
  if (bytes.substr(0, 3) == "\xff\xd8\xff") return "";  // a JPEG's start-of-image marker and the next marker's byte
  if (bytes.size() >= 12 && bytes.substr(0, 4) == "RIFF" && bytes.substr(8, 4) == "WEBP")
    return "is a WebP file whose header does not read";
  return "is neither a PNG, a JPEG nor a WebP file (the formats a glTF texture may have)";
}

}  // namespace

// Every texture is held to the readers' size limits (s3d/image_limits.h) before it is decoded: a PNG of a few
// hundred bytes can declare 20000x20000 pixels, 1.6 GB decoded (6 GB was measured through the renderer).
// The decoded pixels count against the scene's memory (SceneMemory) the same way, before decoding. WebP
// (EXT_texture_webp) is told apart by its bytes and decoded with libwebp, PNG and JPEG by tinygltf's stb_image.
bool loadImageWithinLimits(tinygltf::Image* image, const int index, std::string* error, std::string* warning,
                           int requestedWidth, int requestedHeight, const unsigned char* bytes, int size, void* memory) {
  int width = 0, height = 0, channels = 0;
  const bool webp = webpInfo(bytes, size, width, height);
  if (!webp) {
    const std::string problem =
        stbTextureProblem(std::string_view(reinterpret_cast<const char*>(bytes), std::size_t(std::max(size, 0))));
    if (!problem.empty()) {
      if (error) *error += "image " + std::to_string(index) + " " + problem + "\n";
      return false;
    }
  }
  if ((webp || stbi_info_from_memory(bytes, size, &width, &height, &channels) != 0) &&
      (std::uint32_t(width) > kMaxImageSide || std::uint32_t(height) > kMaxImageSide ||
       std::uint64_t(width) * std::uint64_t(height) > kMaxImagePixels)) {
    if (error)
      *error += "image " + std::to_string(index) + " is " + std::to_string(width) + "x" + std::to_string(height) +
                ", beyond the readers' limit of " + std::to_string(kMaxImageSide) + " pixels a side and " +
                std::to_string(kMaxImagePixels) + " pixels in all\n";
    return false;
  }
  auto& sceneMemory = *static_cast<SceneMemory*>(memory);
  const std::uint64_t bytesPerChannel = !webp && stbi_is_16_bit_from_memory(bytes, size) ? 2 : 1;
  if (!sceneMemory.reserve(std::uint64_t(width) * std::uint64_t(height) * 4 * bytesPerChannel)) {
    if (error)
      *error += "image " + std::to_string(index) + " would take the scene past the " + sceneMemory.limitText() +
                " a scene may take in memory\n";
    return false;
  }
  if (webp) {
    if (decodeWebp(*image, bytes, size)) return true;
    if (error) *error += "image " + std::to_string(index) + " is a WebP file that does not decode\n";
    return false;
  }
  return tinygltf::LoadImageData(image, index, error, warning, requestedWidth, requestedHeight, bytes, size, nullptr);
}

tinygltf::FsCallbacks sandboxedFileCallbacks(SceneFolderSandbox& sandbox) {
  return {fileExistsInside, expandNothing, readWholeFileInside, writeNothing, &sandbox};
}

}  // namespace s3d::renderer::gltf
