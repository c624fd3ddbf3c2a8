// Ray-cast surfaces in a masked render (ShadeMask::Surfaces::RayCast): the masked pixels come out as the raster
// render's wherever both find the same triangle, no raster pass or depth clear runs, an empty mask shades
// nothing, and a scene the compute resolve cannot shade is refused with its reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_bvh.h"
#include "material_test_scenes.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kWidth = 160, kHeight = 90;

vk::Image uploadMask(vk::Context& context, const std::vector<std::uint32_t>& values) {
  vk::Image image = vk::createImage(context, VK_FORMAT_R32_UINT, kWidth, kHeight,
                                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context, image, std::as_bytes(std::span(values)), vk::kComputeWrite);
  return image;
}

// About `share` of the pixels, scattered, so tiles are partly covered and the casts run beside unmasked pixels.
std::vector<std::uint32_t> scatteredMask(double share, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<std::uint32_t> mask(std::size_t(kWidth) * kHeight, 0);
  for (std::uint32_t& value : mask) value = uniform(random) < share ? 1u : 0u;
  return mask;
}

// What the hybrid's eye renderer is: visibility shading (the compute resolve shades what the rays find) and the
// compute transparent pass (it samples depth; the raster one needs a depth buffer).
RendererOptions raycastOptions() {
  RendererOptions options;
  options.gbufferShading = RendererOptions::GBufferShading::Visibility;
  options.transparentCompositing = RendererOptions::TransparentCompositing::Compute;
  return options;
}

bool hasPass(const FrameTimings& timings, const std::string& pass) {
  return std::any_of(timings.passes.begin(), timings.passes.end(), [&](const PassTiming& t) { return t.name == pass; });
}

class RaycastRenderTest : public s3d::test::VulkanTest, public ::testing::WithParamInterface<std::string> {};

// Every built-in scene (SSAO, sun and local shadows, a weapon, glass). The rays name the raster pass's triangle on
// 99.9 % of the masked pixels (the leaves decide a pixel by the rasterizer's rule; the rest: depth ties and
// near-ties on shared edges, see the ray-cast visibility tests). Where they name the same triangle, the pixel is
// shaded from the same surface: within one 8-bit level of display colour (the ray's depth and barycentrics differ
// from the rasterizer's interpolation in the last bits) for 99 % of the pixels, and within 4 levels everywhere: on
// depth-range's far surfaces a device-depth ulp spans more than the occlusion's range check, so a few occlusion
// samples flip (measured: 13 of 2896 pixels, up to 2 levels).
TEST_P(RaycastRenderTest, MaskedPixelsEqualTheRasterRenderWhereTheTrianglesAgree) {
  Scene scene = makeBuiltInScene(GetParam());
  scene.camera = cameraForFrame(scene, 0);
  DeferredRenderer raster(context(), kWidth, kHeight, raycastOptions());
  raster.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  raster.render(view);
  const ImageRGBA8 rasterColor = raster.readDisplayColor();
  const std::vector<std::uint32_t> rasterIds = raster.readVisibilityIds();
  const DepthImage rasterDepth = raster.readLinearDepth();

  DeferredRenderer cast(context(), kWidth, kHeight, raycastOptions());
  cast.setScene(scene);
  cast.setSurfaceBvh(SceneBvh::build(scene));
  const std::vector<std::uint32_t> values = scatteredMask(0.2, 5);
  const vk::Image mask = uploadMask(context(), values);
  cast.render(view, {&mask, 1, ShadeMask::Surfaces::RayCast});
  const ImageRGBA8 color = cast.readDisplayColor();
  const std::vector<std::uint32_t> ids = cast.readVisibilityIds();
  const DepthImage depth = cast.readLinearDepth();
  std::size_t compared = 0, otherTriangle = 0, beyondOneLevel = 0;
  int worst = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] == 0) continue;
    const bool sky = std::isinf(rasterDepth.pixels[i]);
    if (sky ? !std::isinf(depth.pixels[i]) : ids[i] != rasterIds[i]) {
      ++otherTriangle;
      continue;
    }
    ++compared;
    const std::uint32_t x = std::uint32_t(i % kWidth), y = std::uint32_t(i / kWidth);
    int largest = 0;
    for (int c = 0; c < 4; ++c) largest = std::max(largest, std::abs(int(color.at(x, y)[c]) - int(rasterColor.at(x, y)[c])));
    worst = std::max(worst, largest);
    beyondOneLevel += largest > 1 ? 1 : 0;
  }
  std::cout << "[ ray-cast render ] " << GetParam() << ": " << compared << " masked pixels compared, worst "
            << worst << " levels (" << beyondOneLevel << " beyond one); " << otherTriangle << " on another triangle\n";
  EXPECT_GT(compared, values.size() / 8);
  EXPECT_LE(otherTriangle, compared / 1000);
  EXPECT_LE(beyondOneLevel, compared / 100);
  EXPECT_LE(worst, 4);
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenes, RaycastRenderTest, ::testing::ValuesIn(builtInSceneNames()),
                         [](const auto& param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

class RaycastRenderPassTest : public s3d::test::VulkanTest {};

// The surfaces come from the rays: no G-buffer raster pass and no depth-only pass for the occlusion run.
TEST_F(RaycastRenderPassTest, NoRasterPassRuns) {
  Scene scene = makeBuiltInScene("courtyard");
  DeferredRenderer renderer(context(), kWidth, kHeight, raycastOptions());
  renderer.setScene(scene);
  renderer.setSurfaceBvh(SceneBvh::build(scene));
  const vk::Image mask = uploadMask(context(), scatteredMask(0.05, 3));
  const FrameTimings timings =
      renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)), {&mask, 1, ShadeMask::Surfaces::RayCast});
  EXPECT_TRUE(hasPass(timings, "raycast"));
  EXPECT_FALSE(hasPass(timings, "gbuffer"));
  EXPECT_FALSE(hasPass(timings, "ssao-depth"));
}

