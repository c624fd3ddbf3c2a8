// Hostile and careless input files, as a user or an attacker hands them to the loaders: each is refused with one
// clear error naming the file, in bounded time and memory (the loads run in a child process with a time and an
// address-space bound, tests/support/bounded_child.h), never a crash, a hang or a runaway allocation.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "bounded_child.h"
#include "s3d/app/regress_job.h"
#include "s3d/comfort/comfort_profile.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/view_configuration.h"
#include "s3d/json_document.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/tune/tune_script.h"

namespace s3d {
namespace {
namespace fs = std::filesystem;

// Generous for a load that should take milliseconds; the hangs found took minutes or forever.
constexpr double kSeconds = 20.0;
// The loads below need a few MiB; the runaway allocations found reached 16.8 GB.
constexpr std::uint64_t kMemory = std::uint64_t(1) << 30;

class HostileInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("s3d_hostile_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(folder_ / name, std::ios::binary) << text;
    return folder_ / name;
  }
  fs::path fifo(const std::string& name) const {
    const fs::path path = folder_ / name;
    EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    return path;
  }

  // The message `load` fails with, from a bounded child; fails the test on a hang, a crash or a success.
  static std::string errorOf(const std::function<void()>& load) {
    const test::ChildOutcome outcome = test::runBounded(
        [&]() -> std::string {
          try {
            load();
          } catch (const std::invalid_argument& error) {
            return error.what();
          } catch (const std::runtime_error& error) {
            return error.what();
          }
          return "loaded";
        },
        kSeconds, kMemory);
    EXPECT_TRUE(outcome.finished) << "hung (killed after " << kSeconds << " s) or crashed: " << outcome.message;
    EXPECT_NE(outcome.message, "loaded");
    EXPECT_EQ(outcome.message.find("exception: "), std::string::npos) << "an unclear error: " << outcome.message;
    return outcome.message;
  }

  fs::path folder_;
};

// A glTF document with one triangle (a data: URI buffer) under node 0 of scene 0.
nlohmann::json triangleGltf() {
  return nlohmann::json::parse(R"({
    "asset": {"version": "2.0"},
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0}],
    "scenes": [{"nodes": [0]}]
  })");
}

std::string nested(int depth) { return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']'); }

TEST_F(HostileInputs, TheTriangleSceneTheseCasesStartFromLoads) {
  const fs::path file = write("triangle.gltf", triangleGltf().dump());
  EXPECT_EQ(renderer::loadGltfScene(file).objects.size(), 1u);
}

TEST_F(HostileInputs, AGltfNestingArraysTwentyThousandDeepIsRefusedNotAStackOverflow) {
  nlohmann::json doc = triangleGltf();
  std::string text = doc.dump();
  text.insert(text.size() - 1, ",\"extras\":" + nested(20000));
  const fs::path file = write("deep.gltf", text);
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("deep.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("nests deeper than"), std::string::npos) << message;
}

TEST_F(HostileInputs, EveryJsonFileKindRefusesDeepNestingNamingTheFile) {
  const fs::path file = write("deep.json", "{\"a\":" + nested(20000) + "}");
  const std::vector<std::pair<const char*, std::function<void()>>> loaders = {
      {"comfort profile", [&] { comfort::loadComfortProfile(file); }},
      {"display profile", [&] { comfort::loadDisplayProfile(file); }},
      {"views file", [&] { comfort::loadViewConfiguration(file); }},
      {"suite file", [&] { app::loadRegressSuite(file); }},
  };
  for (const auto& [kind, load] : loaders) {
    const std::string message = errorOf(load);
    EXPECT_NE(message.find(std::string(kind) + " '" + file.string() + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("nests deeper than"), std::string::npos) << message;
  }
}

TEST_F(HostileInputs, AJsonSyntaxErrorNamesTheFileWithoutTheLibrarysTag) {
  const fs::path file = write("broken.json", "{\"a\": tru}");
  const std::string message = errorOf([&] { comfort::loadDisplayProfile(file); });
  EXPECT_NE(message.find("display profile '" + file.string() + "': not valid JSON"), std::string::npos) << message;
  EXPECT_EQ(message.find("[json.exception"), std::string::npos) << message;
}

TEST_F(HostileInputs, AFifoAsTheSceneFileIsRefusedAsAFifo) {
  const fs::path file = fifo("scene.gltf");
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("FIFO"), std::string::npos) << message;
  EXPECT_TRUE(test::runBounded([&] { return std::to_string(renderer::sceneFileInputs(file).size()); }, kSeconds, kMemory)
                  .finished)
      << "listing a FIFO scene's inputs hung";
}

TEST_F(HostileInputs, AFifoAsTheSceneDescriptionIsRefusedAsAFifo) {
  const fs::path file = write("room.gltf", triangleGltf().dump());
  fifo("room.scene.json");
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("room.scene.json"), std::string::npos) << message;
  EXPECT_NE(message.find("FIFO"), std::string::npos) << message;
}

