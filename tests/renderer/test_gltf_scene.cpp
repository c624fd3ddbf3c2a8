// glTF 2.0 scenes (renderer/src/gltf_scene.cpp): what the loader takes from the file, the textured render, and
// the errors for missing, corrupt and unsupported files. The asset is tests/data/textured_quad.gltf, written by
// tests/data/make_textured_quad.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "io_test_support.h"
#include "png_test_support.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_file.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;

const fs::path kDataDir = S3D_TEST_DATA_DIR;
const fs::path kTexturedQuad = kDataDir / "textured_quad.gltf";

using test::errorOf;

// A scratch folder per test, removed afterwards.
class ScratchFolder : public test::ScratchFolder {
 public:
  ScratchFolder() : test::ScratchFolder("s3d_gltf_") {}

  // The test asset copied in, so a test can break one of its files.
  fs::path copyOfTexturedQuad() const {
    for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_base_color.png",
                             "textured_quad_normal.png"})
      fs::copy_file(kDataDir / name, path() / name);
    return path() / "textured_quad.gltf";
  }
};

void writeText(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(GltfScene, SceneFilesAreTellApartFromBuiltInNames) {
  EXPECT_TRUE(isSceneFile("a/b/scene.gltf"));
  EXPECT_TRUE(isSceneFile("scene.GLB"));
  EXPECT_FALSE(isSceneFile("courtyard"));
  EXPECT_EQ(sceneDescriptionPath("a/room.gltf"), fs::path("a/room.scene.json"));
}

TEST(GltfScene, LoadsTheQuadWithItsTexturesCameraAndSun) {
  const Scene scene = loadGltfScene(kTexturedQuad);
  ASSERT_EQ(scene.objects.size(), 1u);
  const Mesh& mesh = scene.meshes.at(scene.objects[0].mesh);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.indices.size(), 6u);
  ASSERT_EQ(mesh.texCoords.size(), 4u);
  // No TANGENT in the file: generated from the texture coordinates, +u runs along +x on this quad.
  ASSERT_EQ(mesh.tangents.size(), 4u);
  EXPECT_NEAR(glm::distance(glm::vec3(mesh.tangents[0]), glm::vec3(1.0f, 0.0f, 0.0f)), 0.0f, 1e-5f);
  EXPECT_EQ(mesh.tangents[0].w, 1.0f);  // green points up the image (-v, +y here): bitangent = +cross(n, t)

  const Material& material = scene.objects[0].material;
  ASSERT_GE(material.baseColorTexture, 0);
  ASSERT_GE(material.normalTexture, 0);
  EXPECT_EQ(scene.textures.at(std::size_t(material.baseColorTexture)).encoding, Texture::Encoding::Srgb);
  EXPECT_EQ(scene.textures.at(std::size_t(material.normalTexture)).encoding, Texture::Encoding::Linear);
  EXPECT_EQ(scene.textures[std::size_t(material.baseColorTexture)].width, 8u);
  EXPECT_FALSE(material.isTransparent());

  EXPECT_NEAR(glm::distance(scene.camera.position, glm::vec3(0.0f, 0.0f, 3.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(scene.camera.verticalFovRadians, 0.9f, 1e-6f);
  EXPECT_NEAR(scene.camera.yawRadians, 0.0f, 1e-6f);
  // The light node is turned -30 degrees about X: its +Z, towards the sun, tilts up by 30 degrees.
  EXPECT_NEAR(glm::distance(scene.sun.directionToSun, glm::vec3(0.0f, 0.5f, 0.8660254f)), 0.0f, 1e-5f);
  EXPECT_NEAR(scene.sun.color.r, 1.2f, 1e-6f);
  // From textured_quad.scene.json beside it.
  EXPECT_NEAR(scene.ambientColor.g, 0.2f, 1e-6f);
  EXPECT_FALSE(scene.ambientOcclusion);
}

TEST(GltfScene, TheGlbHoldsTheSameScene) {
  // textured_quad.glb: the same JSON with the buffer and both PNGs in its binary chunk; the .scene.json beside
  // it serves both (NAME.scene.json).
  const Scene text = loadGltfScene(kTexturedQuad), binary = loadGltfScene(kDataDir / "textured_quad.glb");
  ASSERT_EQ(binary.objects.size(), text.objects.size());
  ASSERT_EQ(binary.textures.size(), text.textures.size());
  for (std::size_t t = 0; t < text.textures.size(); ++t) EXPECT_EQ(binary.textures[t].rgba, text.textures[t].rgba);
  EXPECT_EQ(binary.meshes.at(0).indices, text.meshes.at(0).indices);
  EXPECT_EQ(binary.camera.position, text.camera.position);
  EXPECT_EQ(binary.ambientColor, text.ambientColor);
}

TEST(GltfScene, MetallicRoughnessMapsToAlbedoF0AndGlossiness) {
  // Roughness 1 is the widest lobe (exponent 2, glossiness 0); smoother surfaces are glossier.
  EXPECT_NEAR(glossinessFromRoughness(1.0f), 0.0f, 1e-6f);
  EXPECT_GT(glossinessFromRoughness(0.3f), glossinessFromRoughness(0.6f));
  EXPECT_NEAR(glossinessFromRoughness(0.0f), 1.0f, 1e-6f);
  // roughness 0.5: a = r^2 = 0.25, exponent 2 / a^2 - 2 = 30, glossiness (log2(30) - 1) / 10 = 0.3907.
  EXPECT_NEAR(glossinessFromRoughness(0.5f), 0.3907f, 1e-3f);
}

TEST(GltfScene, AMissingFileIsNamed) {
  const std::string message = errorOf<std::runtime_error>([] { loadGltfScene(kDataDir / "no_such.gltf"); });
  EXPECT_NE(message.find("no_such.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST(GltfScene, ACorruptFileIsNamed) {
  ScratchFolder scratch;
  const fs::path file = scratch.path() / "broken.gltf";
  writeText(file, "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ ");  // cut off mid-way
  const std::string message = errorOf<std::runtime_error>([&] { loadGltfScene(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not valid JSON: parse error at line 1"), std::string::npos) << message;
}

TEST(GltfScene, ATruncatedBufferIsNamed) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  const std::string bin = readText(scratch.path() / "textured_quad.bin");
  writeText(scratch.path() / "textured_quad.bin", bin.substr(0, 100));
  const std::string message = errorOf<std::runtime_error>([&] { loadGltfScene(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
}

TEST(GltfScene, AnAbsoluteBufferUriIsRefused) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(file, replaced(readText(file), "\"uri\": \"textured_quad.bin\"",
                           "\"uri\": \"" + (scratch.path() / "textured_quad.bin").string() + "\""));
  const std::string message = errorOf<std::invalid_argument>([&] { loadGltfScene(file); });
  EXPECT_NE(message.find("buffer 0 URI"), std::string::npos) << message;
  EXPECT_NE(message.find("absolute"), std::string::npos) << message;
}

TEST(GltfScene, AnImageUriClimbingOutOfTheFolderIsRefused) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  fs::create_directories(scratch.path() / "inner");
  fs::rename(file, scratch.path() / "inner" / "scene.gltf");
  fs::rename(scratch.path() / "textured_quad.bin", scratch.path() / "inner" / "textured_quad.bin");
  const fs::path moved = scratch.path() / "inner" / "scene.gltf";
  writeText(moved, replaced(readText(moved), "\"uri\": \"textured_quad_base_color.png\"",
                            "\"uri\": \"..%2Ftextured_quad_base_color.png\""));
  const std::string message = errorOf<std::invalid_argument>([&] { loadGltfScene(moved); });
  EXPECT_NE(message.find("image 0 URI"), std::string::npos) << message;
  EXPECT_NE(message.find("climbs out"), std::string::npos) << message;
}

TEST(GltfScene, AnImageUriLeadingOutThroughALinkIsRefused) {
  ScratchFolder scratch;
  scratch.copyOfTexturedQuad();
  fs::create_directories(scratch.path() / "outside");
  fs::rename(scratch.path() / "textured_quad_normal.png", scratch.path() / "outside" / "normal.png");
  fs::create_directories(scratch.path() / "scene");
  for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_base_color.png"})
    fs::rename(scratch.path() / name, scratch.path() / "scene" / name);
  fs::create_symlink(scratch.path() / "outside" / "normal.png", scratch.path() / "scene" / "textured_quad_normal.png");
  const std::string message =
      errorOf<std::invalid_argument>([&] { loadGltfScene(scratch.path() / "scene" / "textured_quad.gltf"); });
  EXPECT_NE(message.find("image 1 URI"), std::string::npos) << message;
  EXPECT_NE(message.find("through a link"), std::string::npos) << message;
}

// A PNG of 45 bytes whose header declares an 8-bit grey width x height image: stb_image would decode it (it
// refuses 4-channel images beyond 1 GB itself, but a grey one of 20000x20000 passes and becomes 1.6 GB of RGBA).
std::string pngHeaderClaiming(std::uint32_t width, std::uint32_t height) {
  auto bigEndian = [](std::uint32_t value) {
    return std::string{char(value >> 24), char((value >> 16) & 0xff), char((value >> 8) & 0xff), char(value & 0xff)};
  };
  auto crc32 = [](const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (unsigned char byte : bytes) {
      crc ^= byte;
      for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  const std::string ihdr = "IHDR" + bigEndian(width) + bigEndian(height) + std::string("\x08\x00\x00\x00\x00", 5);
  const std::string idat = "IDAT" + std::string("\x78\x01", 2);
  return std::string("\x89PNG\r\n\x1a\n", 8) + bigEndian(13) + ihdr + bigEndian(crc32(ihdr)) + bigEndian(2) + idat +
         bigEndian(crc32(idat));
}

// The error loading the textured quad whose base-colour texture file (image 0) holds `bytes`.
std::string errorWithBaseColorTexture(const std::string& bytes) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(scratch.path() / "textured_quad_base_color.png", bytes);
  return errorOf<std::runtime_error>([&] { loadGltfScene(file); });
}

TEST(GltfScene, ATextureBeyondTheReadersLimitsIsRefusedBeforeItIsDecoded) {
  const std::string message = errorWithBaseColorTexture(pngHeaderClaiming(20000, 20000));
  EXPECT_NE(message.find("textured_quad.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("20000x20000, beyond the readers' limit of 16384 pixels a side"), std::string::npos) << message;
}

TEST(GltfScene, ATextureInAFormatGltfDoesNotAllowIsRefused) {
  const std::string message = errorWithBaseColorTexture("RIFF");  // shorter than the WebP header it starts like
  EXPECT_NE(message.find("textured_quad.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("image 0 is neither a PNG, a JPEG nor a WebP file"), std::string::npos) << message;
}

TEST(GltfScene, AWebpTextureWhoseHeaderDoesNotReadIsNamedAsWebp) {
  const std::string message = errorWithBaseColorTexture(std::string("RIFF\x04\0\0\0WEBP", 12));
  EXPECT_NE(message.find("image 0 is a WebP file whose header does not read"), std::string::npos) << message;
}

TEST(GltfScene, EachHostileFuzzSeedIsRefusedByTheCheckItWasWrittenFor) {
  // tests/fuzz/corpus/gltf_scene (make_gltf_scene_seeds.py): each seed must reach the check it was written for.
  const fs::path corpus = kDataDir.parent_path() / "fuzz" / "corpus" / "gltf_scene";
  const std::vector<std::pair<const char*, const char*>> seeds{
      {"absolute_buffer_uri.glb", "is an absolute path"},
      {"escaping_image_uri.glb", "climbs out of the scene's folder"},
      {"encoded_escaping_image_uri.glb", "climbs out of the scene's folder"},
      {"oversized_texture.glb", "20000x20000, beyond the readers' limit"},
      {"oversized_data_uri_texture.glb", "20000x20000, beyond the readers' limit"},
      {"oversized_png_chunk.glb", "image 0 is a corrupt PNG: chunk 'IDAT' declares 1073741808 bytes, more than"},
      {"bmp_texture.glb", "image 0 is neither a PNG, a JPEG nor a WebP file"},
      {"image_view_index_past_32_bits.glb", "image 0's buffer view 4294967298 is not one of the file's buffer views"},
      {"image_view_past_buffer.glb", "image 0's buffer view 2 runs past the end of buffer 0"}};
  for (const auto& [seed, expected] : seeds) {
    std::string message;
    try {
      (void)loadGltfScene(corpus / seed);
    } catch (const std::exception& error) {
      message = error.what();
    }
    EXPECT_NE(message.find(expected), std::string::npos) << seed << ": " << message;
  }
}

TEST(GltfScene, ARequiredExtensionItCannotDrawIsNamed) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(file, replaced(readText(file), "\"extensionsUsed\": [", "\"extensionsRequired\": [\"KHR_texture_basisu\"], \"extensionsUsed\": ["));
  const std::string message = errorOf<std::invalid_argument>([&] { loadGltfScene(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("the required extension 'KHR_texture_basisu' is not supported (s3d reads KHR_lights_punctual, "
                         "KHR_mesh_quantization, EXT_meshopt_compression, KHR_draco_mesh_compression, EXT_texture_webp, "
                         "KHR_texture_transform, KHR_materials_emissive_strength)"),
            std::string::npos)
      << message;
}

TEST(GltfScene, BlendMaterialsAreTransparent) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(file, replaced(readText(file), "\"name\": \"quadrants\",", "\"name\": \"quadrants\", \"alphaMode\": \"BLEND\","));
  EXPECT_TRUE(loadGltfScene(file).objects.at(0).material.isTransparent());
}

// The quad with a second node placing a directional light rotated `rotation` (x, y, z, w).
fs::path quadWithSecondSunNode(const ScratchFolder& scratch, const std::string& rotation) {
  const fs::path file = scratch.copyOfTexturedQuad();
  std::string text = replaced(readText(file), "    0,\n    1,\n    2\n   ]", "    0,\n    1,\n    2,\n    3\n   ]");
  text = replaced(text, "\n ],\n \"cameras\"",
                  ",\n  {\"name\": \"sun again\", \"rotation\": [" + rotation +
                      "], \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}\n ],\n \"cameras\"");
  writeText(file, text);
  return file;
}

TEST(GltfScene, DirectionalLightsFromOneDirectionAddUpIntoTheSun) {
  ScratchFolder scratch;  // exported levels place one sun light twice; glTF counts each placement
  const Scene scene = loadGltfScene(quadWithSecondSunNode(scratch, "-0.258819, 0, 0, 0.965926"));
  EXPECT_NEAR(scene.sun.color.r, 2.4f, 1e-6f) << "twice the light's intensity 1.2";
}

TEST(GltfScene, ADirectionalLightFromAnotherDirectionIsRefusedUnlessTheDescriptionGivesTheSun) {
  ScratchFolder scratch;
  const fs::path file = quadWithSecondSunNode(scratch, "0, 0.7071068, 0, 0.7071068");
  const std::string message = errorOf<std::invalid_argument>([&] { loadGltfScene(file); });
  EXPECT_NE(message.find("directional light 0"), std::string::npos) << message;
  EXPECT_NE(message.find("textured_quad.scene.json"), std::string::npos) << message;
  writeText(scratch.path() / "textured_quad.scene.json", R"({"sun": {"directionToSun": [0, 1, 0]}})");
  EXPECT_EQ(loadGltfScene(file).sun.directionToSun, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(GltfScene, TheSceneDescriptionTurnsOnTheSunsShadows) {
  ScratchFolder scratch;  // glTF lights carry no shadow flag
  const fs::path file = scratch.copyOfTexturedQuad();
  EXPECT_FALSE(loadGltfScene(file).sun.castsShadows);
  writeText(sceneDescriptionPath(file), R"({"sun": {"castsShadows": true, "shadowDistance": 250}})");
  const Scene scene = loadGltfScene(file);
  EXPECT_TRUE(scene.sun.castsShadows);
  EXPECT_EQ(scene.sun.shadowDistance, 250.0f);
}

TEST(GltfScene, AnExtensionTheFileUsesButDoesNotRequireIsAWarningNotAnError) {
  // glTF lets a renderer ignore an extension the file does not require (here unlit shading); the scene loads and
  // says what it left out, naming the file and the extension.
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(file, replaced(readText(file), "\"extensionsUsed\": [", "\"extensionsUsed\": [\"KHR_materials_unlit\", "));
  const Scene scene = loadGltfScene(file);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find(file.string()), std::string::npos) << scene.warnings[0];
  EXPECT_NE(scene.warnings[0].find("'KHR_materials_unlit'"), std::string::npos) << scene.warnings[0];
  EXPECT_TRUE(loadGltfScene(kTexturedQuad).warnings.empty()) << "it reads every extension the quad uses";
}

TEST(GltfScene, AnUnknownSceneDescriptionKeyIsNamed) {
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(sceneDescriptionPath(file), "{\"exposure\": 1.0, \"exposrue\": 2.0}");
  const std::string message = errorOf<std::invalid_argument>([&] { loadGltfScene(file); });
  EXPECT_NE(message.find("textured_quad.scene.json"), std::string::npos) << message;
  EXPECT_NE(message.find("exposrue"), std::string::npos) << message;
}

class GltfRenderTest : public test::VulkanTest {
 protected:
  static constexpr std::uint32_t kSize = 64;

  ImageRGBA8 render(const fs::path& file) {
    const Scene scene = loadGltfScene(file);
    DeferredRenderer renderer(context(), kSize, kSize);
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, 1.0f));
    return renderer.readDisplayColor();
  }
};

TEST_F(GltfRenderTest, TheNormalMapTiltsTheLightingTheWayGltfMeansIt) {
  // The sun comes from 30 degrees above the view axis (dimmed to 0.5 so tone mapping does not flatten the
  // differences). glTF normal maps point green up the image (+y on this quad): a map tilted 30 degrees towards
  // green faces the sun (N.L 1 instead of 0.87), one tilted 64 degrees away turns from it (N.L < 0: ambient
  // only). Red channel of the red quadrant; margins of 4 and 40 levels are a third of the differences these
  // N.L values give after tone mapping (12 and 138 levels on lavapipe). A flipped bitangent swaps the two.
  ScratchFolder scratch;
  const fs::path file = scratch.copyOfTexturedQuad();
  writeText(sceneDescriptionPath(file), R"({"sun": {"color": [0.5, 0.5, 0.5]}, "ambientOcclusion": false})");
  auto redWithNormal = [&](glm::vec3 tangentSpaceNormal) {
    ImageRGBA8 normalMap(8, 8);
    for (std::uint32_t i = 0; i < 64; ++i) {
      std::uint8_t* p = normalMap.at(i % 8, i / 8);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(std::lround((tangentSpaceNormal[c] * 0.5f + 0.5f) * 255.0f));
      p[3] = 255;
    }
    test::writePng(scratch.path() / "textured_quad_normal.png", normalMap);
    return float(render(file).at(21, 21)[0]);
  };
  const float flat = redWithNormal({0.0f, 0.0f, 1.0f});
  const float towardsGreen = redWithNormal({0.0f, 0.5f, 0.866f});
  const float awayFromGreen = redWithNormal({0.0f, -0.9f, 0.436f});
  EXPECT_GT(towardsGreen, flat + 4.0f);
  EXPECT_LT(awayFromGreen, flat - 40.0f);
  std::printf("red quadrant: flat normal map %.0f, tilted up %.0f, tilted down %.0f\n", flat, towardsGreen, awayFromGreen);
}

TEST_F(GltfRenderTest, TheTexturedQuadShowsItsQuadrantColoursWhereTheyBelong) {
  // 64x64, the quad 3 m away fills the middle; each quadrant's centre (uv 0.25/0.75) lands near pixel 21 / 43.
  // The sun, the ambient light and the specular lobe are white, so they add alike to every channel: only the
  // texture makes one channel stand out. Its ~220-vs-~40 texels must leave the texture's strong channels at
  // least 80 of 255 levels above its weak ones after lighting and tone mapping (untextured, all three match).
  // The fixture fails the test on any validation message.
  const ImageRGBA8 image = render(kTexturedQuad);
  auto pixel = [&](std::uint32_t x, std::uint32_t y) {
    const auto* p = image.at(x, y);
    return glm::vec3(p[0], p[1], p[2]);
  };
  const glm::vec3 topLeft = pixel(21, 21), topRight = pixel(43, 21), bottomLeft = pixel(21, 43), bottomRight = pixel(43, 43);
  constexpr float kMargin = 80.0f;
  EXPECT_GT(topLeft.r, std::max(topLeft.g, topLeft.b) + kMargin) << "red quadrant";
  EXPECT_GT(topRight.g, std::max(topRight.r, topRight.b) + kMargin) << "green quadrant";
  EXPECT_GT(bottomLeft.b, std::max(bottomLeft.r, bottomLeft.g) + kMargin) << "blue quadrant";
  EXPECT_GT(std::min(bottomRight.r, bottomRight.g), bottomRight.b + kMargin) << "yellow quadrant";
  // Around the quad: the dark sky of its scene description (0.02 linear, ~26 after tone mapping).
  EXPECT_LT(pixel(2, 2).r, 40.0f);
}

}  // namespace
}  // namespace s3d::renderer
