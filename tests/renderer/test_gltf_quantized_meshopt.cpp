// KHR_mesh_quantization (integer attributes) and EXT_meshopt_compression (views decoded with meshoptimizer):
// files written here from tests/support/gltf_test_documents.h's grid load as the same triangles as its plain float
// variant, within the step each encoding keeps; broken streams and forbidden layouts are clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <meshoptimizer.h>

#include "gltf_test_documents.h"
#include "io_test_support.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;
using test::bytesOf;
using test::GltfBuilder;
using test::GridMesh;

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

class GltfQuantizedMeshopt : public ::testing::Test {
 protected:

  Scene plainGrid() const {
    GltfBuilder builder;
    builder.primitive(test::plainGridPrimitive(builder, grid_));
    return loadGltfScene(builder.writeGltf(folder_ / "plain.gltf"));
  }

  // What loading `file` throws as E (empty when it loads or throws something else).
  template <typename E>
  static std::string errorOf(const fs::path& file, std::uint64_t memoryLimit = kMaxSceneBytes) {
    return test::errorOf<E>([&] { loadGltfScene(file, memoryLimit); });
  }

  test::ScratchFolder scratch_{"s3d_compressed_"};
  const fs::path& folder_ = scratch_.path();
  GridMesh grid_ = test::gridMesh();
};

// ---- KHR_mesh_quantization ----

// Positions as 16-bit integers (4x the grid's, undone by the node's 1/4 scale), normals as normalized bytes,
// texture coordinates as normalized unsigned shorts, tangents as normalized shorts, each padded to 4-byte strides.
GltfBuilder quantizedGrid(const GridMesh& grid, bool declareExtension) {
  GltfBuilder builder;
  if (declareExtension) builder.uses("KHR_mesh_quantization");
  const std::size_t n = grid.vertexCount();
  std::vector<std::int16_t> positions(4 * n, 0), tangents(4 * n);
  std::vector<std::int8_t> normals(4 * n, 0);
  std::vector<std::uint16_t> texCoords(2 * n);
  for (std::size_t v = 0; v < n; ++v) {
    for (std::size_t c = 0; c < 3; ++c) {
      positions[4 * v + c] = std::int16_t(std::lround(grid.positions[3 * v + c] * 4.0f));
      normals[4 * v + c] = std::int8_t(std::lround(grid.normals[3 * v + c] * 127.0f));
    }
    for (std::size_t c = 0; c < 2; ++c) texCoords[2 * v + c] = std::uint16_t(std::lround(grid.texCoords[2 * v + c] * 65535.0f));
    for (std::size_t c = 0; c < 4; ++c) tangents[4 * v + c] = std::int16_t(std::lround(grid.tangents[4 * v + c] * 32767.0f));
  }
  std::vector<std::uint16_t> indices(grid.indices.begin(), grid.indices.end());
  builder.primitive({{"attributes",
                      {{"POSITION", builder.accessor(builder.view(bytesOf(positions), 8), kShort, n, "VEC3")},
                       {"NORMAL", builder.accessor(builder.view(bytesOf(normals), 4), kByte, n, "VEC3", true)},
                       {"TEXCOORD_0", builder.accessor(builder.view(bytesOf(texCoords), 4), kUnsignedShort, n, "VEC2", true)},
                       {"TANGENT", builder.accessor(builder.view(bytesOf(tangents), 8), kShort, n, "VEC4", true)}}},
                     {"indices", builder.accessor(builder.view(bytesOf(indices)), kUnsignedShort, indices.size(), "SCALAR")}},
                    0.25f);
  return builder;
}

TEST_F(GltfQuantizedMeshopt, QuantizedAttributesLoadAsTheFloatGridWithinTheirSteps) {
  const Scene quantized = loadGltfScene(quantizedGrid(grid_, true).writeGltf(folder_ / "quantized.gltf"));
  // Positions: multiples of 1/4 stored as integers and scaled by 1/4 are exact (1e-6: the float transform).
  // Normals: bytes of step 1/127 per component, renormalized: within 0.01. Texture coordinates: step 1/65535.
  // Tangents: step 1/32767.
  test::expectSameTriangles(plainGrid(), quantized, {1e-6f, 0.01f, 1e-5f, 1e-4f});
}