TEST_F(RaycastRenderPassTest, AnEmptyMaskShadesNothing) {
  Scene scene = makeBuiltInScene("fence");
  scene.ambientOcclusion = false;  // the occlusion's cast covers every pixel; without it the cast is the mask's
  RendererOptions options = raycastOptions();
  options.countShadedPixels = true;
  DeferredRenderer renderer(context(), kWidth, kHeight, options);
  renderer.setScene(scene);
  renderer.setSurfaceBvh(SceneBvh::build(scene));
  const vk::Image mask = uploadMask(context(), std::vector<std::uint32_t>(std::size_t(kWidth) * kHeight, 0));
  const FrameTimings timings =
      renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)), {&mask, 1, ShadeMask::Surfaces::RayCast});
  for (const PassTiming& pass : timings.passes) {
    if (pass.shadedPixels) {
      EXPECT_EQ(*pass.shadedPixels, 0u) << pass.name;
    }
  }
}

// With ambient occlusion a masked render casts the occlusion's region: the tiles with a masked pixel and their 8
// neighbours (where the occlusion runs), and no other pixel. A few masked pixels in one tile of the courtyard
// (its ground and walls fill the view's lower part) give ids in exactly that tile's 3x3 block.
TEST_F(RaycastRenderPassTest, WithAmbientOcclusionTheOcclusionsRegionIsCast) {
  Scene scene = makeBuiltInScene("courtyard");
  ASSERT_TRUE(scene.ambientOcclusion);
  DeferredRenderer renderer(context(), kWidth, kHeight, raycastOptions());
  renderer.setScene(scene);
  renderer.setSurfaceBvh(SceneBvh::build(scene));
  std::vector<std::uint32_t> values(std::size_t(kWidth) * kHeight, 0);
  const std::uint32_t tileX = 4, tileY = 3;  // pixels 64..79 x 48..63: the ground, below the horizon
  for (std::uint32_t i = 0; i < 4; ++i) values[std::size_t(tileY * 16 + 3 + i) * kWidth + tileX * 16 + 5 + 2 * i] = 1;
  const vk::Image mask = uploadMask(context(), values);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)), {&mask, 1, ShadeMask::Surfaces::RayCast});
  const std::vector<std::uint32_t> ids = renderer.readVisibilityIds();
  std::size_t castOutside = 0, castInside = 0, insideRegion = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const bool inside = std::abs(int(x / 16) - int(tileX)) <= 1 && std::abs(int(y / 16) - int(tileY)) <= 1;
      const bool cast = ids[std::size_t(y) * kWidth + x] != 0;
      insideRegion += inside ? 1 : 0;
      (inside ? castInside : castOutside) += cast ? 1 : 0;
    }
  EXPECT_EQ(castOutside, 0u);
  EXPECT_GT(castInside, insideRegion / 2);  // the region's surfaces were found (sky pixels get id 0 too)
}

