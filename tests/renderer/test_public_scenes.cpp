// Public glTF scenes as their authors ship them (tests/data/scenes/README.md): each loads without conversion and
// renders a frame. They live in a cache filled by tests/data/scenes/fetch-scenes; without it these tests skip,
// naming the script.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_file.h"
#include "scene_cache.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;

struct PublicScene {
  const char* name;
  const char* file;            // in the scene's cache folder
  std::uint64_t triangles;     // drawn per frame, from the file (README.md)
};

std::ostream& operator<<(std::ostream& out, const PublicScene& scene) { return out << scene.name; }

const PublicScene kPublicScenes[] = {
    {"dungeon", "dungeon/level-dungeon.gltf", 25038},
    {"oak", "oak/oaktree.gltf", 555},
    {"humanoid", "humanoid/humanoid.gltf", 18496},
    {"engine", "engine/2CylinderEngine.glb", 121496},
};

class PublicScenes : public test::VulkanTest, public ::testing::WithParamInterface<PublicScene> {
 protected:
  fs::path file() const { return test::sceneCache() / GetParam().file; }
  bool inCache() const {
    std::error_code error;
    return fs::is_regular_file(file(), error);
  }
  std::string notInCache() const {
    return "public scene '" + std::string(GetParam().name) + "' is not in " + test::sceneCache().string() +
           ": run tests/data/scenes/fetch-scenes (or set S3D_SCENE_CACHE)";
  }
};

TEST_P(PublicScenes, LoadsAsShippedWithEveryTriangle) {
  if (!inCache()) GTEST_SKIP() << notInCache();
  const Scene scene = loadGltfScene(file());
  EXPECT_EQ(trianglesDrawn(scene), GetParam().triangles);
}

TEST_P(PublicScenes, RendersACenterFrameThatShowsTheScene) {
  // The scene description's camera looks at the scene: at least a tenth of the pixels hold a surface (finite
  // linear depth); an empty frame (the sky alone) or a frame of NaNs means the scene did not draw.
  if (!inCache()) GTEST_SKIP() << notInCache();
  const Scene scene = loadGltfScene(file());
  constexpr std::uint32_t kWidth = 160, kHeight = 90;
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  const DepthImage depth = renderer.readLinearDepth();
  std::size_t surface = 0;
  for (float d : depth.pixels) {
    ASSERT_FALSE(std::isnan(d));
    surface += std::isfinite(d) ? 1 : 0;
  }
  EXPECT_GT(surface, depth.pixels.size() / 10);
}

INSTANTIATE_TEST_SUITE_P(Cache, PublicScenes, ::testing::ValuesIn(kPublicScenes),
                         [](const ::testing::TestParamInfo<PublicScene>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace s3d::renderer
