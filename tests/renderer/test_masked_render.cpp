// Masked renders (ShadeMask): each pass shades only what the mask asks for, and the masked pixels come out as
// the unmasked render's. Also the tiled lighting's culling test and the G-buffer's albedo encoding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/renderer_shared.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kWidth = 80, kHeight = 48;  // 5 x 3 tiles

// The mask as the hybrid method hands it over: R32_UINT at output size, GENERAL layout.
vk::Image uploadMask(vk::Context& context, std::uint32_t width, std::uint32_t height,
                     const std::vector<std::uint32_t>& values) {
  vk::Image image = vk::createImage(context, VK_FORMAT_R32_UINT, width, height,
                                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context, image, std::as_bytes(std::span(values)), vk::kComputeWrite);
  return image;
}

// A scattered mask (about `share` of the pixels, values 1..9) plus a solid block, so tiles are partly and fully
// covered, and some tiles not at all.
std::vector<std::uint32_t> scatteredMask(std::uint32_t width, std::uint32_t height, double share, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<std::uint32_t> mask(std::size_t(width) * height, 0);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      if (x >= 48 && y < 32) continue;  // the top right 2x2 tiles stay unmasked
      if (uniform(random) < share || (x >= 8 && x < 20 && y >= 20 && y < 30))
        mask[std::size_t(y) * width + x] = 1 + std::uint32_t(random() % 9);
    }
  return mask;
}

std::uint64_t shadedPixels(const FrameTimings& timings, const std::string& pass) {
  for (const PassTiming& timing : timings.passes)
    if (timing.name == pass) {
      EXPECT_TRUE(timing.shadedPixels.has_value()) << pass << " has no count";
      return timing.shadedPixels.value_or(0);
    }
  ADD_FAILURE() << "no pass " << pass;
  return 0;
}

// A wall straight ahead filling the view: one visible face, so the G-buffer draws each pixel once.
Scene wallScene() {
  Scene scene;
  scene.name = "wall";
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  Object wall;
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -5.5f)) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(40.0f, 40.0f, 1.0f));
  scene.objects.push_back(wall);
  scene.pointLights.push_back({glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(2.0f), 4.0f});
  return scene;
}

// Pixels with mask value >= threshold, and the half-resolution texels of the ambient-occlusion region (the
// tiles with such a pixel and their 8 neighbours), at render size for supersampling `s`.
struct ExpectedCounts {
  std::uint64_t outputPixels = 0;
  std::uint64_t renderPixels = 0;
  std::uint64_t ambientTexels = 0;
};

ExpectedCounts expectedCounts(const std::vector<std::uint32_t>& mask, std::uint32_t width, std::uint32_t height,
                              std::uint32_t threshold, std::uint32_t s) {
  ExpectedCounts counts;
  const std::uint32_t renderWidth = width * s, renderHeight = height * s;
  const std::uint32_t tilesX = (renderWidth + 15) / 16, tilesY = (renderHeight + 15) / 16;
  std::vector<bool> masked(std::size_t(tilesX) * tilesY, false), region(masked.size(), false);
  for (std::uint32_t y = 0; y < renderHeight; ++y)
    for (std::uint32_t x = 0; x < renderWidth; ++x)
      if (mask[std::size_t(y / s) * width + x / s] >= threshold) masked[std::size_t(y / 16) * tilesX + x / 16] = true;
  for (std::uint32_t value : mask) counts.outputPixels += value >= threshold ? 1 : 0;
  counts.renderPixels = counts.outputPixels * s * s;
  for (std::uint32_t ty = 0; ty < tilesY; ++ty)
    for (std::uint32_t tx = 0; tx < tilesX; ++tx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = int(tx) + dx, ny = int(ty) + dy;
          if (nx >= 0 && ny >= 0 && nx < int(tilesX) && ny < int(tilesY) && masked[std::size_t(ny) * tilesX + nx])
            region[std::size_t(ty) * tilesX + tx] = true;
        }
  const std::uint32_t halfWidth = (renderWidth + 1) / 2, halfHeight = (renderHeight + 1) / 2;
  for (std::uint32_t y = 0; y < halfHeight; ++y)
    for (std::uint32_t x = 0; x < halfWidth; ++x) counts.ambientTexels += region[std::size_t(y / 8) * tilesX + x / 8] ? 1 : 0;
  return counts;
}

