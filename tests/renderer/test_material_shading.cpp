// Double-sided materials, emission and texture transforms (scene.h's Material) in the rendered image, each
// against its definition: glTF's flipped back-face normal, emissive x strength added to the lit colour, and
// KHR_texture_transform's uv' = T * R * S * uv.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include "material_test_scenes.h"
#include "s3d/renderer/deferred_renderer.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kSize = 32;

// The textured quad alone, seen from `cameraZ` on the z axis (positive: its front), lit by ambient light and a
// sun.
Scene quadScene(float cameraZ) {
  Scene scene;
  scene.name = "quad";
  scene.meshes = {test::makeTexturedQuad()};
  Object quad;
  quad.material.albedo = glm::vec3(0.6f);
  scene.objects = {quad};
  scene.ambientOcclusion = false;
  scene.ambientColor = glm::vec3(0.1f);
  scene.camera.position = glm::vec3(0.0f, 0.0f, cameraZ);
  scene.camera.yawRadians = cameraZ > 0.0f ? 0.0f : glm::pi<float>();  // facing the quad
  scene.camera.verticalFovRadians = 0.8f;
  return scene;
}

glm::vec4 renderCentreHdr(vk::Context& context, const Scene& scene, RendererOptions options = {}) {
  DeferredRenderer renderer(context, kSize, kSize, options);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, 1.0f));
  const ImageRGBA32F hdr = renderer.readHdrColor();
  const float* p = hdr.at(kSize / 2, kSize / 2);
  return {p[0], p[1], p[2], *renderer.readLinearDepth().at(kSize / 2, kSize / 2)};  // w: linear depth
}

class MaterialShadingTest : public s3d::test::VulkanTest {};

TEST_F(MaterialShadingTest, ABackFaceIsCulledWhenSingleSidedAndLitLikeTheFrontWhenDoubleSided) {
  // The front view, lit by a sun on the camera's side, against the back view lit by the sun mirrored through
  // the quad's plane: with the back face's normal flipped toward the viewer the two are mirror images, so the
  // centre pixel's HDR colour agrees to half-float rounding (0.2 %). Unflipped, the back view would get no sun
  // (N.L < 0) and about a third of the front's light.
  Scene front = quadScene(3.0f);
  front.sun.directionToSun = glm::normalize(glm::vec3(0.0f, 0.5f, 1.0f));
  Scene back = quadScene(-3.0f);
  back.sun.directionToSun = glm::normalize(glm::vec3(0.0f, 0.5f, -1.0f));

  EXPECT_TRUE(std::isinf(renderCentreHdr(context(), back).w)) << "single-sided: the back view sees the sky";
  front.objects[0].material.doubleSided = true;
  back.objects[0].material.doubleSided = true;
  for (auto shading : {RendererOptions::GBufferShading::Raster, RendererOptions::GBufferShading::Visibility}) {
    RendererOptions options;
    options.gbufferShading = shading;
    const glm::vec4 seenFront = renderCentreHdr(context(), front, options);
    const glm::vec4 seenBack = renderCentreHdr(context(), back, options);
    EXPECT_NEAR(seenBack.w, 3.0f, 3e-3f) << gbufferShadingName(shading);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seenBack[c], seenFront[c], 2e-3f * seenFront[c]) << gbufferShadingName(shading);
  }
}

TEST_F(MaterialShadingTest, AnEmissiveSurfaceInTheDarkShowsItsEmission) {
  // Black albedo, no sun and no ambient light: the HDR colour is the emission alone (emissiveFactor x
  // strength), to half-float rounding (0.1 %). Both G-buffer shadings (the visibility path evaluates
  // untextured objects in compute).
  Scene scene = quadScene(3.0f);
  scene.ambientColor = glm::vec3(0.0f);
  scene.sun.color = glm::vec3(0.0f);
  scene.objects[0].material.albedo = glm::vec3(0.0f);
  const glm::vec3 factor(0.25f, 0.5f, 1.0f);
  const float strength = 4.0f;  // KHR_materials_emissive_strength
  scene.objects[0].material.emissive = factor * strength;
  for (auto shading : {RendererOptions::GBufferShading::Raster, RendererOptions::GBufferShading::Visibility}) {
    RendererOptions options;
    options.gbufferShading = shading;
    const glm::vec4 hdr = renderCentreHdr(context(), scene, options);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(hdr[c], factor[c] * strength, 1e-3f * factor[c] * strength) << c;
  }
}

