#include "gltf_parse.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "gltf_files.h"
#include "s3d/input_file.h"

namespace s3d::renderer::gltf {
namespace {

// A fallback buffer gets one byte: tinygltf refuses an empty data: URI, and no uncompressed view may read it
// (an accessor that does is refused as reading past the end of its buffer).
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";
constexpr const char* kWebpDataUri = "data:image/webp;base64,";
constexpr const char* kOctetDataUri = "data:application/octet-stream;base64,";

bool isDatalessFallback(const nlohmann::json& buffer) {
  if (!buffer.is_object() || buffer.contains("uri")) return false;
  const auto extensions = buffer.find("extensions");
  if (extensions == buffer.end() || !extensions->is_object()) return false;
  const auto meshopt = extensions->find("EXT_meshopt_compression");
  if (meshopt == extensions->end() || !meshopt->is_object()) return false;
  const auto fallback = meshopt->find("fallback");
  return fallback != meshopt->end() && fallback->is_boolean() && fallback->get<bool>();
}

// A KHR_draco_mesh_compression primitive's index accessor has no buffer view (its indices lie in the draco
// stream), which tinygltf refuses: it gets the stream's view, never read through it (gltf_draco.h replaces it).
bool giveDracoIndicesAView(nlohmann::json& document) {
  const auto meshes = document.find("meshes");
  const auto accessors = document.find("accessors");
  if (meshes == document.end() || !meshes->is_array() || accessors == document.end() || !accessors->is_array()) return false;
  bool changed = false;
  for (const nlohmann::json& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (const nlohmann::json& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("indices") || !primitive["indices"].is_number_unsigned()) continue;
      const nlohmann::json* draco = primitive.contains("extensions") && primitive["extensions"].is_object() &&
                                            primitive["extensions"].contains("KHR_draco_mesh_compression")
                                        ? &primitive["extensions"]["KHR_draco_mesh_compression"]
                                        : nullptr;
      if (!draco || !draco->is_object() || !draco->contains("bufferView") || !(*draco)["bufferView"].is_number_unsigned()) continue;
      const auto index = primitive["indices"].get<std::size_t>();
      if (index >= accessors->size() || !(*accessors)[index].is_object() || (*accessors)[index].contains("bufferView")) continue;
      (*accessors)[index]["bufferView"] = (*draco)["bufferView"];
      changed = true;
    }
  }
  return changed;
}

// The document as tinygltf can take it, or null when it needs no change.
nlohmann::json rewritten(const nlohmann::json& json) {
  nlohmann::json copy = json;
  bool changed = giveDracoIndicesAView(copy);
  if (auto buffers = copy.find("buffers"); buffers != copy.end() && buffers->is_array())
    for (nlohmann::json& buffer : *buffers)
      if (isDatalessFallback(buffer)) {
        buffer["uri"] = kPlaceholderUri;
        buffer["byteLength"] = 1;
        changed = true;
      }
  if (auto images = copy.find("images"); images != copy.end() && images->is_array())
    for (nlohmann::json& image : *images) {
      if (!image.is_object() || !image.contains("uri") || !image["uri"].is_string()) continue;
      const std::string uri = image["uri"].get<std::string>();
      if (uri.rfind(kWebpDataUri, 0) != 0) continue;
      image["uri"] = kOctetDataUri + uri.substr(std::strlen(kWebpDataUri));  // the image loader tells WebP by its bytes
      changed = true;
    }
  return changed ? copy : nlohmann::json();
}

// `document[arrayName][index]` when both exist and `index` is an unsigned integer inside the array, else null.
const nlohmann::json* element(const nlohmann::json& document, const char* arrayName, const nlohmann::json& index) {
  const auto array = document.find(arrayName);
  if (array == document.end() || !array->is_array() || !index.is_number_unsigned()) return nullptr;
  const auto at = index.get<std::uint64_t>();
  return at < array->size() && (*array)[at].is_object() ? &(*array)[at] : nullptr;
}

// `object[name]` as an unsigned integer, 0 when absent; clears `valid` when it is something else.
std::uint64_t unsignedOrZero(const nlohmann::json& object, const char* name, bool& valid) {
  const auto field = object.find(name);
  if (field == object.end()) return 0;
  if (!field->is_number_unsigned()) valid = false;
  return field->is_number_unsigned() ? field->get<std::uint64_t>() : 0;
}

// Why image `index`'s buffer view cannot be decoded safely, or empty. tinygltf hands an image's buffer view to the
// image decoder without checking that the view lies inside its buffer, so a view past the end was decoded from
// whatever memory follows: the view is held to its buffer's byteLength first (tinygltf holds a buffer's data to
// exactly that length). Its indices must be in range as written: tinygltf cuts a larger integer to 32 bits, so
// 4294967298 would name view 2 there but nothing here.
std::string imageViewProblem(const nlohmann::json& document, std::size_t index, const nlohmann::json& image) {
  const std::string where = "image " + std::to_string(index) + "'s buffer view " + image["bufferView"].dump();
  const nlohmann::json* view = element(document, "bufferViews", image["bufferView"]);
  if (!view) return where + " is not one of the file's buffer views";
  const nlohmann::json* buffer = view->contains("buffer") ? element(document, "buffers", (*view)["buffer"]) : nullptr;
  if (!buffer) return where + " names no buffer of the file";
  const std::string bufferName = "buffer " + (*view)["buffer"].dump();
  bool valid = true;
  const std::uint64_t offset = unsignedOrZero(*view, "byteOffset", valid);
  const std::uint64_t length = unsignedOrZero(*view, "byteLength", valid);
  const std::uint64_t bufferLength = unsignedOrZero(*buffer, "byteLength", valid);
  if (!valid) return where + " or " + bufferName + " gives a byte offset or length that is not a whole number";
  if (length <= bufferLength && offset <= bufferLength - length) return "";
  return where + " runs past the end of " + bufferName + " (" + std::to_string(length) + " bytes from byte " +
         std::to_string(offset) + ", in a buffer of " + std::to_string(bufferLength) + ")";
}

bool imageViewsInsideTheirBuffers(const nlohmann::json& document, std::string& errors) {
  const auto images = document.find("images");
  if (images == document.end() || !images->is_array()) return true;
  for (std::size_t index = 0; index < images->size(); ++index) {
    const nlohmann::json& image = (*images)[index];
    if (!image.is_object() || !image.contains("bufferView")) continue;
    if (const std::string problem = imageViewProblem(document, index, image); !problem.empty()) {
      errors += problem + "\n";
      return false;
    }
  }
  return true;
}

void appendWord(std::string& bytes, std::uint32_t word) {
  char raw[4];
  std::memcpy(raw, &word, 4);
  bytes.append(raw, 4);
}

// A .glb (`file`'s bytes) with its JSON chunk replaced by `json`.
std::string glbWithJson(const std::filesystem::path& file, const std::string& glb, std::string json) {
  std::uint32_t oldLength = 0;
  if (glb.size() >= 20) std::memcpy(&oldLength, glb.data() + 12, 4);
  if (glb.size() < 20 || oldLength > glb.size() - 20)  // gltfJson checked this on its own read of the file
    throw std::runtime_error("glTF file '" + file.string() + "' changed while it was being read");
  while (json.size() % 4 != 0) json += ' ';  // chunks are 4-byte aligned, JSON padded with spaces
  const std::string rest = glb.substr(20 + oldLength);
  std::string out = glb.substr(0, 8);
  appendWord(out, std::uint32_t(20 + json.size() + rest.size()));
  appendWord(out, std::uint32_t(json.size()));
  out.append(glb, 16, 4);  // the chunk type: JSON
  return out + json + rest;
}

}  // namespace

bool parseGltf(tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& errors, std::string& warnings,
               const std::filesystem::path& file, bool binary, const nlohmann::json& json) {
  const nlohmann::json changed = json.is_object() ? rewritten(json) : nlohmann::json();
  if (!imageViewsInsideTheirBuffers(changed.is_null() ? json : changed, errors)) return false;
  if (changed.is_null())
    return binary ? loader.LoadBinaryFromFile(&model, &errors, &warnings, file.string())
                  : loader.LoadASCIIFromFile(&model, &errors, &warnings, file.string());
  const std::string folder = file.parent_path().string();  // where tinygltf resolves URIs, as it does from a file
  const std::string text = changed.dump();
  if (!binary) return loader.LoadASCIIFromString(&model, &errors, &warnings, text.data(), unsigned(text.size()), folder);
  const std::string glb = glbWithJson(file, readInputFile(file, "glTF file", kMaxSceneFileBytes), text);
  return loader.LoadBinaryFromMemory(&model, &errors, &warnings, reinterpret_cast<const unsigned char*>(glb.data()),
                                     unsigned(glb.size()), folder);
}

}  // namespace s3d::renderer::gltf