TEST_F(HostileInputs, EveryOtherInputFileKindRefusesAFifoAsAFifo) {
  const fs::path file = fifo("input.json");
  const std::vector<std::function<void()>> loaders = {
      [&] { comfort::loadComfortProfile(file); }, [&] { comfort::loadDisplayProfile(file); },
      [&] { comfort::loadViewConfiguration(file); }, [&] { app::loadRegressSuite(file); },
      [&] { tune::loadScript(file); }};
  for (const auto& load : loaders) {
    const std::string message = errorOf(load);
    EXPECT_NE(message.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << message;
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  }
}

TEST_F(HostileInputs, NodesSharingChildrenAreRefusedBeforeAnExponentialWalk) {
  // 40 nodes, each listing the next twice: 2^40 paths through a small file.
  nlohmann::json doc = triangleGltf();
  doc["nodes"] = nlohmann::json::array();
  for (int i = 0; i < 40; ++i) doc["nodes"].push_back({{"children", {i + 1, i + 1}}});
  doc["nodes"].push_back({{"mesh", 0}});
  const fs::path file = write("shared.gltf", doc.dump());
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("node 40 is reached twice"), std::string::npos) << message;
}

TEST_F(HostileInputs, ANodeCycleIsRefused) {
  nlohmann::json doc = triangleGltf();
  doc["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
  const fs::path file = write("cycle.gltf", doc.dump());
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(file); }).find("node 0 is reached twice"), std::string::npos);
}

TEST_F(HostileInputs, AnAccessorCountOfTwoToThe32IsRefusedBeforeAllocating) {
  for (const char* attribute : {"POSITION", "indices"}) {
    nlohmann::json doc = triangleGltf();
    doc["accessors"].push_back({{"bufferView", 0}, {"componentType", 5125}, {"count", 4294967295u}, {"type", "SCALAR"}});
    if (std::string(attribute) == "POSITION")
      doc["accessors"][0]["count"] = 4294967295u;
    else
      doc["meshes"][0]["primitives"][0]["indices"] = 1;
    const fs::path file = write("count.gltf", doc.dump());
    const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
    EXPECT_NE(message.find("accessor reads past the end of its buffer"), std::string::npos) << attribute << ": " << message;
  }
}

TEST_F(HostileInputs, SceneDataPastTheMemoryLimitIsRefusedNamingTheLimit) {
  const fs::path file = write("triangle.gltf", triangleGltf().dump());
  const std::string message = errorOf([&] { renderer::loadGltfScene(file, 16); });  // 16 bytes: not even 3 positions
  EXPECT_NE(message.find("a scene may take in memory"), std::string::npos) << message;
}

TEST_F(HostileInputs, ACameraDepthRangePastFloatPrecisionIsRefusedNotAnEmptyFrame) {
  nlohmann::json doc = triangleGltf();
  doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 1e-30}, {"zfar", 1e30}}}}};
  doc["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}});
  doc["scenes"][0]["nodes"].push_back(1);
  const fs::path file = write("camera.gltf", doc.dump());
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("camera 0"), std::string::npos) << message;
  EXPECT_NE(message.find("far/near ratio"), std::string::npos) << message;
}

TEST_F(HostileInputs, ASceneDescriptionCameraReplacesAFileCameraPastFloatPrecision) {
  nlohmann::json doc = triangleGltf();  // real files ship such cameras (a CAD export: near 0.05, far 1e6)
  doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}, {"zfar", 1e6}}}}};
  doc["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}});
  doc["scenes"][0]["nodes"].push_back(1);
  const fs::path file = write("engine.gltf", doc.dump());
  write("engine.scene.json", R"({"camera": {"position": [0, 0, 4], "near": 0.1, "far": 100}})");
  const renderer::Scene scene = renderer::loadGltfScene(file);
  EXPECT_EQ(scene.camera.nearPlane, 0.1f);
  EXPECT_EQ(scene.camera.farPlane, 100.0f);
}