std::vector<float> readDeviceDepth(vk::Context& context, const DeferredRenderer& renderer) {
  constexpr vk::ImageState kSampledByCompute{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  const std::vector<std::byte> bytes = vk::readbackImage(context, renderer.deviceDepth(), kSampledByCompute);
  std::vector<float> depth(bytes.size() / sizeof(float));
  std::memcpy(depth.data(), bytes.data(), bytes.size());
  return depth;
}

// With an uncast depth (the hybrid's base depth) only the masked pixels are cast: they get the same ids and depth
// as when the whole region is cast, and the raster pass's ids (ground pixels, away from triangle edges); the
// region's other pixels get the given depth and id 0 exactly; pixels outside it the cleared depth as before.
TEST_F(RaycastRenderPassTest, WithAnUncastDepthOnlyTheMaskedPixelsOfTheRegionAreCast) {
  Scene scene = makeBuiltInScene("courtyard");
  ASSERT_TRUE(scene.ambientOcclusion);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  DeferredRenderer raster(context(), kWidth, kHeight, raycastOptions());
  raster.setScene(scene);
  raster.render(view);
  const std::vector<std::uint32_t> rasterIds = raster.readVisibilityIds();
  DeferredRenderer renderer(context(), kWidth, kHeight, raycastOptions());
  renderer.setScene(scene);
  renderer.setSurfaceBvh(SceneBvh::build(scene));
  std::vector<std::uint32_t> values(std::size_t(kWidth) * kHeight, 0);
  const std::uint32_t tileX = 4, tileY = 3;  // the ground, as above
  for (std::uint32_t i = 0; i < 4; ++i) values[std::size_t(tileY * 16 + 3 + i) * kWidth + tileX * 16 + 5 + 2 * i] = 1;
  const vk::Image mask = uploadMask(context(), values);
  std::vector<float> given(values.size());
  for (std::size_t i = 0; i < given.size(); ++i) given[i] = 0.5f + 1e-6f * float(i);  // a value of its own per pixel
  const vk::Image uncast = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth, kHeight,
                                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context(), uncast, std::as_bytes(std::span(given)), vk::kComputeWrite);

  renderer.render(view, {&mask, 1, ShadeMask::Surfaces::RayCast});
  const std::vector<std::uint32_t> regionIds = renderer.readVisibilityIds();
  const std::vector<float> regionDepth = readDeviceDepth(context(), renderer);
  renderer.render(view, {&mask, 1, ShadeMask::Surfaces::RayCast, &uncast});
  const std::vector<std::uint32_t> ids = renderer.readVisibilityIds();
  const std::vector<float> depth = readDeviceDepth(context(), renderer);
  std::size_t masked = 0, givenPixels = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::size_t i = std::size_t(y) * kWidth + x;
      const bool inside = std::abs(int(x / 16) - int(tileX)) <= 1 && std::abs(int(y / 16) - int(tileY)) <= 1;
      if (values[i] != 0) {
        ++masked;
        EXPECT_EQ(ids[i], regionIds[i]) << x << ", " << y;
        EXPECT_EQ(ids[i], rasterIds[i]) << x << ", " << y;
        EXPECT_EQ(depth[i], regionDepth[i]) << x << ", " << y;
      } else if (inside) {
        ++givenPixels;
        EXPECT_EQ(ids[i], 0u) << x << ", " << y;
        EXPECT_EQ(depth[i], given[i]) << x << ", " << y;
      } else {
        EXPECT_EQ(ids[i], 0u) << x << ", " << y;
        EXPECT_EQ(depth[i], regionDepth[i]) << x << ", " << y;  // the cleared depth
      }
    }
  EXPECT_EQ(masked, 4u);
  EXPECT_EQ(givenPixels, 9u * 16u * 16u - 4u);
}