class MaskedRenderTest : public test::VulkanTest {};

// The G-buffer counts the render pixels it wrote (each once here: one face, no overdraw), lighting the render
// pixels it lit, the resolve (a pass of its own with supersampling) the output pixels, ambient occlusion and
// its blur the half-resolution texels of the masked tiles and their neighbours.
void expectCountsMatchTheMask(vk::Context& context, std::uint32_t supersample, std::uint32_t threshold,
                              RendererOptions::GBufferShading shading = RendererOptions::GBufferShading::Automatic) {
  const Scene scene = wallScene();
  RendererOptions options;
  options.supersample = supersample;
  options.countShadedPixels = true;
  options.gbufferShading = shading;
  DeferredRenderer renderer(context, kWidth, kHeight, options);
  renderer.setScene(scene);
  const std::vector<std::uint32_t> values = scatteredMask(kWidth, kHeight, 0.05, 7);
  const vk::Image mask = uploadMask(context, kWidth, kHeight, values);
  const FrameTimings timings =
      renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)), ShadeMask{&mask, threshold});
  const ExpectedCounts expected = expectedCounts(values, kWidth, kHeight, threshold, supersample);
  ASSERT_GT(expected.outputPixels, 0u);
  ASSERT_LT(expected.outputPixels, std::uint64_t(kWidth) * kHeight / 4);
  EXPECT_EQ(shadedPixels(timings, "gbuffer"), expected.renderPixels);
  EXPECT_EQ(shadedPixels(timings, "lighting"), expected.renderPixels);
  if (supersample > 1) {
    EXPECT_EQ(shadedPixels(timings, "resolve"), expected.outputPixels);
  }
  EXPECT_EQ(shadedPixels(timings, "ssao"), expected.ambientTexels);
  EXPECT_EQ(shadedPixels(timings, "ssao-blur"), expected.ambientTexels);
  EXPECT_LT(expected.ambientTexels, std::uint64_t(kWidth * supersample / 2) * (kHeight * supersample / 2));
}

TEST_F(MaskedRenderTest, EachPassShadesTheMaskedPixelsOrTheirTiles) { expectCountsMatchTheMask(context(), 1, 1); }

TEST_F(MaskedRenderTest, TheThresholdSelectsTheMaskValuesThatShade) { expectCountsMatchTheMask(context(), 1, 6); }

TEST_F(MaskedRenderTest, WithSupersamplingAMaskPixelShadesAllItsSamples) { expectCountsMatchTheMask(context(), 3, 1); }

// Visibility shading: the G-buffer resolve (which counts for the G-buffer) runs on the masked tiles too.
TEST_F(MaskedRenderTest, UnderVisibilityShadingTheGBufferResolveShadesTheMaskedPixels) {
  expectCountsMatchTheMask(context(), 1, 1, RendererOptions::GBufferShading::Visibility);
}

TEST_F(MaskedRenderTest, AnUnmaskedRenderShadesEveryPixel) {
  const Scene scene = wallScene();
  RendererOptions options;
  options.countShadedPixels = true;
  DeferredRenderer renderer(context(), kWidth, kHeight, options);
  renderer.setScene(scene);
  const FrameTimings timings = renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  EXPECT_EQ(shadedPixels(timings, "gbuffer"), kWidth * kHeight);
  EXPECT_EQ(shadedPixels(timings, "lighting"), kWidth * kHeight);
  EXPECT_EQ(shadedPixels(timings, "ssao"), (kWidth / 2) * (kHeight / 2));
  EXPECT_EQ(shadedPixels(timings, "ssao-blur"), (kWidth / 2) * (kHeight / 2));
}

TEST_F(MaskedRenderTest, AnEmptyMaskShadesNothing) {
  const Scene scene = wallScene();
  RendererOptions options;
  options.countShadedPixels = true;
  DeferredRenderer renderer(context(), kWidth, kHeight, options);
  renderer.setScene(scene);
  const vk::Image mask = uploadMask(context(), kWidth, kHeight, std::vector<std::uint32_t>(kWidth * kHeight, 0));
  const FrameTimings timings = renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)), {&mask});
  for (const char* pass : {"gbuffer", "ssao", "ssao-blur", "lighting"}) EXPECT_EQ(shadedPixels(timings, pass), 0u) << pass;
}

