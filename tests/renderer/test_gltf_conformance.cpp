// The glTF files of Debian's assimp-testmodels (/usr/share/assimp/models/glTF2: Khronos sample models,
// glTF-Asset-Generator cases and assimp's failure cases): each loads, or is refused with one clear error naming
// the file (std::runtime_error or std::invalid_argument, starting "glTF file '<path>'"), never a crash or a hang
// (each load runs in a bounded child process, tests/support/bounded_child.h). The expected outcome of every file is
// listed, so a change of behaviour fails its case. Skipped when the package is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bounded_child.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models/glTF2";
// Generous for loads that take milliseconds; the largest file here is 1.3 MB.
constexpr double kSeconds = 30.0;
constexpr std::uint64_t kMemory = std::uint64_t(2) << 30;

struct Case {
  const char* file;      // under kModels
  const char* expected;  // "loads", or a phrase of the error it is refused with
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.file; }

const Case kCases[] = {
    {"2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "camera 0: its depth range 0.04999999701976776 to 1e+06 spans a far/near ratio"},
    {"BoxBadNormals-glTF-Binary/BoxBadNormals.glb", "loads"},
    {"BoxTexcoords-glTF/boxTexcoords.gltf", "loads"},
    {"BoxTextured-glTF-Binary/BoxTextured.glb", "loads"},
    {"BoxTextured-glTF-Embedded/BoxTextured.gltf", "loads"},
    {"BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf", "loads"},
    {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "the required extension 'KHR_technique_webgl' is not supported"},
    {"BoxTextured-glTF/BoxTextured.gltf", "loads"},
    {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "is corrupt: POSITION contains a non-finite value"},
    {"ClearCoat-glTF/ClearCoatTest.gltf", "loads"},
    {"IncorrectVertexArrays/Cube.gltf", "a primitive of points or lines (mode 1) is not supported"},
    {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "is corrupt: a primitive's index 65535 is out of range"},
    {"IndexOutOfRange/IndexOutOfRange.gltf", "is corrupt: a primitive's index 255 is out of range"},
    {"MissingBin/BoxTextured.gltf", "cannot be loaded: File not found : BoxTextured0.bin"},
    {"RecursiveNodes/RecursiveNodes.gltf", "is corrupt: node 0 is reached twice"},
    {"SchemaFailures/sceneWrongType.gltf", "cannot be loaded: File not found : BoxTextured0.bin"},
    {"TestNoRootNode/NoScene.gltf", "is corrupt: it has no scene"},
    {"TestNoRootNode/SceneWithoutNodes.gltf", "is corrupt: its scene has no triangle meshes"},
    {"cameras/Cameras.gltf", "loads"},
    {"draco/2CylinderEngine.gltf", "camera 0: its depth range 0.04999999701976776 to 1e+06 spans a far/near ratio"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", "a primitive of points or lines (mode 0) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf", "a primitive of points or lines (mode 1) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf", "a primitive of points or lines (mode 2) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf", "a primitive of points or lines (mode 3) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf", "a primitive of points or lines (mode 0) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf", "a primitive of points or lines (mode 1) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf", "a primitive of points or lines (mode 2) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf", "a primitive of points or lines (mode 3) is not supported"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_11.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_14.gltf", "loads"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_15.gltf", "loads"},
    {"glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", "morph targets is not supported"},
    {"issue_3269/texcoord_crash.gltf", "is corrupt: a textured primitive of mesh 0 has no TEXCOORD_0"},
    {"simple_skin/simple_skin.gltf", "loads"},
    {"textureTransform/TextureTransformTest.gltf", "loads"},
    {"wrongTypes/badArray.gltf", "is corrupt: its scene has no triangle meshes"},
    {"wrongTypes/badExtension.gltf", "loads"},
    {"wrongTypes/badNumber.gltf", "loads"},
    {"wrongTypes/badObject.gltf", "loads"},
    {"wrongTypes/badString.gltf", "loads"},
    {"wrongTypes/badUint.gltf", "loads"},
};

class GltfConformance : public ::testing::TestWithParam<Case> {};

// "loads", or the message of the clear error the load throws; anything else escaping is reported as such.
std::string outcomeOf(const fs::path& file) {
  try {
    loadGltfScene(file);
    return "loads";
  } catch (const std::invalid_argument& error) {
    return error.what();
  } catch (const std::runtime_error& error) {
    return error.what();
  } catch (const std::exception& error) {
    return std::string("an unclear error: ") + error.what();
  }
}

TEST_P(GltfConformance, LoadsOrIsRefusedAsListed) {
  if (!fs::exists(kModels)) GTEST_SKIP() << kModels << " is absent: install Debian's assimp-testmodels (.ci/install-deps)";
  const fs::path file = kModels / GetParam().file;
  ASSERT_TRUE(fs::exists(file)) << file;
  const test::ChildOutcome outcome = test::runBounded([&] { return outcomeOf(file); }, kSeconds, kMemory);
  ASSERT_TRUE(outcome.finished) << "hung (killed after " << kSeconds << " s) or crashed: " << outcome.message;
  const std::string expected = GetParam().expected;
  if (expected == "loads") {
    EXPECT_EQ(outcome.message, "loads");
    return;
  }
  EXPECT_EQ(outcome.message.rfind("glTF file '" + file.string() + "'", 0), 0u) << outcome.message;
  EXPECT_NE(outcome.message.find(expected), std::string::npos) << outcome.message;
}

// Every .gltf and .glb of the package is listed above (a new file in a later package needs its expected outcome).
TEST(GltfConformanceList, NamesEveryFileOfThePackage) {
  if (!fs::exists(kModels)) GTEST_SKIP() << kModels << " is absent: install Debian's assimp-testmodels (.ci/install-deps)";
  std::vector<std::string> listed;
  for (const Case& c : kCases) listed.push_back(c.file);
  for (const auto& entry : fs::recursive_directory_iterator(kModels)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".gltf" && extension != ".glb") continue;
    const std::string relative = entry.path().lexically_relative(kModels).string();
    EXPECT_NE(std::find(listed.begin(), listed.end(), relative), listed.end()) << relative << " has no expected outcome";
  }
}

INSTANTIATE_TEST_SUITE_P(AssimpTestModels, GltfConformance, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           std::string name = fs::path(param.param.file).parent_path().filename().string() + "_" +
                                              fs::path(param.param.file).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace s3d::renderer
