// Supersampling anti-aliasing in the deferred renderer: the passes run at N x the output size and the
// resolve averages each output pixel's samples (colour) and keeps the nearest sample's depth.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/srgb.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kWidth = 16, kHeight = 8;
constexpr float kWallDistance = 5.0f;

// A wall facing the camera whose top edge lies `edgeAbovePx` output pixels above the horizon, i.e. inside
// the row just above it (row kHeight / 2 - 1), which spans 0..1 pixel above the horizon.
Scene makeEdgeScene(float edgeAbovePx) {
  Scene scene;
  scene.name = "edge";
  scene.ambientOcclusion = false;  // SSAO's per-pixel pattern would differ between sample grids
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  scene.camera.position = glm::vec3(0.0f);
  const float pixelHeight = 2.0f * kWallDistance * std::tan(scene.camera.verticalFovRadians / 2.0f) / float(kHeight);
  const float top = edgeAbovePx * pixelHeight;
  Object wall;
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, top - 2.0f, -kWallDistance - 0.5f)) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(40.0f, 4.0f, 1.0f));
  scene.objects.push_back(wall);
  return scene;
}

struct Frame {
  ImageRGBA8 color;
  DepthImage depth;
};

class SupersamplingTest : public test::VulkanTest {
 protected:
  Frame render(const Scene& scene, std::uint32_t supersample) {
    DeferredRenderer renderer(context(), kWidth, kHeight, {supersample});
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
    return {renderer.readDisplayColor(), renderer.readLinearDepth()};
  }
};

TEST_F(SupersamplingTest, OutputsKeepTheOutputSize) {
  DeferredRenderer renderer(context(), kWidth, kHeight, {3});
  EXPECT_EQ(renderer.width(), kWidth);
  EXPECT_EQ(renderer.supersample(), 3u);
  Scene scene = makeEdgeScene(0.4f);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  EXPECT_EQ(renderer.readDisplayColor().width, kWidth);
  EXPECT_EQ(renderer.readLinearDepth().height, kHeight);
  EXPECT_EQ(renderer.readHdrColor().width, kWidth);
  EXPECT_EQ(renderer.readFirstPersonMask().size(), std::size_t(kWidth) * kHeight);
}

TEST_F(SupersamplingTest, RejectsAFactorOutsideOneToFour) {
  EXPECT_THROW(DeferredRenderer(context(), kWidth, kHeight, {0}), std::invalid_argument);
  EXPECT_THROW(DeferredRenderer(context(), kWidth, kHeight, {5}), std::invalid_argument);
  EXPECT_THROW(DeferredRenderer(context(), 8192, 8, {3}), std::invalid_argument);  // renders 24576 wide
}

TEST_F(SupersamplingTest, APixelHalfCoveredByAnEdgeIsTheAverageOfBothSurfaces) {
  // The edge at 0.4 px above the horizon: the single sample (0.5 px) sees sky, of the 2x2 samples the lower
  // pair (0.25 px) sees the wall and the upper pair (0.75 px) the sky.
  const Scene scene = makeEdgeScene(0.4f);
  const std::uint32_t edgeRow = kHeight / 2 - 1, x = kWidth / 2;
  const Frame single = render(scene, 1);
  const Frame supersampled = render(scene, 2);
  EXPECT_TRUE(std::isinf(*single.depth.at(x, edgeRow))) << "one sample per pixel: the edge row is sky";
  // Nearest sample's depth: the wall at 5 m (tolerance as for D32 depth at 5 m, see test_renderer).
  EXPECT_NEAR(*supersampled.depth.at(x, edgeRow), kWallDistance, 5e-3f);

  // Averaged in linear light: compare decoded values. Tolerance 2 % of full scale: the sky's colour changes
  // with direction across the quarter pixel between the sample rows, and 8-bit rounding.
  auto linear = [](const ImageRGBA8& image, std::uint32_t px, std::uint32_t py, int channel) {
    return stereo::srgbToLinear(float(image.at(px, py)[channel]) / 255.0f);
  };
  for (int channel = 0; channel < 3; ++channel) {
    const float sky = linear(supersampled.color, x, edgeRow - 1, channel);
    const float wall = linear(supersampled.color, x, edgeRow + 1, channel);
    EXPECT_NEAR(linear(supersampled.color, x, edgeRow, channel), 0.5f * (sky + wall), 0.02f) << "channel " << channel;
  }
}

TEST_F(SupersamplingTest, AFlatSurfaceLooksTheSameAtEveryFactor) {
  // Tolerance 1 level: the wall's shading is constant over its face; only 8-bit rounding differs.
  const Scene scene = makeEdgeScene(0.4f);
  const Frame single = render(scene, 1);
  const Frame supersampled = render(scene, 3);
  for (int channel = 0; channel < 3; ++channel)
    EXPECT_NEAR(supersampled.color.at(kWidth / 2, kHeight - 2)[channel], single.color.at(kWidth / 2, kHeight - 2)[channel], 1);
  EXPECT_NEAR(*supersampled.depth.at(kWidth / 2, kHeight - 2), *single.depth.at(kWidth / 2, kHeight - 2), 5e-3f);
}

}  // namespace
}  // namespace s3d::renderer
