// KHR_draco_mesh_compression (primitives decoded with libdraco) and EXT_texture_webp (textures decoded with
// libwebp): files written here with the same libraries' encoders load as their uncompressed variants, a real
// exporter's draco file (Debian's assimp-testmodels) loads, and broken data is a clear error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <dlfcn.h>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <stb/stb_image.h>
#include <tiny_gltf.h>
#include <webp/encode.h>

#include "gltf_test_documents.h"
#include "io_test_support.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;
using test::GltfBuilder;
using test::GridMesh;

const fs::path kDataDir = S3D_TEST_DATA_DIR;

class GltfDracoWebp : public ::testing::Test {
 protected:

  template <typename E>
  static std::string errorOf(const fs::path& file) {
    return test::errorOf<E>([&] { loadGltfScene(file); });
  }

  test::ScratchFolder scratch_{"s3d_draco_webp_"};
  const fs::path& folder_ = scratch_.path();
  GridMesh grid_ = test::gridMesh();
};

// ---- KHR_draco_mesh_compression ----

int addDracoAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components, const std::vector<float>& values) {
  const auto points = draco::AttributeValueIndex::ValueType(mesh.num_points());
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, std::uint8_t(components), draco::DT_FLOAT32, false, std::int64_t(sizeof(float)) * components, 0);
  const int id = mesh.AddAttribute(attribute, true, points);
  for (draco::AttributeValueIndex::ValueType v = 0; v < points; ++v)
    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v), &values[std::size_t(v) * std::size_t(components)]);
  return int(mesh.attribute(id)->unique_id());
}

