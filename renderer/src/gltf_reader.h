#pragma once
// Reading a parsed glTF model's accessors within the scene's memory limit; every error names the file.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "s3d/number_text.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::renderer::gltf {
namespace fs = std::filesystem;

// before it is made, so a small file cannot declare its way past the limit (scene_file.h, kMaxSceneBytes).
struct SceneMemory {
  std::uint64_t limit = kMaxSceneBytes;
  std::uint64_t used = 0;

  std::string limitText() const {
    return limit >= (1u << 20) ? std::to_string(limit >> 20) + " MiB" : std::to_string(limit) + " bytes";
  }
  // False when `bytes` more do not fit; else counts them.
  bool reserve(std::uint64_t bytes) {
    if (bytes > limit - used) return false;
    used += bytes;
    return true;
  }
};

// Every error names the file it comes from.
class GltfReader {
 public:
  GltfReader(const fs::path& file, const tinygltf::Model& model, SceneMemory& memory)
      : file_(file), model_(model), memory_(memory),
        quantized_(std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_mesh_quantization") !=
                   model.extensionsUsed.end()) {}

  [[noreturn]] void corrupt(const std::string& what) const {
    throw std::runtime_error("glTF file '" + file_.string() + "' is corrupt: " + what);
  }
  [[noreturn]] void unsupported(const std::string& what) const { refuse(what + " is not supported"); }
  [[noreturn]] void refuse(const std::string& why) const {
    throw std::invalid_argument("glTF file '" + file_.string() + "': " + why);
  }