TEST(TextureTransform, FollowsTheExtensionsTranslationRotationScale) {
  // KHR_texture_transform: uv' = T * R * S * uv, R counter-clockwise in uv space with v down (u' = cos u +
  // sin v, v' = -sin u + cos v: the direction Khronos's TextureTransformTest model marks correct). Worked by
  // hand for scale (2, 3), rotation pi/2, offset (0.5, 0.25): S (1, 1) = (2, 3); R turns it to (3, -2); T adds
  // the offset.
  TextureTransform transform;
  transform.offset = glm::vec2(0.5f, 0.25f);
  transform.rotation = glm::half_pi<float>();
  transform.scale = glm::vec2(2.0f, 3.0f);
  const glm::vec2 uv = transform.apply(glm::vec2(1.0f, 1.0f));
  EXPECT_NEAR(uv.x, 3.5f, 1e-6f);
  EXPECT_NEAR(uv.y, -1.75f, 1e-6f);
  EXPECT_TRUE(TextureTransform{}.isIdentity());
  EXPECT_EQ(TextureTransform{}.apply(glm::vec2(0.3f, 0.7f)), glm::vec2(0.3f, 0.7f));
}

TEST_F(MaterialShadingTest, ATransformedTextureIsSampledWhereTheTransformSays) {
  // Ambient light only, scaled so the quad's diffuse light is exactly 1 (ambient x 0.3 for a normal with y = 0),
  // white albedo and no specular: each pixel's HDR colour is the texture's filtered colour at the transformed
  // uv (sampleBilinear). Tolerance 0.02 linear: lavapipe's bilinear weights have 8 fractional bits, the
  // G-buffer stores albedo in 16-bit unorm and HDR in half floats; an untransformed or mirrored lookup of
  // these scattered texels misses by several tenths.
  Scene scene = quadScene(3.0f);
  scene.sun.color = glm::vec3(0.0f);
  scene.ambientColor = glm::vec3(1.0f / 0.3f);
  Texture texture;
  texture.width = texture.height = 4;
  for (std::uint32_t i = 0; i < 16; ++i)
    texture.rgba.insert(texture.rgba.end(), {std::uint8_t(i * 67 % 256), std::uint8_t(i * 151 % 256), std::uint8_t(i * 29 % 256), 255});
  scene.textures = {texture};
  Material& material = scene.objects[0].material;
  material.albedo = glm::vec3(1.0f);
  material.specularColor = glm::vec3(0.0f);
  material.baseColorTexture = 0;
  material.baseColorTransform.offset = glm::vec2(0.3f, -0.2f);
  material.baseColorTransform.rotation = 0.7f;
  material.baseColorTransform.scale = glm::vec2(1.5f, 0.8f);
  DeferredRenderer renderer(context(), kSize, kSize);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, 1.0f));
  const ImageRGBA32F hdr = renderer.readHdrColor();
  int compared = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const glm::vec3 ray = test::pixelRay(scene.camera, x, y, kSize, kSize);
      const glm::vec2 hit = glm::vec2(scene.camera.position + ray * (3.0f / -ray.z));
      if (std::abs(hit.x) > 0.98f || std::abs(hit.y) > 0.98f) continue;  // the quad's edge: coverage may differ
      const glm::vec4 expected =
          test::sampleBilinear(texture, material.baseColorTransform.apply(test::quadTexCoord(hit)));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(hdr.at(x, y)[c], expected[c], 0.02f) << x << "," << y << " channel " << c;
      ++compared;
    }
  EXPECT_GT(compared, 100);
}

}  // namespace
}  // namespace s3d::renderer