TEST_F(MaskedRenderTest, AMaskOfAnotherSizeOrFormatIsRejected) {
  const Scene scene = wallScene();
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  const vk::Image small = uploadMask(context(), kWidth / 2, kHeight, std::vector<std::uint32_t>(kWidth / 2 * kHeight, 1));
  EXPECT_THROW(renderer.render(view, {&small}), std::invalid_argument);
  const vk::Image bytes = vk::createImage(context(), VK_FORMAT_R8_UINT, kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  EXPECT_THROW(renderer.render(view, {&bytes}), std::invalid_argument);
}

bool hasPass(const FrameTimings& timings, const std::string& pass) {
  return std::any_of(timings.passes.begin(), timings.passes.end(), [&](const PassTiming& t) { return t.name == pass; });
}

// Ambient occlusion needs every pixel's depth in a masked render: under visibility shading (untextured scene) the
// G-buffer pass rasterizes every pixel and the occlusion reads its depth, so no depth-only pass runs; under raster
// shading the G-buffer stays within the mask and a depth-only pass ("ssao-depth") rasterizes the rest.
TEST_F(MaskedRenderTest, OnlyRasterShadingAddsADepthOnlyPassForTheOcclusion) {
  const Scene scene = wallScene();
  const vk::Image mask = uploadMask(context(), kWidth, kHeight, scatteredMask(kWidth, kHeight, 0.05, 7));
  for (auto [shading, depthPass] : {std::pair{RendererOptions::GBufferShading::Visibility, false},
                                    std::pair{RendererOptions::GBufferShading::Raster, true}}) {
    RendererOptions options;
    options.gbufferShading = shading;
    DeferredRenderer renderer(context(), kWidth, kHeight, options);
    renderer.setScene(scene);
    const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
    EXPECT_EQ(hasPass(renderer.render(view, {&mask}), "ssao-depth"), depthPass) << gbufferShadingName(shading);
    EXPECT_FALSE(hasPass(renderer.render(view), "ssao-depth")) << gbufferShadingName(shading);
  }
}

// Every built-in scene (SSAO, sun and local shadows, a weapon, glass), masked pixels against the unmasked
// render, under both G-buffer shadings. Tolerance: one 8-bit level of display colour and 1e-5 relative linear
// depth. The passes compute the same values from the same inputs, except that under raster shading ambient
// occlusion reads a depth-only pass's depth in a masked render, and Vulkan's invariance rules promise the same
// depth from two pipelines only when they share all state (they share the vertex module, not the fragment stage).
class MaskedSceneTest : public test::VulkanTest,
                        public ::testing::WithParamInterface<std::tuple<std::string, RendererOptions::GBufferShading>> {};

void expectMaskedPixelsEqualTheUnmaskedRender(vk::Context& context, const std::string& sceneName,
                                              const RendererOptions& options) {
  Scene scene = makeBuiltInScene(sceneName);
  scene.camera = cameraForFrame(scene, 0);
  DeferredRenderer renderer(context, kWidth, kHeight, options);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  renderer.render(view);
  const ImageRGBA8 fullColor = renderer.readDisplayColor();
  const DepthImage fullDepth = renderer.readLinearDepth();
  const std::vector<std::uint32_t> values = scatteredMask(kWidth, kHeight, 0.2, 11);
  const vk::Image mask = uploadMask(context, kWidth, kHeight, values);
  renderer.render(view, {&mask});
  const ImageRGBA8 color = renderer.readDisplayColor();
  const DepthImage depth = renderer.readLinearDepth();
  int worst = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      if (values[std::size_t(y) * kWidth + x] == 0) continue;
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(color.at(x, y)[c]) - int(fullColor.at(x, y)[c])));
      const float expected = *fullDepth.at(x, y);
      if (std::isinf(expected))
        EXPECT_TRUE(std::isinf(*depth.at(x, y))) << "(" << x << ", " << y << ")";
      else
        EXPECT_NEAR(*depth.at(x, y), expected, 1e-5f * expected) << "(" << x << ", " << y << ")";
    }
  EXPECT_LE(worst, 1);
}