TEST_F(HostileInputs, ASceneDescriptionCameraPastFloatPrecisionIsRefused) {
  const fs::path file = write("room.gltf", triangleGltf().dump());
  write("room.scene.json", R"({"camera": {"near": 0.00001, "far": 1000000000}})");
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("room.scene.json"), std::string::npos) << message;
  EXPECT_NE(message.find("far/near ratio"), std::string::npos) << message;
}

TEST_F(HostileInputs, ANodeMatrixOverflowingFloatsIsRefusedNotAnEmptyFrame) {
  nlohmann::json doc = triangleGltf();
  doc["nodes"][0]["matrix"] = {1e39, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const fs::path file = write("matrix.gltf", doc.dump());
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(file); }).find("node 0's transform overflows"), std::string::npos);
}

TEST_F(HostileInputs, AScaleThatPushesVerticesPastFloatsIsRefused) {
  nlohmann::json doc = triangleGltf();
  doc["nodes"] = {{{"children", {1}}, {"scale", {1e20, 1e20, 1e20}}}, {{"mesh", 0}, {"scale", {1e20, 1e20, 1e20}}}};
  const fs::path file = write("scale.gltf", doc.dump());
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("overflows"), std::string::npos) << message;
}

TEST_F(HostileInputs, NumbersPastFloatsRangeAreRefusedBeforeTheyAreConverted) {
  nlohmann::json doc = triangleGltf();
  doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1e300, 1, 1, 1}}}}}};
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  const fs::path material = write("material.gltf", doc.dump());
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(material); }).find("baseColorFactor 1e+300 is not a number within"),
            std::string::npos);
  doc = triangleGltf();
  doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 1e300}, {"zfar", 1e301}}}}};
  doc["nodes"].push_back({{"camera", 0}});
  doc["scenes"][0]["nodes"].push_back(1);
  const fs::path camera = write("camera.gltf", doc.dump());
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(camera); }).find("within single precision"), std::string::npos);
}

TEST_F(HostileInputs, AnUncompressedViewOfAMeshoptFallbackBufferIsRefused) {
  // The fallback buffer as exporters write it (a length but no data), read by a view without the extension.
  nlohmann::json doc = triangleGltf();
  doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  doc["extensionsRequired"] = {"EXT_meshopt_compression"};
  doc["buffers"].push_back({{"byteLength", 4096}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  doc["bufferViews"][0]["buffer"] = 1;
  const fs::path file = write("meshopt.gltf", doc.dump());
  const std::string message = errorOf([&] { renderer::loadGltfScene(file); });
  EXPECT_NE(message.find("meshopt.gltf' is corrupt: POSITION accessor reads past the end of its buffer"), std::string::npos)
      << message;
}

TEST_F(HostileInputs, UnnamedNodesAndMaterialsAreNamedByIndex) {
  nlohmann::json doc = triangleGltf();
  doc["materials"] = {{{"name", "leaves"}, {"alphaMode", "MASK"}, {"alphaCutoff", -1.0}}};
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  const fs::path material = write("material.gltf", doc.dump());
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(material); }).find("material 0 ('leaves')'s alphaCutoff"), std::string::npos);
  doc = triangleGltf();
  doc["skins"] = {{{"joints", {0}}}};
  doc["nodes"][0]["skin"] = 0;
  const fs::path skin = write("skin.gltf", doc.dump());
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(skin); }).find("mesh 0 primitive 0's JOINTS_0 and WEIGHTS_0 are not both present"),
            std::string::npos);
}

TEST_F(HostileInputs, AnEmptyGlbIsRefusedClearly) {
  // Found by fuzz_gltf_scene: tinygltf indexed the first byte of an empty file and threw std::out_of_range.
  const fs::path file = write("empty.glb", "");
  EXPECT_NE(errorOf([&] { renderer::loadGltfScene(file); }).find("is empty"), std::string::npos);
}

TEST(JsonDocument, NestingUpToTheLimitParses) {
  EXPECT_NO_THROW(parseJsonDocument(nested(kMaxJsonDepth), "test"));
  EXPECT_THROW(parseJsonDocument(nested(kMaxJsonDepth + 1), "test"), InputFileError);
}

}  // namespace
}  // namespace s3d
