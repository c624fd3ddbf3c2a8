#include "gltf_draco.h"

#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <draco/compression/decode.h>

namespace s3d::renderer::gltf {
namespace {

class DracoDecoder {
 public:
  DracoDecoder(const std::filesystem::path& file, tinygltf::Model& model, SceneMemory& memory)
      : reader_(file, model, memory), model_(model) {}

  void decode(tinygltf::Primitive& primitive, const std::string& where) {
    const tinygltf::Value& ext = primitive.extensions.at("KHR_draco_mesh_compression");
    if (!ext.IsObject() || !ext.Get("bufferView").IsInt() || !ext.Get("attributes").IsObject())
      reader_.corrupt(where + " has no bufferView or attributes");
    const Stream stream = viewBytes(ext.Get("bufferView").GetNumberAsInt(), where);
    const std::vector<std::pair<std::string, int>> attributes = attributeIds(primitive, ext.Get("attributes"), where);
    std::uint64_t declared = 0;  // the decoded data's size as the file's accessors declare it
    for (const auto& [name, id] : attributes) declared += accessorBytes(primitive.attributes.at(name), where);
    if (primitive.indices >= 0) declared += accessorBytes(primitive.indices, where);
    reader_.allocationFor<unsigned char>(declared, where);
    const std::unique_ptr<draco::Mesh> mesh = decodedMesh(stream, where);
    const std::uint64_t indexCount = std::uint64_t(mesh->num_faces()) * 3;
    if (primitive.indices < 0) reader_.allocationFor<std::uint32_t>(indexCount, where);
    else if (indexCount != model_.accessors[std::size_t(primitive.indices)].count)
      reader_.corrupt(where + "'s draco stream has " + std::to_string(mesh->num_faces()) +
                      " triangles, not what its index accessor declares");

    tinygltf::Buffer decoded;
    for (const auto& [name, id] : attributes) {
      const tinygltf::Accessor declaredAccessor = model_.accessors.at(std::size_t(primitive.attributes.at(name)));
      primitive.attributes[name] = addAccessor(decoded, declaredAccessor.type, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                               attributeValues(*mesh, name, id, declaredAccessor, where));
    }
    std::vector<unsigned char> indices(std::size_t(mesh->num_faces()) * 12);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
      for (int corner = 0; corner < 3; ++corner) {
        const std::uint32_t index = mesh->face(f)[corner].value();
        std::memcpy(&indices[(std::size_t(f.value()) * 3 + std::size_t(corner)) * 4], &index, 4);
      }
    primitive.indices = addAccessor(decoded, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices);
    model_.buffers.push_back(std::move(decoded));
  }

 private:
  struct Stream {
    const unsigned char* bytes = nullptr;
    std::size_t size = 0;
  };

  Stream viewBytes(int viewIndex, const std::string& where) const {
    if (viewIndex < 0 || std::size_t(viewIndex) >= model_.bufferViews.size())
      reader_.corrupt(where + "'s buffer view " + std::to_string(viewIndex) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(viewIndex)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
      reader_.corrupt(where + "'s buffer view refers to a missing buffer");
    const std::vector<unsigned char>& data = model_.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
      reader_.corrupt(where + "'s buffer view reads past the end of its buffer");
    return {data.data() + view.byteOffset, view.byteLength};
  }

  // The attributes the extension maps to draco ids, each also an attribute of the primitive (whose accessor
  // gives its element type and count).
  std::vector<std::pair<std::string, int>> attributeIds(const tinygltf::Primitive& primitive,
                                                        const tinygltf::Value& map, const std::string& where) const {
    std::vector<std::pair<std::string, int>> ids;
    for (const std::string& name : map.Keys()) {
      if (!map.Get(name).IsInt()) reader_.corrupt(where + "'s draco id of " + name + " is not an integer");
      if (primitive.attributes.count(name) == 0)
        reader_.corrupt(where + " maps " + name + " to draco but has no " + name + " accessor");
      const int accessor = primitive.attributes.at(name);
      if (accessor < 0 || std::size_t(accessor) >= model_.accessors.size())
        reader_.corrupt(where + "'s " + name + " accessor " + std::to_string(accessor) + " does not exist");
      ids.emplace_back(name, map.Get(name).GetNumberAsInt());
    }
    return ids;
  }

  std::uint64_t accessorBytes(int accessorIndex, const std::string& where) const {
    if (accessorIndex < 0 || std::size_t(accessorIndex) >= model_.accessors.size())
      reader_.corrupt(where + "'s accessor " + std::to_string(accessorIndex) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(accessorIndex)];
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type));
    if (components <= 0 || accessor.count > (std::uint64_t(1) << 40))
      reader_.corrupt(where + "'s accessor " + std::to_string(accessorIndex) + " has an invalid type or count");
    return std::uint64_t(accessor.count) * std::uint64_t(components) * 4;
  }