  // An accessor's elements as floats (components per element), normalized integers mapped to [0, 1] / [-1, 1].
  // Unnormalized integers only where KHR_mesh_quantization allows them (POSITION, TEXCOORD_n) in a file that
  // declares it; their values are taken as they are (the node transform dequantizes).
  std::vector<float> readFloats(int accessorIndex, int type, const char* what) const {
    const tinygltf::Accessor& accessor = accessorAt(accessorIndex, what);
    if (accessor.type != type) corrupt(std::string(what) + " accessor has the wrong element type");
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(type));
    const Span span = spanOf(accessor, components, what);
    const bool asIs = accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !accessor.normalized;
    if (asIs && !(quantized_ && (std::strcmp(what, "POSITION") == 0 || std::strncmp(what, "TEXCOORD_", 9) == 0)))
      unsupported(std::string(what) + " stored as unnormalized integers");
    std::vector<float> values(allocationFor<float>(accessor.count * std::size_t(components), what));
    forEachComponent(span, accessor.count, components, [&](std::size_t i, const unsigned char* p) {
      values[i] = componentValue(p, accessor.componentType, !asIs, what);
    });
    for (float v : values)
      if (!std::isfinite(v)) corrupt(std::string(what) + " contains a non-finite value");
    return values;
  }

  std::vector<std::uint32_t> readIndices(int accessorIndex) const {
    const tinygltf::Accessor& accessor = accessorAt(accessorIndex, "index");
    if (accessor.type != TINYGLTF_TYPE_SCALAR) corrupt("index accessor is not scalar");
    const Span span = spanOf(accessor, 1, "index");
    std::vector<std::uint32_t> indices(allocationFor<std::uint32_t>(accessor.count, "index"));
    forEachComponent(span, accessor.count, 1, [&](std::size_t i, const unsigned char* p) {
      switch (accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = *p; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          indices[i] = v;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&indices[i], p, 4); break;
        default: corrupt("index accessor has an invalid component type");
      }
    });
    return indices;
  }

  // An accessor of unsigned integers (not normalized: JOINTS_n), `type` elements of unsigned byte or short.
  std::vector<std::uint32_t> readUnsigned(int accessorIndex, int type, const std::string& what) const {
    const tinygltf::Accessor& accessor = accessorAt(accessorIndex, what.c_str());
    if (accessor.type != type) corrupt(what + " accessor has the wrong element type");
    if (accessor.normalized) corrupt(what + " accessor is normalized (it holds indices)");
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(type));
    const Span span = spanOf(accessor, components, what.c_str());
    std::vector<std::uint32_t> values(allocationFor<std::uint32_t>(accessor.count * std::size_t(components), what));
    forEachComponent(span, accessor.count, components, [&](std::size_t i, const unsigned char* p) {
      if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        values[i] = *p;
      } else if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        values[i] = v;
      } else {
        corrupt(what + " accessor is not of unsigned bytes or shorts");
      }
    });
    return values;
  }

  const fs::path& file() const { return file_; }

  // A number of the file as a float: refused past float's range (converting it would be undefined behaviour).
  float toFloat(double value, const std::string& what) const {
    if (!(std::abs(value) <= double(std::numeric_limits<float>::max())))
      corrupt(what + " " + numberText(value) + " is not a number within single precision");
    return float(value);
  }

  // Counts `count` elements of T against the scene's memory before they are allocated; returns `count`.
  template <typename T>
  std::size_t allocationFor(std::size_t count, const std::string& what) const {
    if (!memory_.reserve(std::uint64_t(count) * sizeof(T)))
      refuse("its " + what + " data would take the scene past the " + memory_.limitText() +
             " a scene may take in memory");
    return count;
  }

 private:
  const tinygltf::Accessor& accessorAt(int index, const char* what) const {
    if (index < 0 || std::size_t(index) >= model_.accessors.size())
      corrupt(std::string(what) + " accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(index)];
    if (accessor.sparse.isSparse) unsupported(std::string("a sparse ") + what + " accessor");
    return accessor;
  }

  // Where an accessor's elements lie: checked to lie inside its buffer view and buffer before anything is
  // allocated for them (a count of 2^32 in a small file must not allocate first).
  struct Span {
    const unsigned char* begin = nullptr;
    std::size_t stride = 0, componentSize = 0;
  };

  Span spanOf(const tinygltf::Accessor& accessor, int components, const char* what) const {
    if (accessor.count == 0) return {};
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= model_.bufferViews.size())
      corrupt(std::string(what) + " accessor has no buffer view");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(accessor.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
      corrupt(std::string(what) + " buffer view refers to a missing buffer");
    const std::vector<unsigned char>& data = model_.buffers[std::size_t(view.buffer)].data;
    const int componentSize = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    const int stride = accessor.ByteStride(view);
    if (componentSize <= 0 || stride <= 0) corrupt(std::string(what) + " accessor has an invalid layout");
    const std::size_t elementSize = std::size_t(componentSize) * std::size_t(components);
    // In overflow-free steps (every offset and count is the file's): the view lies in the buffer, and
    // accessor.byteOffset + stride * (count - 1) + elementSize lies in the view.
    if (view.byteOffset > data.size()) corrupt(std::string(what) + " buffer view starts past the end of its buffer");
    const std::size_t viewBytes = std::min(view.byteLength, data.size() - view.byteOffset);
    if (accessor.byteOffset > viewBytes || viewBytes - accessor.byteOffset < elementSize ||
        (accessor.count - 1) > (viewBytes - accessor.byteOffset - elementSize) / std::size_t(stride))
      corrupt(std::string(what) + " accessor reads past the end of its buffer");
    const std::size_t begin = view.byteOffset + accessor.byteOffset;
    return {data.data() + begin, std::size_t(stride), std::size_t(componentSize)};
  }

  // One component as a float: normalized integers mapped to [0, 1] / [-1, 1], else as they are.
  float componentValue(const unsigned char* p, int componentType, bool normalized, const char* what) const {
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(*p) / 255.0f : float(*p);
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float v = float(std::int8_t(*p));
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? float(v) / 65535.0f : float(v);
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
      }
      default: corrupt(std::string(what) + " accessor has an invalid component type");
    }
  }

  // Calls visit(component index, bytes) for every component of a span checked by spanOf.
  static void forEachComponent(const Span& span, std::size_t count, int components,
                               const std::function<void(std::size_t, const unsigned char*)>& visit) {
    for (std::size_t element = 0; element < count; ++element)
      for (int c = 0; c < components; ++c)
        visit(element * std::size_t(components) + std::size_t(c),
              span.begin + element * span.stride + std::size_t(c) * span.componentSize);
  }

  fs::path file_;
  const tinygltf::Model& model_;
  SceneMemory& memory_;
  bool quantized_ = false;  // the file uses KHR_mesh_quantization
};

// " ('name')" after an index, or nothing for an unnamed element: files name few of their nodes and materials.
inline std::string named(const std::string& name) { return name.empty() ? "" : " ('" + name + "')"; }

}  // namespace s3d::renderer::gltf
