// The transparent pass's two implementations (RendererOptions::TransparentCompositing): a blended raster pass,
// and a compute pass that finds each pixel's transparent fragments itself (perspective-correct barycentrics at
// the pixel centre, the same depth test and blending order). Both must give the same image and the same
// transparent mask.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

using Compositing = RendererOptions::TransparentCompositing;

struct Frame {
  ImageRGBA8 color;
  std::vector<std::uint8_t> transparentMask;
};

class TransparentCompositingTest : public test::VulkanTest {
 protected:
  Frame render(const Scene& scene, RendererOptions options, Compositing compositing, std::uint32_t width,
               std::uint32_t height) {
    options.transparentCompositing = compositing;
    DeferredRenderer renderer(context(), width, height, options);
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, float(width) / float(height)));
    return {renderer.readDisplayColor(), renderer.readTransparentMask()};
  }

  // Colours within one level (the raster pass rounds the half-float target after each blended fragment, the
  // compute pass once) and the same transparent mask, except at a few pixels whose centre lies within rounding of
  // a pane's outline (the rasterizer snaps vertices to sub-pixel positions; the compute pass does not): at most
  // `edgePixels` may differ in either (none did on lavapipe at these sizes).
  void expectSameImage(const Scene& scene, RendererOptions options, std::uint32_t width, std::uint32_t height,
                       std::size_t edgePixels) {
    const Frame raster = render(scene, options, Compositing::Raster, width, height);
    const Frame compute = render(scene, options, Compositing::Compute, width, height);
    std::size_t colourOff = 0, maskOff = 0, covered = 0;
    for (std::size_t p = 0; p < std::size_t(width) * height; ++p) {
      int largest = 0;
      for (int c = 0; c < 4; ++c)
        largest = std::max(largest, std::abs(int(raster.color.pixels[4 * p + c]) - int(compute.color.pixels[4 * p + c])));
      colourOff += largest > 1 ? 1 : 0;
      maskOff += raster.transparentMask[p] != compute.transparentMask[p] ? 1 : 0;
      covered += raster.transparentMask[p];
    }
    EXPECT_GT(covered, 0u) << scene.name << ": no transparent pixel to compare";
    EXPECT_LE(colourOff, edgePixels) << scene.name;
    EXPECT_LE(maskOff, edgePixels) << scene.name;
  }
};

TEST_F(TransparentCompositingTest, TheGlassSceneLooksTheSameEitherWay) {
  expectSameImage(makeGlassScene(), {}, 160, 90, 4);
}

TEST_F(TransparentCompositingTest, TheGlassSceneLooksTheSameEitherWayWithReversedZ) {
  RendererOptions options;
  options.reversedZ = true;  // the world layer's depth range and the depth test mirrored
  expectSameImage(makeGlassScene(), options, 160, 90, 4);
}

TEST_F(TransparentCompositingTest, TheGlassSceneLooksTheSameEitherWayWithSupersampling) {
  RendererOptions options;
  options.supersample = 2;
  expectSameImage(makeGlassScene(), options, 96, 54, 4);
}

// A transparent floor reaching behind the eye: its triangles have vertices behind the eye plane, which the
// rasterizer clips and the compute pass must cover exactly as far as the clipped triangles reach.
TEST_F(TransparentCompositingTest, ATransparentFloorReachingBehindTheEyeLooksTheSameEitherWay) {
  Scene scene = makeGlassScene();
  Object floor;
  floor.mesh = 1;  // the unit box
  floor.material.albedo = glm::vec3(0.2f, 0.4f, 0.9f);
  floor.material.opacity = 0.4f;
  floor.transform = glm::scale(glm::translate(glm::mat4(1.0f), scene.camera.position + glm::vec3(0.0f, -0.5f, 0.0f)),
                               glm::vec3(6.0f, 0.02f, 30.0f));
  scene.objects.push_back(floor);
  expectSameImage(scene, {}, 160, 90, 4);
}

}  // namespace
}  // namespace s3d::renderer
