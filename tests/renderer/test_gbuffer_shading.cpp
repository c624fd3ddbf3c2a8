// The G-buffer pass's two shadings (RendererOptions::GBufferShading): raster shading evaluates each pixel's
// normal and material in the fragment shader; visibility shading rasterizes triangle ids and evaluates the same
// surface in a compute pass (the G-buffer resolve). Both must give the same image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/renderer/renderer_shared.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

using Shading = RendererOptions::GBufferShading;

struct Frame {
  ImageRGBA8 color;
  DepthImage depth;
};

// The largest difference between two images in any colour channel, in 8-bit levels.
int largestDifference(const ImageRGBA8& a, const ImageRGBA8& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
}

class GBufferShadingTest : public test::VulkanTest {
 protected:
  Frame render(const Scene& scene, Shading shading, std::uint32_t width, std::uint32_t height) {
    RendererOptions options;
    options.gbufferShading = shading;
    DeferredRenderer renderer(context(), width, height, options);
    EXPECT_EQ(renderer.gbufferShading(), shading);
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, float(width) / float(height)));
    return {renderer.readDisplayColor(), renderer.readLinearDepth()};
  }

  // Same depth (the same raster pass) and colours within one level: the normal reaches the half-float target
  // through a colour attachment in one and an image store in the other, whose roundings may differ by an ulp.
  void expectSameImage(const Scene& scene, std::uint32_t width, std::uint32_t height) {
    const Frame raster = render(scene, Shading::Raster, width, height);
    const Frame visibility = render(scene, Shading::Visibility, width, height);
    EXPECT_LE(largestDifference(raster.color, visibility.color), 1) << scene.name;
    EXPECT_EQ(raster.depth.pixels, visibility.depth.pixels) << scene.name;
  }
};

TEST(VisibilityPacking, NarrowIdsWhileObjectAndTriangleIndicesFit32Bits) {
  // 5 objects take 3 bits, leaving 29 for the triangle; the all-ones id stays free for S3D_RASTER_SHADED.
  EXPECT_EQ(gpu::visibilityPacking(5, (1u << 29) - 1), glm::uvec2(3, 0));
  EXPECT_EQ(gpu::visibilityPacking(5, 1u << 29), glm::uvec2(3, 1));
  EXPECT_EQ(gpu::visibilityPacking(1, 12), glm::uvec2(0, 0));
  EXPECT_EQ(gpu::visibilityPacking(65535, 65535), glm::uvec2(16, 0));
  EXPECT_EQ(gpu::visibilityPacking(65535, 65536), glm::uvec2(16, 1));
}

TEST(VisibilityPacking, IdsRoundTrip) {
  for (const glm::uvec4 options : {glm::uvec4(0, 0, 3, 0), glm::uvec4(0, 0, 0, 0), glm::uvec4(0, 0, 16, 1)}) {
    const std::uint32_t object = options.z == 0 && options.w == 0 ? 0u : 5u;
    const glm::uvec2 id = gpu::packVisibility(object, 123456u, options);
    EXPECT_EQ(gpu::unpackVisibilityObject(id, options), object);
    EXPECT_EQ(gpu::unpackVisibilityTriangle(id, options), 123456u);
    EXPECT_NE(id.x, S3D_RASTER_SHADED);
  }
}

TEST_F(GBufferShadingTest, EveryBuiltInSceneLooksTheSameEitherWay) {
  for (const char* name : {"courtyard", "glass", "fence", "cover", "depth-range"}) {
    Scene scene = makeBuiltInScene(name);
    expectSameImage(scene, 160, 90);
  }
}