  std::unique_ptr<draco::Mesh> decodedMesh(const Stream& stream, const std::string& where) const {
    std::string problem;
    try {
      draco::DecoderBuffer buffer;
      buffer.Init(reinterpret_cast<const char*>(stream.bytes), stream.size);
      draco::Decoder decoder;
      auto result = decoder.DecodeMeshFromBuffer(&buffer);
      if (result.ok()) return std::move(result).value();
      problem = result.status().error_msg_string();
    } catch (const std::bad_alloc&) {
      problem = "it declares more data than fits in memory";
    } catch (const std::length_error&) {
      problem = "it declares more data than fits in memory";
    }
    reader_.corrupt(where + "'s draco stream does not decode (" + problem + ")");
  }

  // One attribute's values per point as floats, checked against the accessor the file declares for it.
  std::vector<unsigned char> attributeValues(const draco::Mesh& mesh, const std::string& name, int id,
                                             const tinygltf::Accessor& declared, const std::string& where) const {
    const draco::PointAttribute* attribute = id < 0 ? nullptr : mesh.GetAttributeByUniqueId(std::uint32_t(id));
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(declared.type));
    if (!attribute) reader_.corrupt(where + "'s draco stream has no attribute " + std::to_string(id) + " (" + name + ")");
    if (attribute->num_components() != components || mesh.num_points() != declared.count)
      reader_.corrupt(where + "'s draco attribute " + name + " does not match its accessor's type and count");
    std::vector<float> values(std::size_t(mesh.num_points()) * std::size_t(components));
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p)
      if (!attribute->ConvertValue<float>(attribute->mapped_index(p), std::int8_t(components),
                                          &values[std::size_t(p.value()) * std::size_t(components)]))
        reader_.corrupt(where + "'s draco attribute " + name + " cannot be read as numbers");
    std::vector<unsigned char> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  }

  // An accessor over `bytes` appended to `buffer` through a view of its own; returns the accessor's index.
  int addAccessor(tinygltf::Buffer& buffer, int type, int componentType, const std::vector<unsigned char>& bytes) {
    tinygltf::BufferView view;
    view.buffer = int(model_.buffers.size());  // `buffer` is appended once complete
    view.byteOffset = buffer.data.size();
    view.byteLength = bytes.size();
    buffer.data.insert(buffer.data.end(), bytes.begin(), bytes.end());
    model_.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = int(model_.bufferViews.size() - 1);
    accessor.componentType = componentType;
    accessor.type = type;
    accessor.count = bytes.size() / std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(componentType)) *
                                                tinygltf::GetNumComponentsInType(std::uint32_t(type)));
    model_.accessors.push_back(accessor);
    return int(model_.accessors.size() - 1);
  }

  GltfReader reader_;
  tinygltf::Model& model_;
};

}  // namespace

void decodeDracoPrimitives(const std::filesystem::path& file, tinygltf::Model& model, SceneMemory& memory) {
  DracoDecoder decoder(file, model, memory);
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      if (primitive.extensions.count("KHR_draco_mesh_compression") == 0) continue;
      decoder.decode(primitive, "mesh " + std::to_string(m) + named(model.meshes[m].name) + " primitive " +
                                    std::to_string(p) + " (KHR_draco_mesh_compression)");
    }
}

}  // namespace s3d::renderer::gltf