TEST_P(MaskedSceneTest, MaskedPixelsEqualTheUnmaskedRender) {
  RendererOptions options;
  options.gbufferShading = std::get<1>(GetParam());
  expectMaskedPixelsEqualTheUnmaskedRender(context(), std::get<0>(GetParam()), options);
}

// A display target (the hybrid's displaced eye) takes the masked pixels' display colour, as the unmasked render's
// within one 8-bit level (the tolerance above), and keeps every other pixel's bytes exactly: no pass writes them.
// Courtyard resolves in the lighting pass; glass, and any scene supersampled, in the resolve pass after it.
void expectADisplayTargetTakesOnlyTheMaskedPixels(vk::Context& context, const std::string& sceneName,
                                                  std::uint32_t supersample) {
  Scene scene = makeBuiltInScene(sceneName);
  scene.camera = cameraForFrame(scene, 0);
  RendererOptions options;
  options.supersample = supersample;
  DeferredRenderer renderer(context, kWidth, kHeight, options);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  renderer.render(view);
  const ImageRGBA8 fullColor = renderer.readDisplayColor();
  const std::vector<std::uint32_t> values = scatteredMask(kWidth, kHeight, 0.2, 5);
  const vk::Image mask = uploadMask(context, kWidth, kHeight, values);
  const std::vector<std::uint8_t> before(std::size_t(kWidth) * kHeight * 4, 77);
  const vk::Image target = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight,
                                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                               VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  vk::uploadImage(context, target, std::as_bytes(std::span(before)), vk::kComputeWrite);
  ShadeMask shadeMask{&mask};
  shadeMask.displayTarget = &target;
  renderer.render(view, shadeMask);
  const std::vector<std::byte> after = vk::readbackImage(context, target, vk::kComputeWrite);
  int worst = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x)
      for (int c = 0; c < 4; ++c) {
        const int got = int(after[(std::size_t(y) * kWidth + x) * 4 + std::size_t(c)]);
        if (values[std::size_t(y) * kWidth + x] == 0)
          ASSERT_EQ(got, 77) << "(" << x << ", " << y << ") outside the mask";
        else
          worst = std::max(worst, std::abs(got - int(fullColor.at(x, y)[c])));
      }
  EXPECT_LE(worst, 1);
}

TEST_F(MaskedRenderTest, ADisplayTargetTakesOnlyTheMaskedPixelsFromTheLightingPass) {
  expectADisplayTargetTakesOnlyTheMaskedPixels(context(), "courtyard", 1);
}
TEST_F(MaskedRenderTest, ADisplayTargetTakesOnlyTheMaskedPixelsFromTheResolveAfterGlass) {
  expectADisplayTargetTakesOnlyTheMaskedPixels(context(), "glass", 1);
}
TEST_F(MaskedRenderTest, ADisplayTargetTakesOnlyTheMaskedPixelsOfASupersampledRender) {
  expectADisplayTargetTakesOnlyTheMaskedPixels(context(), "courtyard", 2);
}