// An uncast depth is for ray-cast surfaces, as an R32_SFLOAT image of the output's size.
TEST_F(RaycastRenderPassTest, AnUncastDepthOfAnotherKindIsRefused) {
  Scene scene = makeBuiltInScene("cover");
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  DeferredRenderer renderer(context(), kWidth, kHeight, raycastOptions());
  renderer.setScene(scene);
  renderer.setSurfaceBvh(SceneBvh::build(scene));
  const vk::Image mask = uploadMask(context(), scatteredMask(0.05, 3));
  const vk::Image depth = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  const vk::Image small = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth / 2, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  EXPECT_THROW(renderer.render(view, {&mask, 1, ShadeMask::Surfaces::Raster, &depth}), std::invalid_argument);
  EXPECT_THROW(renderer.render(view, {&mask, 1, ShadeMask::Surfaces::RayCast, &small}), std::invalid_argument);
  EXPECT_THROW(renderer.render(view, {&mask, 1, ShadeMask::Surfaces::RayCast, &mask}), std::invalid_argument);
}

// The first-person layer lives in camera space, so a camera that moves along its path needs no new BVH: every
// weapon pixel of later frames, cast through the tree built once, names the raster pass's triangle (all but
// 0.1 %: the leaves decide edges by the rasterizer's rule) and shades within one 8-bit level there.
TEST_F(RaycastRenderPassTest, AMovingCameraKeepsTheFirstPersonLayerWithoutANewBvh) {
  Scene scene = makeBuiltInScene("courtyard");
  DeferredRenderer raster(context(), kWidth, kHeight, raycastOptions());
  DeferredRenderer cast(context(), kWidth, kHeight, raycastOptions());
  raster.setScene(scene);
  cast.setScene(scene);
  cast.setSurfaceBvh(SceneBvh::build(scene));
  for (std::size_t frame : {std::size_t(0), std::size_t(7), std::size_t(15)}) {
    scene.camera = cameraForFrame(scene, frame);
    const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
    raster.render(view);
    const std::vector<std::uint8_t> weapon = raster.readFirstPersonMask();
    const std::vector<std::uint32_t> rasterIds = raster.readVisibilityIds();
    const ImageRGBA8 rasterColor = raster.readDisplayColor();
    cast.render(view, {nullptr, 1, ShadeMask::Surfaces::RayCast});
    const std::vector<std::uint32_t> ids = cast.readVisibilityIds();
    const ImageRGBA8 color = cast.readDisplayColor();
    std::size_t weaponPixels = 0, otherTriangle = 0, beyondOneLevel = 0;
    for (std::size_t i = 0; i < weapon.size(); ++i) {
      if (!weapon[i]) continue;
      ++weaponPixels;
      if (ids[i] != rasterIds[i]) {
        ++otherTriangle;
        continue;
      }
      const std::uint32_t x = std::uint32_t(i % kWidth), y = std::uint32_t(i / kWidth);
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(color.at(x, y)[c]) - int(rasterColor.at(x, y)[c])) > 1) {
          ++beyondOneLevel;
          break;
        }
    }
    EXPECT_GT(weaponPixels, 100u) << "frame " << frame;  // the weapon is in view
    EXPECT_LE(otherTriangle, weaponPixels / 1000) << "frame " << frame;
    EXPECT_EQ(beyondOneLevel, 0u) << "frame " << frame;
  }
}

// A ray-cast render needs a BVH and visibility shading (the refusal names it); the same renderer still rasterizes.
TEST_F(RaycastRenderPassTest, WithoutABvhOrUnderRasterShadingItIsRefused) {
  Scene scene = makeBuiltInScene("cover");
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  const vk::Image mask = uploadMask(context(), scatteredMask(0.05, 3));
  DeferredRenderer noBvh(context(), kWidth, kHeight, raycastOptions());
  noBvh.setScene(scene);
  EXPECT_FALSE(noBvh.raycastSurfacesRefusal().has_value());
  EXPECT_FALSE(noBvh.hasSurfaceBvh());
  EXPECT_THROW(noBvh.render(view, {&mask, 1, ShadeMask::Surfaces::RayCast}), std::invalid_argument);
  EXPECT_NO_THROW(noBvh.render(view, {&mask}));

  RendererOptions rasterShading = raycastOptions();
  rasterShading.gbufferShading = RendererOptions::GBufferShading::Raster;
  DeferredRenderer raster(context(), kWidth, kHeight, rasterShading);
  raster.setScene(scene);
  raster.setSurfaceBvh(SceneBvh::build(scene));
  ASSERT_TRUE(raster.raycastSurfacesRefusal().has_value());
  EXPECT_NE(raster.raycastSurfacesRefusal()->find("visibility"), std::string::npos);
}

