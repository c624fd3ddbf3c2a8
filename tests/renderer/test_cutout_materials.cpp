// Alpha cut-outs (Material::alphaCutoff, glTF alphaMode MASK) through the renderer: the centre view, its
// depth, the cut-out (foliage) mask and the sun's shadow map, each held to a CPU alpha test of the texture.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "material_test_scenes.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/vk/resources.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kSize = 64;
constexpr float kQuadDepth = 3.0f, kWallDepth = 5.0f;  // linear depth of the quad and of the wall behind it

// 8x8 texels whose alphas scatter over 0..1 (so the cut follows the filtered alpha, not texel edges).
Texture scatteredAlphaTexture() {
  Texture texture;
  texture.width = texture.height = 8;
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < 8; ++x)
      texture.rgba.insert(texture.rgba.end(), {255, 255, 255, std::uint8_t((x * 37 + y * 91 + x * y * 13) % 256)});
  return texture;
}

// A red cut-out quad 3 m in front of the camera, a blue wall `wallGap` behind it.
Scene cutoutScene(float cutoff, float cutoutAlpha, float wallGap = kWallDepth - kQuadDepth) {
  Scene scene;
  scene.name = "cut-out";
  scene.meshes = {test::makeTexturedQuad(), makeBox(glm::vec3(10.0f, 10.0f, 0.5f))};
  scene.textures = {scatteredAlphaTexture()};
  Object quad;
  quad.mesh = 0;
  quad.material.albedo = glm::vec3(0.8f, 0.05f, 0.05f);
  quad.material.baseColorTexture = 0;
  quad.material.alphaCutoff = cutoff;
  quad.material.cutoutAlpha = cutoutAlpha;
  Object wall;
  wall.mesh = 1;
  wall.material.albedo = glm::vec3(0.05f, 0.05f, 0.8f);
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -wallGap - 0.5f));  // front at z = -wallGap
  scene.objects = {quad, wall};
  scene.ambientOcclusion = false;
  scene.camera.position = glm::vec3(0.0f, 0.0f, kQuadDepth);
  scene.camera.pitchRadians = 0.0f;
  scene.camera.verticalFovRadians = 0.8f;
  return scene;
}

// The CPU alpha test per pixel: kept (the quad drawn), cut (the wall shows) or too close to the cutoff to call
// (the filtered alpha within 0.03 of it: lavapipe's bilinear weights have 8 fractional bits, and the pixel's
// texture coordinate is interpolated in float) or too close to the quad's edge (within 0.02 m).
enum class Expected { Kept, Cut, Either };
glm::vec2 quadPointAt(const Scene& scene, std::uint32_t x, std::uint32_t y) {
  const glm::vec3 ray = test::pixelRay(scene.camera, x, y, kSize, kSize);
  return glm::vec2(scene.camera.position + ray * (kQuadDepth / -ray.z));
}
Expected expectedAt(const Scene& scene, std::uint32_t x, std::uint32_t y) {
  const glm::vec2 hit = quadPointAt(scene, x, y);
  if (std::abs(hit.x) > 1.02f || std::abs(hit.y) > 1.02f) return Expected::Cut;  // beside the quad: the wall
  if (std::abs(hit.x) > 0.98f || std::abs(hit.y) > 0.98f) return Expected::Either;
  const Material& material = scene.objects[0].material;
  const float alpha = material.cutoutAlpha * test::sampleBilinear(scene.textures[0], test::quadTexCoord(hit)).a;
  if (std::abs(alpha - material.alphaCutoff) < 0.03f) return Expected::Either;
  return alpha < material.alphaCutoff ? Expected::Cut : Expected::Kept;
}

class CutoutRenderTest : public s3d::test::VulkanTest,
                         public ::testing::WithParamInterface<RendererOptions::GBufferShading> {};