// The grid as one draco stream, quantized as exporters do by default (positions 14 bits, normals 10, texture
// coordinates 12; the tangents' generic attribute unquantized), its accessors sized by what the stream decodes to.
GltfBuilder dracoGrid(const GridMesh& grid) {
  draco::Mesh mesh;
  mesh.set_num_points(std::uint32_t(grid.vertexCount()));
  nlohmann::json ids = {{"POSITION", addDracoAttribute(mesh, draco::GeometryAttribute::POSITION, 3, grid.positions)},
                        {"NORMAL", addDracoAttribute(mesh, draco::GeometryAttribute::NORMAL, 3, grid.normals)},
                        {"TEXCOORD_0", addDracoAttribute(mesh, draco::GeometryAttribute::TEX_COORD, 2, grid.texCoords)},
                        {"TANGENT", addDracoAttribute(mesh, draco::GeometryAttribute::GENERIC, 4, grid.tangents)}};
  for (std::size_t i = 0; i < grid.indices.size(); i += 3)
    mesh.AddFace({draco::PointIndex(grid.indices[i]), draco::PointIndex(grid.indices[i + 1]), draco::PointIndex(grid.indices[i + 2])});
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer encoded;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(mesh, &encoded).ok());
  const std::string stream(encoded.data(), encoded.size());
  draco::DecoderBuffer decodable;
  decodable.Init(stream.data(), stream.size());
  draco::Decoder decoder;
  const auto decoded = decoder.DecodeMeshFromBuffer(&decodable);
  EXPECT_TRUE(decoded.ok());
  const std::size_t points = decoded.value()->num_points(), faces = decoded.value()->num_faces();

  GltfBuilder builder;
  builder.uses("KHR_draco_mesh_compression");
  const int view = builder.view(stream);
  builder.primitive({{"attributes",
                      {{"POSITION", builder.accessor(-1, 5126, points, "VEC3")},
                       {"NORMAL", builder.accessor(-1, 5126, points, "VEC3")},
                       {"TEXCOORD_0", builder.accessor(-1, 5126, points, "VEC2")},
                       {"TANGENT", builder.accessor(-1, 5126, points, "VEC4")}}},
                     {"indices", builder.accessor(-1, 5125, 3 * faces, "SCALAR")},
                     {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", ids}}}}}});
  return builder;
}

Scene plainGrid(const GridMesh& grid, const fs::path& file) {
  GltfBuilder builder;
  builder.primitive(test::plainGridPrimitive(builder, grid));
  return loadGltfScene(builder.writeGltf(file));
}

TEST_F(GltfDracoWebp, ADracoCompressedPrimitiveDecodesToTheGridWithinItsQuantization) {
  const Scene draco = loadGltfScene(dracoGrid(grid_).writeGlb(folder_ / "draco.glb"));
  // Positions: 14 bits over the grid's extent of 1, within one step (6.2e-5). Normals: 10-bit octahedral,
  // within 0.005 per component. Texture coordinates: 12 bits over [0, 1], within one step (2.5e-4). Tangents:
  // unquantized, exact.
  test::expectSameTriangles(plainGrid(grid_, folder_ / "plain.gltf"), draco, {6.2e-5f, 0.005f, 2.5e-4f, 0.0f});
}

TEST_F(GltfDracoWebp, ACorruptDracoStreamIsRefusedNamingTheMeshAndPrimitive) {
  GltfBuilder builder = dracoGrid(grid_);
  builder.doc["bufferViews"][0]["byteLength"] = 12;  // the stream cut short
  const fs::path file = builder.writeGltf(folder_ / "cut.gltf");
  const std::string message = errorOf<std::runtime_error>(file);
  EXPECT_NE(message.find("glTF file '" + file.string() + "' is corrupt: mesh 0 primitive 0 "
                         "(KHR_draco_mesh_compression)'s draco stream does not decode"),
            std::string::npos)
      << message;
}

TEST_F(GltfDracoWebp, ADracoStreamThatDoesNotMatchItsAccessorsIsRefused) {
  GltfBuilder builder = dracoGrid(grid_);
  builder.doc["accessors"][0]["count"] = 7;  // POSITION: not the stream's point count
  const fs::path file = builder.writeGltf(folder_ / "count.gltf");
  EXPECT_NE(errorOf<std::runtime_error>(file).find("draco attribute POSITION does not match its accessor's type and count"),
            std::string::npos);
}

// The exporter's file of glTF-Sample-Models (Debian's assimp-testmodels): 29 meshes whose POSITION accessors
// declare the bounds of their decoded positions.
TEST_F(GltfDracoWebp, ARealDracoFileDecodesWithinTheBoundsItsAccessorsDeclare) {
  const fs::path original = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
  if (!fs::exists(original)) GTEST_SKIP() << original << " is absent: install Debian's assimp-testmodels (.ci/install-deps)";
  std::ifstream in(original);
  nlohmann::json doc = nlohmann::json::parse(in);
  // Its camera's depth range (0.05 to 1e6) is past what the renderer resolves (refused on its own): dropped.
  doc.erase("cameras");
  for (auto& node : doc["nodes"]) node.erase("camera");
  const fs::path file = folder_ / "engine.gltf";
  std::ofstream(file) << doc.dump();
  fs::copy_file(original.parent_path() / "2CylinderEngine.bin", folder_ / "2CylinderEngine.bin");
  const Scene scene = loadGltfScene(file);
  glm::vec3 declaredMin(1e30f), declaredMax(-1e30f), loadedMin(1e30f), loadedMax(-1e30f);
  for (const auto& mesh : doc["meshes"])
    for (const auto& primitive : mesh["primitives"]) {
      const auto& accessor = doc["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()];
      for (int c = 0; c < 3; ++c) {
        declaredMin[c] = std::min(declaredMin[c], accessor["min"][std::size_t(c)].get<float>());
        declaredMax[c] = std::max(declaredMax[c], accessor["max"][std::size_t(c)].get<float>());
      }
    }
  for (const Mesh& mesh : scene.meshes)
    for (const Vertex& vertex : mesh.vertices) {
      loadedMin = glm::min(loadedMin, vertex.position);
      loadedMax = glm::max(loadedMax, vertex.position);
    }
  EXPECT_GE(scene.objects.size(), 29u);
  // The exporter quantized the positions (with bits the JSON does not name; the largest difference measured is
  // 1.6e-4 of the extent): within 1/1000 of the extent, which still tells positions from a mismatched attribute.
  const float tolerance = 1e-3f * glm::length(declaredMax - declaredMin);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(loadedMin[c], declaredMin[c], tolerance) << c;
    EXPECT_NEAR(loadedMax[c], declaredMax[c], tolerance) << c;
  }
}

// Debian's libdraco.so exports its own copies of tinygltf (another version) and stb_image; the link order
// (s3d_draco in CMakeLists.txt) gives every caller Debian's libtinygltf and libstb instead.
TEST(GltfDracoLinking, TinygltfAndStbImageComeFromTheirOwnLibrariesNotDracos) {
  const auto libraryOf = [](void* symbol) {
    Dl_info info{};
    return dladdr(symbol, &info) != 0 && info.dli_fname ? std::string(info.dli_fname) : std::string("(none)");
  };
  const std::string tinygltf = libraryOf(reinterpret_cast<void*>(&tinygltf::LoadImageData));
  const std::string stb = libraryOf(reinterpret_cast<void*>(&stbi_info_from_memory));
  EXPECT_NE(tinygltf.find("libtinygltf"), std::string::npos) << tinygltf;
  EXPECT_NE(stb.find("libstb"), std::string::npos) << stb;
}

// ---- EXT_texture_webp ----

// The textured quad (tests/data) copied in; returns its JSON.
nlohmann::json copyOfTexturedQuad(const fs::path& folder) {
  for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_base_color.png", "textured_quad_normal.png"})
    fs::copy_file(kDataDir / name, folder / name);
  std::ifstream in(folder / "textured_quad.gltf");
  return nlohmann::json::parse(in);
}

std::string losslessWebp(const Texture& texture) {
  std::uint8_t* output = nullptr;
  const std::size_t size = WebPEncodeLosslessRGBA(texture.rgba.data(), int(texture.width), int(texture.height),
                                                  int(texture.width) * 4, &output);
  std::string bytes(reinterpret_cast<const char*>(output), size);
  WebPFree(output);
  return bytes;
}

// The quad with its base color texture (texture 0) showing image 2 through EXT_texture_webp only.
fs::path withWebpBaseColor(nlohmann::json doc, const nlohmann::json& image, const fs::path& file) {
  doc["images"].push_back(image);
  doc["textures"][0] = {{"sampler", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 2}}}}}};
  doc["extensionsUsed"].push_back("EXT_texture_webp");
  doc["extensionsRequired"] = {"EXT_texture_webp"};
  std::ofstream(file) << doc.dump();
  return file;
}