// The scene's center view rendered by the raster pass and by rays (every pixel masked), both under visibility
// shading; refusal: why the rays were refused (nothing else is rendered then).
struct RasterAndCast {
  std::optional<std::string> refusal;
  ImageRGBA8 rasterColor, color;
  DepthImage rasterDepth, depth;
  std::vector<std::uint32_t> ids;  // the rays' visibility ids
};
RasterAndCast renderBothWays(vk::Context& context, const Scene& scene, const SceneBvh& bvh) {
  RasterAndCast result;
  const ViewMatrices matrices = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  DeferredRenderer cast(context, kWidth, kHeight, raycastOptions());
  cast.setScene(scene);
  result.refusal = cast.raycastSurfacesRefusal();
  if (result.refusal) return result;
  DeferredRenderer raster(context, kWidth, kHeight, raycastOptions());
  raster.setScene(scene);
  raster.render(matrices);
  result.rasterColor = raster.readDisplayColor();
  result.rasterDepth = raster.readLinearDepth();
  cast.setSurfaceBvh(bvh);
  const vk::Image mask = uploadMask(context, std::vector<std::uint32_t>(std::size_t(kWidth) * kHeight, 1u));
  cast.render(matrices, {&mask, 1, ShadeMask::Surfaces::RayCast});
  result.color = cast.readDisplayColor();
  result.depth = cast.readLinearDepth();
  result.ids = cast.readVisibilityIds();
  return result;
}

// Every texture's texels are sampled from one storage buffer: a scene whose texels exceed the device's largest
// storage-buffer range (128 MiB on lavapipe) is refused, naming the scene, rather than bound past the range.
TEST_F(RaycastRenderPassTest, TexelsBeyondTheDevicesStorageBufferRangeAreRefused) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context().physicalDevice(), &properties);
  const std::uint64_t range = properties.limits.maxStorageBufferRange;
  if (range > (std::uint64_t(256) << 20)) GTEST_SKIP() << "a texture past this device's range would not fit the test";
  Scene scene = makeBuiltInScene("cover");
  Texture large;
  large.width = 4096;
  large.height = std::uint32_t(range / (4 * 4096)) + 1;  // one row past the range
  large.rgba.assign(std::size_t(large.width) * large.height * 4, 255);
  scene.textures = {large};
  scene.meshes.push_back(test::makeTexturedQuad());
  Object quad;
  quad.mesh = std::uint32_t(scene.meshes.size() - 1);
  quad.material.baseColorTexture = 0;
  scene.objects.push_back(quad);
  DeferredRenderer renderer(context(), kWidth, kHeight, raycastOptions());
  renderer.setScene(scene);
  const std::optional<std::string> refusal = renderer.raycastSurfacesRefusal();
  ASSERT_TRUE(refusal.has_value());
  EXPECT_NE(refusal->find("'cover'"), std::string::npos) << *refusal;
  EXPECT_NE(refusal->find("MiB of texels"), std::string::npos) << *refusal;
}

// A texture whose texels change by at most 40 levels between neighbours (a filtered value is then within a level
// of the hardware's, whose filter weights are rounded to 8 bits on some devices) with a red-green-blue pattern.
Texture patternTexture(std::uint32_t width, std::uint32_t height, Texture::Encoding encoding) {
  Texture texture;
  texture.width = width;
  texture.height = height;
  texture.encoding = encoding;
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const float u = float(x) / float(width), v = float(y) / float(height);
      texture.rgba.push_back(std::uint8_t(128 + 100 * std::sin(6.2832f * u)));
      texture.rgba.push_back(std::uint8_t(128 + 100 * std::cos(6.2832f * v)));
      texture.rgba.push_back(std::uint8_t(encoding == Texture::Encoding::Srgb ? 60 + 120 * u * v : 230));
      texture.rgba.push_back(255);
    }
  return texture;
}