TEST_P(CutoutRenderTest, TheCentreViewShowsTheWallExactlyWhereTheAlphaTestCutsTheQuad) {
  // Coverage alpha = 0.8 x texel alpha against a cutoff of 0.4. Depth tells quad (3 m) from wall (5 m) to 1e-3
  // relative (float depth); colour says red quad against blue wall; the cut-out mask is the quad's drawn pixels.
  const Scene scene = cutoutScene(0.4f, 0.8f);
  RendererOptions options;
  options.gbufferShading = GetParam();
  DeferredRenderer renderer(context(), kSize, kSize, options);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, 1.0f));
  const DepthImage depth = renderer.readLinearDepth();
  const ImageRGBA8 color = renderer.readDisplayColor();
  const std::vector<std::uint8_t> cutoutMask = renderer.readCutoutMask();
  const std::vector<std::uint8_t> transparentMask = renderer.readTransparentMask();
  int kept = 0, cutOnQuad = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const float d = *depth.at(x, y);
      const bool drawn = std::abs(d - kQuadDepth) < 1e-3f * kQuadDepth;
      ASSERT_TRUE(drawn || std::abs(d - kWallDepth) < 1e-3f * kWallDepth) << x << "," << y << ": depth " << d;
      EXPECT_EQ(cutoutMask[y * kSize + x], drawn ? 1 : 0) << x << "," << y;
      EXPECT_EQ(transparentMask[y * kSize + x], 0) << "a cut-out is not transparent";
      const Expected expected = expectedAt(scene, x, y);
      if (expected == Expected::Either) continue;
      EXPECT_EQ(drawn, expected == Expected::Kept) << x << "," << y;
      const std::uint8_t* p = color.at(x, y);
      EXPECT_EQ(p[0] > p[2], expected == Expected::Kept) << x << "," << y << ": red " << int(p[0]) << " blue " << int(p[2]);
      const glm::vec2 hit = quadPointAt(scene, x, y);
      if (expected == Expected::Kept) ++kept;
      else if (std::abs(hit.x) < 1.0f && std::abs(hit.y) < 1.0f) ++cutOnQuad;
    }
  // Both outcomes are well represented on the quad (it covers about 1400 of the 4096 pixels).
  EXPECT_GT(kept, 300);
  EXPECT_GT(cutOnQuad, 300);
}

INSTANTIATE_TEST_SUITE_P(Shading, CutoutRenderTest,
                         ::testing::Values(RendererOptions::GBufferShading::Raster,
                                           RendererOptions::GBufferShading::Visibility),
                         [](const auto& param) { return std::string(gbufferShadingName(param.param)); });

class CutoutMaskedRenderTest : public s3d::test::VulkanTest {};

TEST_F(CutoutMaskedRenderTest, AMaskedRenderOfACutoutEqualsTheUnmaskedOne) {
  // Under raster shading a masked render with ambient occlusion takes the occlusion's depth from a depth-only
  // pass, which must cut the quad as the G-buffer does: the wall 0.3 m behind the quad is within the occlusion
  // radius (0.5 m), so a hole-less depth would darken it. Masked pixels against the unmasked render: one 8-bit
  // level of colour and 1e-5 relative depth (masked_render tests' tolerance).
  Scene scene = cutoutScene(0.4f, 0.8f, 0.3f);
  scene.ambientOcclusion = true;
  RendererOptions options;
  options.gbufferShading = RendererOptions::GBufferShading::Raster;
  DeferredRenderer renderer(context(), kSize, kSize, options);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, 1.0f);
  renderer.render(view);
  const ImageRGBA8 fullColor = renderer.readDisplayColor();
  const DepthImage fullDepth = renderer.readLinearDepth();
  std::vector<std::uint32_t> values(std::size_t(kSize) * kSize);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = (i / kSize / 4 + i % kSize / 4) % 2;  // 4x4 checker
  vk::Image mask = vk::createImage(context(), VK_FORMAT_R32_UINT, kSize, kSize,
                                   VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context(), mask, std::as_bytes(std::span(values)), vk::kComputeWrite);
  renderer.render(view, {&mask});
  const ImageRGBA8 color = renderer.readDisplayColor();
  const DepthImage depth = renderer.readLinearDepth();
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      if (values[std::size_t(y) * kSize + x] == 0) continue;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(color.at(x, y)[c], fullColor.at(x, y)[c], 1) << x << "," << y;
      EXPECT_NEAR(*depth.at(x, y), *fullDepth.at(x, y), 1e-5f * *fullDepth.at(x, y)) << x << "," << y;
    }
}

class CutoutShadowTest : public s3d::test::VulkanTest {};

