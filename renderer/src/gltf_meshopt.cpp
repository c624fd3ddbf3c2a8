#include "gltf_meshopt.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <meshoptimizer.h>

namespace s3d::renderer::gltf {
namespace {

// One view's extension object, its fields checked against the extension's rules.
struct CompressedView {
  std::size_t buffer = 0, byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter = "NONE";
};

class MeshoptDecoder {
 public:
  MeshoptDecoder(const std::filesystem::path& file, tinygltf::Model& model, SceneMemory& memory)
      : reader_(file, model, memory), model_(model) {}

  void decode(std::size_t viewIndex) {
    const std::string where = "buffer view " + std::to_string(viewIndex) + " (EXT_meshopt_compression)";
    const CompressedView view = parse(viewIndex, where);
    const std::vector<unsigned char>& source = model_.buffers[view.buffer].data;
    if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset)
      reader_.corrupt(where + " reads past the end of buffer " + std::to_string(view.buffer));
    if (view.count > (std::uint64_t(1) << 40) / view.byteStride)
      reader_.corrupt(where + " declares " + std::to_string(view.count) + " elements");
    const std::size_t size = view.count * view.byteStride;
    tinygltf::BufferView& target = model_.bufferViews[viewIndex];
    if (target.byteLength != size)
      reader_.corrupt(where + " is " + std::to_string(target.byteLength) + " bytes long but decodes to " + std::to_string(size));
    tinygltf::Buffer decoded;
    decoded.data.resize(reader_.allocationFor<unsigned char>(size, where));
    const unsigned char* stream = source.data() + view.byteOffset;
    int status = -1;
    if (view.mode == "ATTRIBUTES")
      status = meshopt_decodeVertexBuffer(decoded.data.data(), view.count, view.byteStride, stream, view.byteLength);
    else if (view.mode == "TRIANGLES")
      status = meshopt_decodeIndexBuffer(decoded.data.data(), view.count, view.byteStride, stream, view.byteLength);
    else
      status = meshopt_decodeIndexSequence(decoded.data.data(), view.count, view.byteStride, stream, view.byteLength);
    if (status != 0) reader_.corrupt(where + "'s compressed stream does not decode (meshoptimizer status " + std::to_string(status) + ")");
    if (view.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data.data(), view.count, view.byteStride);
    if (view.filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data.data(), view.count, view.byteStride);
    if (view.filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data.data(), view.count, view.byteStride);
    model_.buffers.push_back(std::move(decoded));
    target.buffer = int(model_.buffers.size() - 1);
    target.byteOffset = 0;
  }

 private:
  // A non-negative integer field of the extension object (`fallback` when absent and optional).
  std::size_t integer(const tinygltf::Value& object, const char* key, const std::string& where, bool required) const {
    if (!object.Has(key)) {
      if (required) reader_.corrupt(where + " has no " + key);
      return 0;
    }
    const tinygltf::Value& value = object.Get(key);
    const double number = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
    if (!(number >= 0.0 && number <= 9007199254740992.0) || std::floor(number) != number)
      reader_.corrupt(where + "'s " + key + " is not a non-negative integer");
    return std::size_t(number);
  }

  std::string text(const tinygltf::Value& object, const char* key, const std::string& fallback) const {
    if (!object.Has(key)) return fallback;
    return object.Get(key).IsString() ? object.Get(key).Get<std::string>() : std::string("(not a string)");
  }

  CompressedView parse(std::size_t viewIndex, const std::string& where) const {
    const tinygltf::Value& ext = model_.bufferViews[viewIndex].extensions.at("EXT_meshopt_compression");
    if (!ext.IsObject()) reader_.corrupt(where + " is not an object");
    CompressedView view;
    view.buffer = integer(ext, "buffer", where, true);
    if (view.buffer >= model_.buffers.size()) reader_.corrupt(where + " refers to a missing buffer");
    view.byteOffset = integer(ext, "byteOffset", where, false);
    view.byteLength = integer(ext, "byteLength", where, true);
    view.byteStride = integer(ext, "byteStride", where, true);
    view.count = integer(ext, "count", where, true);
    view.mode = text(ext, "mode", "");
    view.filter = text(ext, "filter", "NONE");
    // The extension's rules, which meshoptimizer's decoders assume (they assert rather than check).
    const std::size_t stride = view.byteStride;
    bool valid = false;
    if (view.mode == "ATTRIBUTES")
      valid = stride > 0 && stride % 4 == 0 && stride <= 256 &&
              (view.filter == "NONE" || (view.filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) ||
               (view.filter == "QUATERNION" && stride == 8) || view.filter == "EXPONENTIAL");
    else if (view.mode == "TRIANGLES")
      valid = (stride == 2 || stride == 4) && view.count % 3 == 0 && view.filter == "NONE";
    else if (view.mode == "INDICES")
      valid = (stride == 2 || stride == 4) && view.filter == "NONE";
    if (!valid)
      reader_.corrupt(where + " has mode '" + view.mode + "', filter '" + view.filter + "' and byteStride " +
                      std::to_string(stride) + ", which the extension does not allow together");
    return view;
  }

  GltfReader reader_;
  tinygltf::Model& model_;
};

}  // namespace

void decodeMeshoptViews(const std::filesystem::path& file, tinygltf::Model& model, SceneMemory& memory) {
  MeshoptDecoder decoder(file, model, memory);
  const std::size_t views = model.bufferViews.size();  // decoding appends buffers, never views
  for (std::size_t v = 0; v < views; ++v)
    if (model.bufferViews[v].extensions.count("EXT_meshopt_compression") != 0) decoder.decode(v);
}

}  // namespace s3d::renderer::gltf
