// glTF material features beyond metallic-roughness (renderer/src/gltf_material_extras.cpp): alphaMode MASK
// with alphaCutoff, doubleSided, KHR_texture_transform, emissiveFactor with KHR_materials_emissive_strength,
// and the errors for what the renderer cannot draw. Each test edits a copy of tests/data/textured_quad.gltf
// (written by tests/data/make_textured_quad.py).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "io_test_support.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;

const fs::path kDataDir = S3D_TEST_DATA_DIR;

// A copy of the textured quad in a scratch folder, with its material's JSON edited.
class EditedQuad {
 public:
  EditedQuad() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = fs::temp_directory_path() / ("s3d_gltf_material_" + std::string(info->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_base_color.png",
                             "textured_quad_normal.png"})
      fs::copy_file(kDataDir / name, folder_ / name);
    std::ifstream in(file(), std::ios::binary);
    text_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ~EditedQuad() { fs::remove_all(folder_); }
  fs::path file() const { return folder_ / "textured_quad.gltf"; }

  // Replaces the first `from` in the file with `to` (a test failure when it is missing).
  EditedQuad& replace(const std::string& from, const std::string& to) {
    const std::size_t at = text_.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text_.replace(at, from.size(), to);
    std::ofstream(file(), std::ios::binary) << text_;
    return *this;
  }
  // Adds JSON members to the material named "quadrants".
  EditedQuad& addToMaterial(const std::string& members) { return replace("\"name\": \"quadrants\",", "\"name\": \"quadrants\", " + members + ","); }
  EditedQuad& addToBaseColorTexture(const std::string& members) {
    return replace("\"baseColorTexture\": {", "\"baseColorTexture\": {" + members + ",");
  }

 private:
  fs::path folder_;
  std::string text_;
};

using test::errorOf;

TEST(GltfMaterials, MaskMaterialsAreOpaqueCutoutsWithTheirCutoffAndFactorAlpha) {
  EditedQuad quad;
  quad.addToMaterial("\"alphaMode\": \"MASK\", \"alphaCutoff\": 0.3")
      .replace("\"metallicFactor\": 0.0", "\"baseColorFactor\": [1.0, 1.0, 1.0, 0.75], \"metallicFactor\": 0.0");
  const Material material = loadGltfScene(quad.file()).objects.at(0).material;
  EXPECT_TRUE(material.isCutout());
  EXPECT_FALSE(material.isTransparent());
  EXPECT_FLOAT_EQ(material.alphaCutoff, 0.3f);
  EXPECT_FLOAT_EQ(material.cutoutAlpha, 0.75f);
  EXPECT_FLOAT_EQ(material.opacity, 1.0f);
}

TEST(GltfMaterials, AMaskWithoutACutoffUsesGltfsDefaultOfAHalf) {
  EditedQuad quad;
  quad.addToMaterial("\"alphaMode\": \"MASK\"");
  EXPECT_FLOAT_EQ(loadGltfScene(quad.file()).objects.at(0).material.alphaCutoff, 0.5f);
}

TEST(GltfMaterials, OpaqueAndBlendMaterialsAreNoCutoutsAndDoubleSidedIsRead) {
  EditedQuad quad;
  EXPECT_FALSE(loadGltfScene(quad.file()).objects.at(0).material.isCutout());
  EXPECT_FALSE(loadGltfScene(quad.file()).objects.at(0).material.doubleSided);
  quad.addToMaterial("\"doubleSided\": true");
  EXPECT_TRUE(loadGltfScene(quad.file()).objects.at(0).material.doubleSided);
}

TEST(GltfMaterials, TextureTransformsAreReadPerTexture) {
  EditedQuad quad;
  quad.addToBaseColorTexture(
          "\"extensions\": {\"KHR_texture_transform\": {\"offset\": [0.5, 0.25], \"rotation\": 0.4, \"scale\": [2, 3]}}")
      .replace("\"extensionsUsed\": [", "\"extensionsRequired\": [\"KHR_texture_transform\"], \"extensionsUsed\": [\"KHR_texture_transform\", ");
  const Material material = loadGltfScene(quad.file()).objects.at(0).material;
  EXPECT_EQ(material.baseColorTransform.offset, glm::vec2(0.5f, 0.25f));
  EXPECT_FLOAT_EQ(material.baseColorTransform.rotation, 0.4f);
  EXPECT_EQ(material.baseColorTransform.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_TRUE(material.normalTransform.isIdentity());
}

TEST(GltfMaterials, ATextureTransformOntoAnotherTexCoordSetIsRefusedNamingTheMaterial) {
  EditedQuad quad;
  quad.addToBaseColorTexture("\"extensions\": {\"KHR_texture_transform\": {\"texCoord\": 1}}");
  const std::string message = errorOf<std::invalid_argument>([&] { loadGltfScene(quad.file()); });
  EXPECT_NE(message.find(quad.file().string()), std::string::npos) << message;
  EXPECT_NE(message.find("material 0 ('quadrants')"), std::string::npos) << message;
  EXPECT_NE(message.find("TEXCOORD_1"), std::string::npos) << message;
}

TEST(GltfMaterials, EmissionIsTheFactorTimesTheStrength) {
  EditedQuad quad;
  quad.addToMaterial(
      "\"emissiveFactor\": [0.5, 0.25, 1.0], "
      "\"extensions\": {\"KHR_materials_emissive_strength\": {\"emissiveStrength\": 4.0}}");
  const Material material = loadGltfScene(quad.file()).objects.at(0).material;
  EXPECT_EQ(material.emissive, glm::vec3(2.0f, 1.0f, 4.0f));
}

TEST(GltfMaterials, ANegativeCutoffIsCorruptNamingTheMaterial) {
  EditedQuad quad;
  quad.addToMaterial("\"alphaMode\": \"MASK\", \"alphaCutoff\": -0.5");
  const std::string message = errorOf<std::runtime_error>([&] { loadGltfScene(quad.file()); });
  EXPECT_NE(message.find("material 0 ('quadrants')"), std::string::npos) << message;
  EXPECT_NE(message.find("alphaCutoff"), std::string::npos) << message;
}

}  // namespace
}  // namespace s3d::renderer