// Textured, normal-mapped and double-sided objects, which the raster pass shades itself under visibility shading:
// cast, the compute resolve samples their texels (bilinear, repeating, sRGB decoded first, as the sampler does),
// applies the texture transform and the normal map, and flips a back face's normal. Two tilted quads (one seen
// from behind) in front of the cover scene, every pixel masked; where both renders see the same depth, the
// display colour is within one level for 99 % of the pixels and within 3 everywhere (filter weights and
// interpolation differ from the rasterizer's in the last bits).
TEST_F(RaycastRenderPassTest, TexturedAndDoubleSidedSurfacesComeOutAsTheRasterRendersThem) {
  Scene scene = makeBuiltInScene("cover");
  scene.camera = cameraForFrame(scene, 0);
  scene.textures = {patternTexture(24, 16, Texture::Encoding::Srgb), patternTexture(8, 8, Texture::Encoding::Linear)};
  scene.meshes.push_back(test::makeTexturedQuad());
  const glm::mat4 view = cameraView(scene.camera);
  const glm::mat4 cameraToWorld = glm::inverse(view);
  Object front;
  front.mesh = std::uint32_t(scene.meshes.size() - 1);
  front.material.baseColorTexture = 0;
  front.material.normalTexture = 1;
  front.material.baseColorTransform.scale = glm::vec2(2.0f, 1.5f);
  front.material.baseColorTransform.rotation = 0.3f;
  front.transform = cameraToWorld * glm::translate(glm::mat4(1.0f), glm::vec3(-0.9f, 0.0f, -4.0f)) *
                    glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(0.0f, 1.0f, 0.0f));
  Object back = front;
  back.material.normalTexture = kNoTexture;
  back.material.doubleSided = true;
  back.transform = cameraToWorld * glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.2f, -4.0f)) *
                   glm::rotate(glm::mat4(1.0f), 2.6f, glm::vec3(0.0f, 1.0f, 0.0f));  // its back toward the camera
  scene.objects.push_back(front);
  scene.objects.push_back(back);

  const RasterAndCast renders = renderBothWays(context(), scene, SceneBvh::build(scene));
  ASSERT_FALSE(renders.refusal.has_value()) << *renders.refusal;
  const ImageRGBA8 &rasterColor = renders.rasterColor, &color = renders.color;
  const DepthImage &rasterDepth = renders.rasterDepth, &depth = renders.depth;

  std::size_t compared = 0, onQuads = 0, beyondOneLevel = 0;
  int worst = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float seen = *rasterDepth.at(x, y), cast = *depth.at(x, y);
      if (std::isinf(seen) || !(std::abs(cast - seen) <= 1e-4f * seen)) continue;
      ++compared;
      onQuads += seen > 3.0f && seen < 5.0f ? 1 : 0;
      int largest = 0;
      for (int c = 0; c < 4; ++c) largest = std::max(largest, std::abs(int(color.at(x, y)[c]) - int(rasterColor.at(x, y)[c])));
      worst = std::max(worst, largest);
      beyondOneLevel += largest > 1 ? 1 : 0;
    }
  std::cout << "[ ray-cast render ] textured quads: " << compared << " pixels compared (" << onQuads
            << " at the quads' depth), worst " << worst << " levels (" << beyondOneLevel << " beyond one)\n";
  EXPECT_GT(onQuads, std::size_t(kWidth) * kHeight / 10) << "the quads cover a tenth of the image";
  EXPECT_LE(beyondOneLevel, compared / 100);
  EXPECT_LE(worst, 3);
}