TEST_F(MaskedRenderTest, WithoutAMaskADisplayTargetTakesEveryPixel) {
  Scene scene = makeBuiltInScene("courtyard");
  scene.camera = cameraForFrame(scene, 0);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  renderer.render(view);
  const ImageRGBA8 fullColor = renderer.readDisplayColor();
  const std::vector<std::uint8_t> before(std::size_t(kWidth) * kHeight * 4, 77);
  const vk::Image target = vk::createImage(context(), VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight,
                                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                               VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  vk::uploadImage(context(), target, std::as_bytes(std::span(before)), vk::kComputeWrite);
  ShadeMask everyPixel;
  everyPixel.displayTarget = &target;
  renderer.render(view, everyPixel);
  const std::vector<std::byte> after = vk::readbackImage(context(), target, vk::kComputeWrite);
  // Exact: the same passes on the same inputs, only the image they store into differs.
  EXPECT_EQ(std::memcmp(after.data(), fullColor.pixels.data(), after.size()), 0);
}

TEST_F(MaskedRenderTest, ADisplayTargetOfAnotherSizeOrFormatIsRejected) {
  const Scene scene = wallScene();
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
  const vk::Image small = vk::createImage(context(), VK_FORMAT_R8G8B8A8_UNORM, kWidth / 2, kHeight, storage);
  const vk::Image wide = vk::createImage(context(), VK_FORMAT_R16G16B16A16_SFLOAT, kWidth, kHeight, storage);
  for (const vk::Image* target : {&small, &wide}) {
    ShadeMask mask;
    mask.displayTarget = target;
    EXPECT_THROW(renderer.render(view, mask), std::invalid_argument);
  }
}

// The compute transparent pass (a GPU's) reads the shade mask itself instead of a depth fill before it; same
// tolerance as above.
TEST_F(MaskedRenderTest, TheComputeTransparentPassKeepsTheMaskedGlassPixels) {
  RendererOptions options;
  options.gbufferShading = RendererOptions::GBufferShading::Visibility;
  options.transparentCompositing = RendererOptions::TransparentCompositing::Compute;
  expectMaskedPixelsEqualTheUnmaskedRender(context(), "glass", options);
}

// The compute transparent pass composites nothing outside the mask: the transparent coverage (the metrics' region)
// is zero there and, in the mask, what the unmasked render gives. Exact: the same pass on the same inputs.
TEST_F(MaskedRenderTest, TheComputeTransparentPassCompositesOnlyTheMaskedPixels) {
  Scene scene = makeBuiltInScene("glass");
  scene.camera = cameraForFrame(scene, 0);
  RendererOptions options;
  options.gbufferShading = RendererOptions::GBufferShading::Visibility;
  options.transparentCompositing = RendererOptions::TransparentCompositing::Compute;
  DeferredRenderer renderer(context(), kWidth, kHeight, options);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  renderer.render(view);
  const std::vector<std::uint8_t> full = renderer.readTransparentMask();
  const std::vector<std::uint32_t> values = scatteredMask(kWidth, kHeight, 0.2, 11);
  const vk::Image mask = uploadMask(context(), kWidth, kHeight, values);
  renderer.render(view, {&mask});
  const std::vector<std::uint8_t> masked = renderer.readTransparentMask();
  ASSERT_EQ(masked.size(), values.size());
  std::size_t coveredOutside = 0, coveredInside = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] == 0) {
      coveredOutside += masked[i] != 0 ? 1 : 0;
    } else {
      EXPECT_EQ(masked[i], full[i]) << "pixel " << i;
      coveredInside += masked[i] != 0 ? 1 : 0;
    }
  }
  EXPECT_EQ(coveredOutside, 0u);
  EXPECT_GT(coveredInside, 0u);  // the mask does meet the panes
}