TEST_F(GltfDracoWebp, AWebpTextureLoadsAsTheSamePixelsAsThePng) {
  const nlohmann::json doc = copyOfTexturedQuad(folder_);
  const Scene png = loadGltfScene(folder_ / "textured_quad.gltf");
  const Texture& expected = png.textures.at(std::size_t(png.objects.at(0).material.baseColorTexture));
  std::ofstream(folder_ / "base_color.webp", std::ios::binary) << losslessWebp(expected);
  const Scene webp = loadGltfScene(withWebpBaseColor(doc, {{"uri", "base_color.webp"}}, folder_ / "webp.gltf"));
  const Texture& actual = webp.textures.at(std::size_t(webp.objects.at(0).material.baseColorTexture));
  EXPECT_EQ(actual.width, expected.width);
  EXPECT_EQ(actual.height, expected.height);
  EXPECT_EQ(actual.encoding, Texture::Encoding::Srgb);
  EXPECT_TRUE(actual.rgba == expected.rgba) << "lossless WebP: every byte equal";
}

TEST_F(GltfDracoWebp, AWebpTextureInADataUriLoads) {
  const nlohmann::json doc = copyOfTexturedQuad(folder_);
  const Scene png = loadGltfScene(folder_ / "textured_quad.gltf");
  const Texture& expected = png.textures.at(std::size_t(png.objects.at(0).material.baseColorTexture));
  const nlohmann::json image = {{"uri", "data:image/webp;base64," + test::base64(losslessWebp(expected))}};
  const Scene webp = loadGltfScene(withWebpBaseColor(doc, image, folder_ / "webp.gltf"));
  EXPECT_TRUE(webp.textures.at(std::size_t(webp.objects.at(0).material.baseColorTexture)).rgba == expected.rgba);
}