// A cut-out (alpha cutoff 0.5 over a texture whose alpha rises and falls across it) is cast where its alpha test
// keeps it: the rays' ids are the reference traversal's with CutoutCoverage (the same filter and arithmetic; a
// hit whose alpha lies within rounding of the cutoff may differ: at most 2 pixels), and against the raster render,
// whose sampler filters the alpha with its own weights, the two see different surfaces on at most 2 % of the
// quad's pixels (along the cut's edges) and elsewhere match within 3 levels.
TEST_F(RaycastRenderPassTest, ACutOutIsCastWhereItsAlphaTestKeepsIt) {
  Scene scene = makeBuiltInScene("cover");
  scene.camera = cameraForFrame(scene, 0);
  Texture leaf = patternTexture(16, 16, Texture::Encoding::Srgb);
  for (std::uint32_t i = 0; i < 16 * 16; ++i)
    leaf.rgba[4 * i + 3] = std::uint8_t(128 + 120 * std::sin(0.9f * float(i % 16)) * std::cos(0.7f * float(i / 16)));
  scene.textures = {leaf};
  scene.meshes.push_back(test::makeTexturedQuad());
  Object quad;
  quad.mesh = std::uint32_t(scene.meshes.size() - 1);
  quad.material.baseColorTexture = 0;
  quad.material.alphaCutoff = 0.5f;
  quad.transform = glm::inverse(cameraView(scene.camera)) * glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -3.0f)) *
                   glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0.0f, 1.0f, 0.0f));
  scene.objects.push_back(quad);
  const std::uint32_t quadIndex = std::uint32_t(scene.objects.size() - 1);

  const SceneBvh bvh = SceneBvh::build(scene);
  const RasterAndCast renders = renderBothWays(context(), scene, bvh);
  ASSERT_FALSE(renders.refusal.has_value()) << *renders.refusal;
  const ImageRGBA8 &rasterColor = renders.rasterColor, &color = renders.color;
  const DepthImage &rasterDepth = renders.rasterDepth, &depth = renders.depth;
  const std::vector<std::uint32_t>& ids = renders.ids;

  const RaycastCamera camera = raycastCamera(scene, centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  const CutoutCoverage coverage(scene);
  std::size_t otherId = 0, cutAway = 0, onQuad = 0, otherSurface = 0, beyondThree = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const RaycastHit tested = bvh.castPixel(camera, {x, y}, {kWidth, kHeight}, &coverage);
      const RaycastHit untested = bvh.castPixel(camera, {x, y}, {kWidth, kHeight});
      otherId += ids[std::size_t(y) * kWidth + x] != visibilityIdOf(tested, bvh.visibilityPacking).x ? 1 : 0;
      const bool quadHit = untested.hit && untested.object == quadIndex;
      onQuad += quadHit ? 1 : 0;
      cutAway += quadHit && (!tested.hit || tested.object != quadIndex) ? 1 : 0;
      const float seen = *rasterDepth.at(x, y), castDepth = *depth.at(x, y);
      const bool sameSurface = std::isinf(seen) ? std::isinf(castDepth) : std::abs(castDepth - seen) <= 1e-4f * seen;
      if (!sameSurface) {
        otherSurface += quadHit ? 1 : 0;
        continue;
      }
      int largest = 0;
      for (int c = 0; c < 4; ++c) largest = std::max(largest, std::abs(int(color.at(x, y)[c]) - int(rasterColor.at(x, y)[c])));
      beyondThree += largest > 3 ? 1 : 0;
    }
  std::cout << "[ ray-cast render ] cut-out quad: " << onQuad << " pixels on it, " << cutAway << " cut away; "
            << otherId << " ids off the reference, " << otherSurface << " on another surface than the raster's, "
            << beyondThree << " beyond 3 levels\n";
  EXPECT_GT(cutAway, onQuad / 5) << "the alpha test cuts a fifth of the quad away";
  EXPECT_LT(cutAway, onQuad * 4 / 5) << "and keeps a fifth of it";
  EXPECT_LE(otherId, 2u);
  EXPECT_LE(otherSurface, onQuad / 50);
  EXPECT_EQ(beyondThree, 0u);
}

// A new scene (or pose) drops the BVH: rays through the old tree would find the old triangles.
TEST_F(RaycastRenderPassTest, ANewSceneNeedsANewBvh) {
  Scene scene = makeBuiltInScene("cover");
  DeferredRenderer renderer(context(), kWidth, kHeight, raycastOptions());
  renderer.setScene(scene);
  renderer.setSurfaceBvh(SceneBvh::build(scene));
  EXPECT_TRUE(renderer.hasSurfaceBvh());
  renderer.setScene(scene);
  EXPECT_FALSE(renderer.hasSurfaceBvh());
}

}  // namespace
}  // namespace s3d::renderer