// Under visibility shading the masked G-buffer writes every pixel's depth, so a raster transparent pass needs the
// mask's depth fill before it ("mask-depth"); the compute pass skips unshaded pixels and needs none.
TEST_F(MaskedRenderTest, OnlyARasterTransparentPassNeedsTheMaskDepthFill) {
  Scene scene = makeBuiltInScene("glass");
  scene.camera = cameraForFrame(scene, 0);
  const vk::Image mask = uploadMask(context(), kWidth, kHeight, scatteredMask(kWidth, kHeight, 0.05, 7));
  for (auto [compositing, fill] : {std::pair{RendererOptions::TransparentCompositing::Compute, false},
                                   std::pair{RendererOptions::TransparentCompositing::Raster, true}}) {
    RendererOptions options;
    options.gbufferShading = RendererOptions::GBufferShading::Visibility;
    options.transparentCompositing = compositing;
    DeferredRenderer renderer(context(), kWidth, kHeight, options);
    renderer.setScene(scene);
    const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
    EXPECT_EQ(hasPass(renderer.render(view, {&mask}), "mask-depth"), fill) << (fill ? "raster" : "compute");
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenes, MaskedSceneTest,
                         ::testing::Combine(::testing::ValuesIn(builtInSceneNames()),
                                            ::testing::Values(RendererOptions::GBufferShading::Raster,
                                                              RendererOptions::GBufferShading::Visibility)),
                         [](const auto& param) {
                           std::string name = std::get<0>(param.param);
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name + "_" + gbufferShadingName(std::get<1>(param.param));
                         });

// The culling test never drops a light that reaches a point of the tile: points sampled in random spheres that
// fall inside a random tile's rays and depth range must find the sphere accepted. Off-axis projections too.
TEST(TileCulling, AcceptsEverySphereThatReachesThePointsOfTheTile) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int reaching = 0, rejected = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const glm::vec4 projection(1.2f + 0.3f * unit(random), -(1.8f + 0.3f * unit(random)), 0.1f * unit(random),
                               0.1f * unit(random));
    const float x0 = unit(random), y0 = unit(random);
    const glm::vec4 rect(x0, y0, std::min(1.0f, x0 + 0.1f), std::min(1.0f, y0 + 0.1f));
    const float nearDepth = 1.0f + 5.0f * (unit(random) + 1.0f);
    const glm::vec2 range(nearDepth, nearDepth + 3.0f * (unit(random) + 1.0f));
    const glm::vec3 centre(6.0f * unit(random), 6.0f * unit(random), -(range.x + 4.0f * unit(random)));
    const float radius = 0.2f + 2.0f * (unit(random) + 1.0f);
    const bool accepted = gpu::sphereTouchesTile(centre, radius, range, rect, projection, true);
    rejected += accepted ? 0 : 1;
    for (int sample = 0; sample < 64; ++sample) {
      // A point of the tile: ndc inside the rectangle, depth inside the range.
      const float ndcX = glm::mix(rect.x, rect.z, 0.5f * (unit(random) + 1.0f));
      const float ndcY = glm::mix(rect.y, rect.w, 0.5f * (unit(random) + 1.0f));
      const float depth = glm::mix(range.x, range.y, 0.5f * (unit(random) + 1.0f));
      const glm::vec3 point((ndcX + projection.z) * depth / projection.x, (ndcY + projection.w) * depth / projection.y,
                            -depth);
      if (glm::length(point - centre) > radius) continue;
      ++reaching;
      ASSERT_TRUE(accepted) << "trial " << trial;
    }
  }
  EXPECT_GT(reaching, 100);  // the sampling found spheres that reach tiles
  EXPECT_GT(rejected, 1000);  // and the test does reject (it is not "always true")
}

TEST(TileCulling, WithoutSidePlanesOnlyTheDepthRangeCounts) {
  const glm::vec4 projection(1.0f, -1.0f, 0.0f, 0.0f);
  const glm::vec4 rect(-1.0f, -1.0f, -0.9f, -0.9f);
  const glm::vec3 farRight(50.0f, 0.0f, -5.0f);  // beside the tile's rays, inside its depth range
  EXPECT_FALSE(gpu::sphereTouchesTile(farRight, 1.0f, glm::vec2(4.0f, 6.0f), rect, projection, true));
  EXPECT_TRUE(gpu::sphereTouchesTile(farRight, 1.0f, glm::vec2(4.0f, 6.0f), rect, projection, false));
  EXPECT_FALSE(gpu::sphereTouchesTile(farRight, 1.0f, glm::vec2(7.0f, 9.0f), rect, projection, false));
}

// The G-buffer's material keeps the albedo to half a 16-bit step and the object index exactly.
TEST(GBufferMaterial, PackedAlbedoAndObjectIndexSurviveThePacking) {
  for (std::uint32_t index : {0u, 1u, 1234u, 65534u})
    for (float value = 0.0f; value <= 1.0f; value += 1.0f / 512.0f) {
      const glm::vec3 albedo(value, 1.0f - value, 0.5f * value);
      const glm::uvec2 packed = gpu::packMaterial(albedo, index);
      const glm::vec3 decoded = gpu::unpackAlbedo(packed);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(decoded[c], albedo[c], 0.5f / 65535.0f + 1e-7f) << value << " " << c;
      EXPECT_EQ(gpu::unpackObjectIndex(packed), index);
    }
}

}  // namespace
}  // namespace s3d::renderer