TEST_F(GBufferShadingTest, AMaskedRenderResolvesTheMaskedPixelsAsAFullOneDoes) {
  // Every third pixel of every other row is masked: the G-buffer resolve runs over the mask's tiles only and must
  // give those pixels what the unmasked raster-shaded render gives them (within one level, as above).
  constexpr std::uint32_t kWidth = 160, kHeight = 90;
  const Scene scene = makeBuiltInScene("courtyard");
  const Frame full = render(scene, Shading::Raster, kWidth, kHeight);
  std::vector<std::uint32_t> values(std::size_t(kWidth) * kHeight, 0);
  for (std::uint32_t y = 0; y < kHeight; y += 2)
    for (std::uint32_t x = y % 3; x < kWidth; x += 3) values[std::size_t(y) * kWidth + x] = 1;
  vk::Image mask = vk::createImage(context(), VK_FORMAT_R32_UINT, kWidth, kHeight,
                                   VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context(), mask, std::as_bytes(std::span(values)), vk::kComputeWrite);
  RendererOptions options;
  options.gbufferShading = Shading::Visibility;
  DeferredRenderer renderer(context(), kWidth, kHeight, options);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)), ShadeMask{&mask, 1});
  const ImageRGBA8 masked = renderer.readDisplayColor();
  int largest = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (values[i] != 0)
      for (std::size_t c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(int(masked.pixels[4 * i + c]) - int(full.color.pixels[4 * i + c])));
  EXPECT_LE(largest, 1);
}

TEST_F(GBufferShadingTest, TexturedObjectsKeepTheirRasterShadedSurface) {
  // The glTF quad has a base-colour texture and a normal map: under visibility shading it writes its G-buffer in
  // the raster pass (S3D_RASTER_SHADED), untextured objects beside it get theirs from the resolve.
  Scene scene = loadGltfScene(std::filesystem::path(S3D_TEST_DATA_DIR) / "textured_quad.gltf");
  Object floor;
  floor.mesh = std::uint32_t(scene.meshes.size());
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  floor.transform = glm::translate(glm::mat4(1.0f), scene.camera.position + glm::vec3(0.0f, -1.5f, -3.0f)) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(6.0f, 0.2f, 6.0f));
  scene.objects.push_back(floor);
  expectSameImage(scene, 64, 64);
}

// A bumpy grid of `quads` x `quads` quads (two triangles each) facing +Z after `degenerate` zero-area triangles
// (nothing to draw, but they push the grid's triangle indices up), its vertex normals tilted by position, so a
// wrong triangle or barycentric shows as a wrong normal.
Mesh bumpyGrid(std::uint32_t quads, std::uint32_t degenerate = 0) {
  Mesh mesh;
  for (std::uint32_t y = 0; y <= quads; ++y)
    for (std::uint32_t x = 0; x <= quads; ++x) {
      const glm::vec2 p = glm::vec2(x, y) / float(quads) - 0.5f;
      mesh.vertices.push_back({glm::vec3(p, 0.0f), glm::normalize(glm::vec3(std::sin(9.0f * p.x), std::cos(7.0f * p.y), 1.5f))});
    }
  mesh.indices.assign(3 * std::size_t(degenerate), 0u);
  for (std::uint32_t y = 0; y < quads; ++y)
    for (std::uint32_t x = 0; x < quads; ++x) {
      const std::uint32_t i = y * (quads + 1) + x;
      for (std::uint32_t index : {i, i + 1, i + quads + 2, i, i + quads + 2, i + quads + 1}) mesh.indices.push_back(index);
    }
  return mesh;
}

TEST_F(GBufferShadingTest, WideIdsServeScenesWhoseIdsOverflow32Bits) {
  // 4097 objects take 13 bits, leaving 19 for a triangle: the grid's triangles come after 2^19 degenerate ones,
  // so their ids need wide packing. The grid fills the view; the other objects are small boxes behind the camera.
  Scene scene;
  scene.name = "wide-ids";
  scene.meshes.push_back(bumpyGrid(16, 1u << 19));
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  ASSERT_EQ(gpu::visibilityPacking(4097, scene.meshes[0].indices.size() / 3).y, 1u);
  Object grid;
  grid.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.7f, 4.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(8.0f));
  grid.castsShadow = false;
  scene.objects.push_back(grid);
  for (std::uint32_t i = 0; i < 4096; ++i) {
    Object box;
    box.mesh = 1;
    box.castsShadow = false;
    box.transform = glm::translate(glm::mat4(1.0f), glm::vec3(float(i % 64), float(i / 64), 40.0f)) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(0.2f));
    scene.objects.push_back(box);
  }
  scene.camera.position = glm::vec3(0.0f, 1.7f, 8.0f);
  expectSameImage(scene, 64, 36);
}

}  // namespace
}  // namespace s3d::renderer