// A lossless WebP header (RIFF, VP8L) declaring `width` x `height` (at most 16384 a side) over a few bytes.
std::string webpHeaderClaiming(std::uint32_t width, std::uint32_t height) {
  const std::uint32_t size = (width - 1) | ((height - 1) << 14) | (1u << 28);  // 14-bit sides less one, alpha
  const std::string vp8l = std::string("\x2f", 1) + test::bytesOf(&size, 4) + std::string(11, '\0');
  const auto word = [](std::uint32_t value) { return test::bytesOf(&value, 4); };
  const std::string chunk = "VP8L" + word(std::uint32_t(vp8l.size())) + vp8l;
  return "RIFF" + word(std::uint32_t(4 + chunk.size())) + "WEBP" + chunk;
}

TEST_F(GltfDracoWebp, AWebpTextureBeyondTheImageLimitIsRefusedBeforeDecoding) {
  const nlohmann::json doc = copyOfTexturedQuad(folder_);
  // 16384 x 16384: within the side limit, past the 2^26 pixels in all (1 GiB decoded from 36 bytes).
  std::ofstream(folder_ / "huge.webp", std::ios::binary) << webpHeaderClaiming(16384, 16384);
  const fs::path file = withWebpBaseColor(doc, {{"uri", "huge.webp"}}, folder_ / "webp.gltf");
  const std::string message = errorOf<std::runtime_error>(file);
  EXPECT_NE(message.find("glTF file '" + file.string() + "' cannot be loaded: image 2 is 16384x16384, beyond the readers' limit"),
            std::string::npos)
      << message;
}

TEST_F(GltfDracoWebp, ACorruptWebpTextureIsRefused) {
  const nlohmann::json doc = copyOfTexturedQuad(folder_);
  const Scene png = loadGltfScene(folder_ / "textured_quad.gltf");
  const std::string webp = losslessWebp(png.textures.at(0));
  std::ofstream(folder_ / "cut.webp", std::ios::binary) << webp.substr(0, webp.size() / 2);  // its header intact
  const fs::path file = withWebpBaseColor(doc, {{"uri", "cut.webp"}}, folder_ / "webp.gltf");
  const std::string message = errorOf<std::runtime_error>(file);
  EXPECT_NE(message.find("image 2 is a WebP file that does not decode"), std::string::npos) << message;
}

// The fuzz target's seeds for these extensions (tests/fuzz/corpus/README.md) are the grid: each loads as it,
// within the loosest step of the encodings above (draco's positions and texture coordinates, meshopt's
// octahedral normals, quantized tangents).
TEST_F(GltfDracoWebp, TheCompressedFuzzSeedsLoadAsTheGrid) {
  const Scene plain = plainGrid(grid_, folder_ / "plain.gltf");
  for (const char* seed : {"quantized.glb", "meshopt_triangles.glb", "meshopt_sequence.glb", "draco.glb", "webp_texture.glb"}) {
    SCOPED_TRACE(seed);
    test::expectSameTriangles(plain, loadGltfScene(kDataDir / ".." / "fuzz" / "corpus" / "gltf_scene" / seed),
                              {6.2e-5f, 0.02f, 2.5e-4f, 1e-4f});
  }
}

}  // namespace
}  // namespace s3d::renderer