// The ground under a horizontal quad 1 m up, the sun straight overhead; the camera stands low (0.4 m) and sees
// the quad from below, where it is culled (single-sided), so only its shadow shows. The quad's 4x4 texture
// holds a 2x2 checker of opaque and empty blocks.
Scene shadowScene(float cutoff) {
  Scene scene;
  scene.name = "cut-out-shadow";
  scene.meshes = {test::makeTexturedQuad(), makeGroundPlane(20.0f)};
  Texture checker;
  checker.width = checker.height = 4;
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x = 0; x < 4; ++x)
      checker.rgba.insert(checker.rgba.end(), {255, 255, 255, std::uint8_t((x < 2) == (y < 2) ? 255 : 0)});
  scene.textures = {checker};
  Object quad;
  quad.mesh = 0;
  quad.material.baseColorTexture = 0;
  quad.material.alphaCutoff = cutoff;
  // Quad space (x, y, 0) -> world (x, 1, -y): facing up.
  quad.transform = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)), -glm::half_pi<float>(),
                               glm::vec3(1.0f, 0.0f, 0.0f));
  Object ground;
  ground.mesh = 1;
  ground.material.albedo = glm::vec3(0.5f);
  scene.objects = {quad, ground};
  scene.sun.directionToSun = glm::vec3(0.0f, 1.0f, 0.0f);
  scene.sun.color = glm::vec3(2.0f);
  scene.sun.castsShadows = true;
  scene.ambientColor = glm::vec3(0.1f);
  scene.ambientOcclusion = false;
  scene.camera.position = glm::vec3(0.0f, 0.4f, 3.0f);
  scene.camera.pitchRadians = -0.25f;
  scene.camera.verticalFovRadians = 0.9f;
  return scene;
}

TEST_F(CutoutShadowTest, TheShadowOfACutoutHasItsHoles) {
  // Lit ground: HDR red 0.5 x (0.1 ambient + 2 sun) = 1.05; shadowed: 0.05 (exposure 1). Pixels are called
  // lit above 0.55. Judged away from the blocks' edges (0.2 m: the bilinear texture blends half a texel, 0.25
  // m at the edge, and percentage-closer filtering blurs a few shadow texels) and from the quad's border.
  auto litUnderQuad = [&](float cutoff, int& litUnderKept, int& litUnderHoles, int& underKept, int& underHoles) {
    const Scene scene = shadowScene(cutoff);
    DeferredRenderer renderer(context(), kSize, kSize);
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, 1.0f));
    const ImageRGBA32F hdr = renderer.readHdrColor();
    for (std::uint32_t y = 0; y < kSize; ++y)
      for (std::uint32_t x = 0; x < kSize; ++x) {
        const glm::vec3 ray = test::pixelRay(scene.camera, x, y, kSize, kSize);
        if (ray.y >= 0.0f) continue;
        const glm::vec3 ground = scene.camera.position + ray * (scene.camera.position.y / -ray.y);
        const glm::vec2 uv((ground.x + 1.0f) * 0.5f, (ground.z + 1.0f) * 0.5f);  // the quad's uv above it
        if (std::abs(ground.x) > 0.8f || std::abs(ground.z) > 0.8f || std::abs(ground.x) < 0.2f || std::abs(ground.z) < 0.2f)
          continue;
        const bool holeAbove = test::sampleBilinear(scene.textures[0], uv).a < 0.5f;
        const bool lit = hdr.at(x, y)[0] > 0.55f;
        ++(holeAbove ? underHoles : underKept);
        if (lit) ++(holeAbove ? litUnderHoles : litUnderKept);
      }
  };
  int litUnderKept = 0, litUnderHoles = 0, underKept = 0, underHoles = 0;
  litUnderQuad(0.5f, litUnderKept, litUnderHoles, underKept, underHoles);
  EXPECT_GT(underKept, 30);
  EXPECT_GT(underHoles, 30);
  EXPECT_EQ(litUnderKept, 0) << "the opaque blocks cast shadow";
  EXPECT_EQ(litUnderHoles, underHoles) << "the sun shines through the holes";
  // Control: the same quad without the cut-out shadows all of it.
  int solidLitKept = 0, solidLitHoles = 0, solidKept = 0, solidHoles = 0;
  litUnderQuad(0.0f, solidLitKept, solidLitHoles, solidKept, solidHoles);
  EXPECT_EQ(solidLitKept + solidLitHoles, 0);
  std::printf("ground pixels under opaque blocks %d, under holes %d\n", underKept, underHoles);
}

TEST_F(CutoutShadowTest, ACutoutIsNotTransparentAndAScenewithoutCutoutsHasAnEmptyMask) {
  Scene scene = cutoutScene(0.4f, 1.0f);
  EXPECT_FALSE(scene.objects[0].material.isTransparent());
  EXPECT_TRUE(scene.objects[0].material.isCutout());
  scene.objects[0].material.alphaCutoff = 0.0f;  // the same quad, not a cut-out
  DeferredRenderer renderer(context(), kSize, kSize);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, 1.0f));
  const std::vector<std::uint8_t> mask = renderer.readCutoutMask();
  ASSERT_EQ(mask.size(), std::size_t(kSize) * kSize);
  for (std::uint8_t value : mask) ASSERT_EQ(value, 0);
}

}  // namespace
}  // namespace s3d::renderer