TEST_F(GltfQuantizedMeshopt, UnnormalizedIntegerPositionsWithoutTheExtensionAreRefused) {
  const fs::path file = quantizedGrid(grid_, false).writeGltf(folder_ / "undeclared.gltf");
  const std::string message = errorOf<std::invalid_argument>(file);
  EXPECT_NE(message.find("glTF file '" + file.string() + "': POSITION stored as unnormalized integers is not supported"),
            std::string::npos)
      << message;
}

TEST_F(GltfQuantizedMeshopt, UnnormalizedIntegerNormalsAreRefusedEvenWithTheExtension) {
  GltfBuilder builder = quantizedGrid(grid_, true);
  builder.doc["accessors"][1].erase("normalized");  // NORMAL: the extension allows normalized integers only
  const fs::path file = builder.writeGltf(folder_ / "normals.gltf");
  EXPECT_NE(errorOf<std::invalid_argument>(file).find("NORMAL stored as unnormalized integers is not supported"), std::string::npos);
}

// ---- EXT_meshopt_compression ----

enum class IndexMode { Triangles, Sequence };

// The grid with every view compressed into buffer 0 and a fallback buffer 1 without data, as gltfpack writes it:
// positions and tangents unfiltered, normals octahedral (8 bits), texture coordinates exponential (15-bit
// mantissa), indices as a triangle list (32-bit) or an index sequence (16-bit).
class MeshoptGrid {
 public:
  explicit MeshoptGrid(const GridMesh& grid, IndexMode mode) : n_(grid.vertexCount()) {
    builder.uses("EXT_meshopt_compression");
    builder.uses("KHR_mesh_quantization");
    builder.doc["buffers"].push_back({{"byteLength", 0}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    std::vector<float> normals4(4 * n_, 0.0f);
    for (std::size_t v = 0; v < n_; ++v)
      for (std::size_t c = 0; c < 3; ++c) normals4[4 * v + c] = grid.normals[3 * v + c];
    std::vector<std::int8_t> octahedral(4 * n_);
    meshopt_encodeFilterOct(octahedral.data(), n_, 4, 8, normals4.data());
    std::vector<std::uint32_t> exponential(2 * n_);
    meshopt_encodeFilterExp(exponential.data(), n_, 8, 15, grid.texCoords.data());
    const nlohmann::json attributes = {
        {"POSITION", builder.accessor(vertices(grid.positions.data(), 12, "NONE"), kFloat, n_, "VEC3")},
        {"NORMAL", builder.accessor(vertices(octahedral.data(), 4, "OCTAHEDRAL"), kByte, n_, "VEC3", true)},
        {"TEXCOORD_0", builder.accessor(vertices(exponential.data(), 8, "EXPONENTIAL"), kFloat, n_, "VEC2")},
        {"TANGENT", builder.accessor(vertices(grid.tangents.data(), 16, "NONE"), kFloat, n_, "VEC4")}};
    const std::size_t count = grid.indices.size();
    std::string encoded;
    if (mode == IndexMode::Triangles) {
      encoded.resize(meshopt_encodeIndexBufferBound(count, n_));
      encoded.resize(meshopt_encodeIndexBuffer(bytes(encoded), encoded.size(), grid.indices.data(), count));
    } else {
      encoded.resize(meshopt_encodeIndexSequenceBound(count, n_));
      encoded.resize(meshopt_encodeIndexSequence(bytes(encoded), encoded.size(), grid.indices.data(), count));
    }
    const bool triangles = mode == IndexMode::Triangles;
    const int indexView = compressed(encoded, count, triangles ? 4 : 2, triangles ? "TRIANGLES" : "INDICES", "NONE");
    builder.primitive({{"attributes", attributes},
                       {"indices", builder.accessor(indexView, triangles ? kUnsignedInt : kUnsignedShort, count, "SCALAR")}});
    builder.doc["buffers"][1]["byteLength"] = fallbackBytes_;
  }

  GltfBuilder builder;

 private:
  static unsigned char* bytes(std::string& text) { return reinterpret_cast<unsigned char*>(text.data()); }

  int vertices(const void* data, std::size_t stride, const char* filter) {
    std::string encoded(meshopt_encodeVertexBufferBound(n_, stride), '\0');
    encoded.resize(meshopt_encodeVertexBuffer(bytes(encoded), encoded.size(), data, n_, stride));
    return compressed(encoded, n_, stride, "ATTRIBUTES", filter);
  }

  // A view of the fallback buffer whose data lies compressed in buffer 0.
  int compressed(const std::string& encoded, std::size_t count, std::size_t stride, const char* mode, const char* filter) {
    const std::size_t offset = builder.append(encoded);
    nlohmann::json view = {{"buffer", 1}, {"byteOffset", fallbackBytes_}, {"byteLength", count * stride},
                           {"extensions", {{"EXT_meshopt_compression",
                                            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", encoded.size()},
                                             {"byteStride", stride}, {"count", count}, {"mode", mode}, {"filter", filter}}}}}};
    if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
    fallbackBytes_ += (count * stride + 3) / 4 * 4;
    builder.doc["bufferViews"].push_back(view);
    return int(builder.doc["bufferViews"].size() - 1);
  }

  std::size_t n_;
  std::size_t fallbackBytes_ = 0;
};

// Positions and tangents: unfiltered, lossless (0). Normals: 8-bit octahedral, within 0.02 per component.
// Texture coordinates: 15-bit mantissas of values in [0, 1], within 1e-4.
constexpr test::Tolerances kMeshoptSteps{0.0f, 0.02f, 1e-4f, 0.0f};

TEST_F(GltfQuantizedMeshopt, MeshoptCompressedViewsDecodeToTheGrid) {
  const fs::path file = MeshoptGrid(grid_, IndexMode::Triangles).builder.writeGltf(folder_ / "meshopt.gltf");
  test::expectSameTriangles(plainGrid(), loadGltfScene(file), kMeshoptSteps);
}

TEST_F(GltfQuantizedMeshopt, AMeshoptGlbWithAnIndexSequenceDecodesToTheGrid) {
  const fs::path file = MeshoptGrid(grid_, IndexMode::Sequence).builder.writeGlb(folder_ / "meshopt.glb");
  test::expectSameTriangles(plainGrid(), loadGltfScene(file), kMeshoptSteps);
}

TEST_F(GltfQuantizedMeshopt, ACorruptMeshoptStreamIsRefusedNamingTheBufferView) {
  MeshoptGrid grid(grid_, IndexMode::Triangles);
  grid.builder.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 5;  // cut short
  const fs::path file = grid.builder.writeGltf(folder_ / "cut.gltf");
  const std::string message = errorOf<std::runtime_error>(file);
  EXPECT_NE(message.find("glTF file '" + file.string() + "' is corrupt: buffer view 0 (EXT_meshopt_compression)'s "
                         "compressed stream does not decode"),
            std::string::npos)
      << message;
}

TEST_F(GltfQuantizedMeshopt, DecodedMeshoptSizesCountAgainstTheSceneMemoryBeforeDecoding) {
  MeshoptGrid grid(grid_, IndexMode::Triangles);
  // 2^28 positions of 16 bytes: 4 GiB decoded from a stream of a few bytes; refused before it is allocated.
  nlohmann::json& view = grid.builder.doc["bufferViews"][0];
  view["byteLength"] = std::uint64_t(1) << 32;
  view["byteStride"] = 16;
  view["extensions"]["EXT_meshopt_compression"]["count"] = std::uint64_t(1) << 28;
  view["extensions"]["EXT_meshopt_compression"]["byteStride"] = 16;
  const fs::path file = grid.builder.writeGltf(folder_ / "huge.gltf");
  const std::string message = errorOf<std::invalid_argument>(file, std::uint64_t(64) << 20);
  EXPECT_NE(message.find("buffer view 0 (EXT_meshopt_compression) data would take the scene past the 64 MiB"),
            std::string::npos)
      << message;
}

TEST_F(GltfQuantizedMeshopt, AMeshoptLayoutTheExtensionForbidsIsRefused) {
  MeshoptGrid grid(grid_, IndexMode::Triangles);
  grid.builder.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";  // needs stride 8
  const fs::path file = grid.builder.writeGltf(folder_ / "quaternion.gltf");
  EXPECT_NE(errorOf<std::runtime_error>(file).find("buffer view 1 (EXT_meshopt_compression) has mode 'ATTRIBUTES', filter "
                                                   "'QUATERNION' and byteStride 4, which the extension does not allow"),
            std::string::npos);
}

}  // namespace
}  // namespace s3d::renderer
