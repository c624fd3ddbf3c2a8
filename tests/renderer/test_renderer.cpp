// The deferred renderer on tiny scenes: the linear depth it hands to the stereo pass, per layer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/renderer_shared.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kWidth = 64, kHeight = 36;

// A camera at the origin looking down -Z at a wall whose front face is at z = -wallDistance, plus an
// optional first-person box whose front face is at camera-space depth weaponDepth in the lower right.
Scene makeWallScene(float wallDistance, bool withWeapon, float weaponDepth = 0.5f) {
  Scene scene;
  scene.name = "wall";
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  scene.camera.position = glm::vec3(0.0f);
  Object wall;
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -2.0f, -wallDistance - 0.5f)) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(40.0f, 4.0f, 1.0f));  // covers the lower half
  scene.objects.push_back(wall);
  if (withWeapon) {
    Object weapon;
    weapon.layer = Layer::FirstPerson;
    weapon.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.15f, -0.1f, -weaponDepth - 0.05f)) *
                       glm::scale(glm::mat4(1.0f), glm::vec3(0.1f));
    scene.objects.push_back(weapon);
  }
  return scene;
}

// Linear depth at a pixel, after rendering the scene's center view.
struct DepthProbe {
  DepthImage depth;
  float at(std::uint32_t x, std::uint32_t y) const { return *depth.at(x, y); }
};

class DeferredRendererTest : public test::VulkanTest {
 protected:
  DepthProbe renderDepth(const Scene& scene) {
    DeferredRenderer renderer(context(), kWidth, kHeight);
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
    return {renderer.readLinearDepth()};
  }
};

TEST_F(DeferredRendererTest, WorldDepthIsTheDistanceToTheWall) {
  // Tolerance 1e-3 relative: D32 device depth at 5 m with near 0.1 / far 1000 resolves ~3e-6 m; the rest
  // is the float reconstruction in Listing 4.3.
  DepthProbe probe = renderDepth(makeWallScene(5.0f, false));
  EXPECT_NEAR(probe.at(kWidth / 2, kHeight - 4), 5.0f, 5e-3f);
}

TEST_F(DeferredRendererTest, SkyHasInfiniteDepth) {
  DepthProbe probe = renderDepth(makeWallScene(5.0f, false));
  float sky = probe.at(kWidth / 2, 2);
  EXPECT_TRUE(std::isinf(sky) && sky > 0.0f) << sky;
}

TEST_F(DeferredRendererTest, FirstPersonDepthIsReconstructedWithItsOwnRange) {
  // The weapon's front face at 0.5 m in camera space, drawn with its own projection into device depth
  // [0, 0.1]; Listing 4.3 must give 0.5 m back. Tolerance 1e-3 m (float reconstruction near the split).
  Scene scene = makeWallScene(5.0f, true, 0.5f);
  DepthProbe probe = renderDepth(scene);
  // Find the weapon's pixel: the nearest depth in the image.
  float nearest = INFINITY;
  for (float depth : probe.depth.pixels) nearest = std::min(nearest, depth);
  EXPECT_NEAR(nearest, 0.5f, 1e-3f);
  EXPECT_NEAR(probe.at(kWidth / 2, kHeight - 4), 5.0f, 5e-3f);  // the world around it is unchanged
}

TEST_F(DeferredRendererTest, ABrighterSunGivesABrighterWall) {
  Scene dim = makeWallScene(5.0f, false);
  dim.sun.directionToSun = glm::vec3(0.0f, 0.0f, 1.0f);  // straight onto the wall's front face
  dim.sun.color = glm::vec3(0.5f);
  Scene bright = dim;
  bright.sun.color = glm::vec3(1.0f);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  auto wallRed = [&](const Scene& scene) {
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
    return renderer.readDisplayColor().at(kWidth / 2, kHeight - 4)[0];
  };
  EXPECT_GT(wallRed(bright), wallRed(dim));
}

TEST_F(DeferredRendererTest, RejectsAbsurdResolutions) {
  EXPECT_THROW(DeferredRenderer(context(), 0, 10), std::invalid_argument);
  EXPECT_THROW(DeferredRenderer(context(), 20000, 10), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::renderer

namespace s3d::renderer {
namespace {

std::vector<std::string> passNames(const FrameTimings& timings) {
  std::vector<std::string> names;
  for (const PassTiming& pass : timings.passes) names.push_back(pass.name);
  return names;
}

// The passes a frame runs, with the G-buffer's resolve after the G-buffer where the renderer shades visibility
// (a GPU's default): the rest of the list is the same on every device.
std::vector<std::string> framePasses(const DeferredRenderer& renderer, std::vector<std::string> names) {
  if (renderer.gbufferShading() == RendererOptions::GBufferShading::Visibility)
    names.insert(names.begin() + 1, "gbuffer-resolve");
  return names;
}

TEST_F(DeferredRendererTest, LightingIsOneComputePassThatResolvesWhenNothingFollowsIt) {
  Scene scene = makeWallScene(5.0f, false);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  FrameTimings timings = renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  EXPECT_EQ(passNames(timings), framePasses(renderer, {"gbuffer", "ssao", "ssao-blur", "lighting"}));
}

TEST_F(DeferredRendererTest, WithSupersamplingTheResolveIsAPassOfItsOwn) {
  Scene scene = makeWallScene(5.0f, false);
  DeferredRenderer renderer(context(), kWidth, kHeight, {2});
  renderer.setScene(scene);
  FrameTimings timings = renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  EXPECT_EQ(passNames(timings), framePasses(renderer, {"gbuffer", "ssao", "ssao-blur", "lighting", "resolve"}));
}

// A transparent object out of view makes the frame run the transparent pass (drawing nothing) and the resolve
// pass; the images must be those the lighting pass resolves in place: HDR and depth bit for bit, display colour
// within one 8-bit level (the resolve pass tone-maps the float16-stored HDR, whose rounding Vulkan leaves to the
// implementation; the in-place resolve tone-maps the colour before that store).
TEST_F(DeferredRendererTest, TheInPlaceResolveEqualsTheResolvePass) {
  Scene scene = makeWallScene(5.0f, true);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  const std::vector<std::string> inPlace = passNames(renderer.render(view));
  const ImageRGBA8 color = renderer.readDisplayColor();
  const DepthImage depth = renderer.readLinearDepth();
  const ImageRGBA32F hdr = renderer.readHdrColor();
  Object behind = scene.objects.front();
  behind.material.opacity = 0.5f;
  behind.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f));  // behind the camera
  scene.objects.push_back(behind);
  renderer.setScene(scene);
  const std::vector<std::string> separate = passNames(renderer.render(view));
  ASSERT_EQ(std::count(inPlace.begin(), inPlace.end(), "resolve"), 0);
  ASSERT_EQ(std::count(separate.begin(), separate.end(), "resolve"), 1);
  const ImageRGBA8 resolvedColor = renderer.readDisplayColor();
  ASSERT_EQ(resolvedColor.pixels.size(), color.pixels.size());
  int worst = 0;
  for (std::size_t i = 0; i < color.pixels.size(); ++i)
    worst = std::max(worst, std::abs(int(resolvedColor.pixels[i]) - int(color.pixels[i])));
  EXPECT_LE(worst, 1);
  EXPECT_EQ(renderer.readLinearDepth().pixels, depth.pixels);
  EXPECT_EQ(renderer.readHdrColor().pixels, hdr.pixels);
}

TEST_F(DeferredRendererTest, AVisiblePointLightBrightensTheWall) {
  Scene scene = makeWallScene(5.0f, false);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  const ViewMatrices view = centerViewMatrices(scene, float(kWidth) / float(kHeight));
  renderer.render(view);
  const std::uint8_t unlit = renderer.readDisplayColor().at(kWidth / 2, kHeight - 4)[0];
  scene.pointLights.push_back({glm::vec3(0.0f, -1.0f, -4.0f), glm::vec3(4.0f, 0.0f, 0.0f), 3.0f});
  renderer.setScene(scene);
  renderer.render(view);
  EXPECT_GT(renderer.readDisplayColor().at(kWidth / 2, kHeight - 4)[0], unlit);
}

TEST_F(DeferredRendererTest, MoreObjectsThanTheGBufferCanIndexAreRejected) {
  Scene scene = makeWallScene(5.0f, false);
  scene.objects.assign(S3D_NO_OBJECT, scene.objects.front());
  DeferredRenderer renderer(context(), kWidth, kHeight);
  EXPECT_THROW(renderer.setScene(scene), std::invalid_argument);
}

// A tile's light list holds the lights that reach its surfaces in light order, wherever they stand in the light
// buffer: four lights on the wall (one shadowed) among 196 small ones that float 1.5 m ahead, far in front of
// the wall's depth range, so every tile culls those. The four end up at buffer positions up to 199 (every word of
// the culling's mask, every round of its light loop) yet must light the wall bit for bit as they do alone, in the
// same order (a fixed summation order).
TEST_F(DeferredRendererTest, TheWallIsLitByTheLightsThatReachItWhereverTheyStandInTheLightBuffer) {
  Scene alone = makeWallScene(5.0f, false);
  const PointLight reaching[] = {{glm::vec3(-1.5f, -1.0f, -4.0f), glm::vec3(1.5f, 0.2f, 0.2f), 3.0f, true},
                                 {glm::vec3(-0.5f, -1.5f, -4.2f), glm::vec3(0.2f, 1.5f, 0.2f), 2.5f},
                                 {glm::vec3(0.6f, -1.2f, -4.1f), glm::vec3(0.2f, 0.2f, 1.5f), 3.0f},
                                 {glm::vec3(1.6f, -0.8f, -4.3f), glm::vec3(1.0f, 1.0f, 0.2f), 2.0f}};
  alone.pointLights.assign(std::begin(reaching), std::end(reaching));
  Scene among = makeWallScene(5.0f, false);
  for (int i = 0; i < 200; ++i) {
    const int slot = i == 70 ? 1 : i == 140 ? 2 : i == 199 ? 3 : i == 0 ? 0 : -1;  // the shadowed one goes first anyway
    if (slot >= 0) {
      among.pointLights.push_back(reaching[slot]);
    } else {
      const glm::vec3 ahead(-0.4f + 0.05f * float(i % 16), -0.3f + 0.05f * float(i / 16), -1.5f);
      among.pointLights.push_back({ahead, glm::vec3(1.0f), 0.2f});
    }
  }
  const ViewMatrices view = centerViewMatrices(alone, float(kWidth) / float(kHeight));
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(alone);
  renderer.render(view);
  const ImageRGBA32F litAlone = renderer.readHdrColor();
  renderer.setScene(among);
  renderer.render(view);
  EXPECT_EQ(renderer.readHdrColor().pixels, litAlone.pixels);
  renderer.setScene(makeWallScene(5.0f, false));
  renderer.render(view);
  EXPECT_NE(renderer.readHdrColor().pixels, litAlone.pixels);  // the four lights do reach the wall
}

TEST_F(DeferredRendererTest, MoreThanTheMaximumOfLightsIsRejected) {
  Scene scene = makeWallScene(5.0f, false);
  scene.pointLights.assign(S3D_MAX_LIGHTS + 1, PointLight{glm::vec3(0.0f, -1.0f, -4.0f), glm::vec3(1.0f), 1.0f});
  DeferredRenderer renderer(context(), kWidth, kHeight);
  EXPECT_THROW(renderer.setScene(scene), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::renderer

namespace s3d::renderer {
namespace {

TEST_F(DeferredRendererTest, WeaponDepthPushChangesLinearDepthButNotTheImage) {
  // The push is applied to the stereo pass's linear depth only: same pixels, weapon at offset + scale * d.
  Scene scene = makeWallScene(5.0f, true, 0.5f);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  const float aspect = float(kWidth) / float(kHeight);
  renderer.render(centerViewMatrices(scene, aspect));
  const ImageRGBA8 unpushedColor = renderer.readDisplayColor();
  renderer.render(centerViewMatrices(scene, aspect, {1.0f, 2.0f}));
  EXPECT_EQ(renderer.readDisplayColor().pixels, unpushedColor.pixels);
  const DepthImage depth = renderer.readLinearDepth();
  float nearest = INFINITY;
  for (float d : depth.pixels) nearest = std::min(nearest, d);
  EXPECT_NEAR(nearest, 1.0f + 2.0f * 0.5f, 2e-3f);  // 2x the 1e-3 m tolerance above, scaled by the push
}

TEST_F(DeferredRendererTest, AbsurdWeaponPushIsRejected) {
  Scene scene = makeWallScene(5.0f, true);
  EXPECT_THROW(centerViewMatrices(scene, 1.0f, {-1.0f, 1.0f}), std::invalid_argument);
  EXPECT_THROW(centerViewMatrices(scene, 1.0f, {0.0f, 0.0f}), std::invalid_argument);
  EXPECT_THROW(centerViewMatrices(scene, 1.0f, {NAN, 1.0f}), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::renderer

namespace s3d::renderer {
namespace {

// A floor and a wall meeting in a corner ahead, lit by ambient light only (no sun), so the ambient
// occlusion is all that changes between the two renders.
Scene cornerScene(bool ambientOcclusion) {
  Scene scene;
  scene.name = "corner";
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  scene.camera.position = glm::vec3(0.0f, 1.0f, 0.0f);
  scene.camera.pitchRadians = -0.35f;
  Object floor;
  floor.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.5f, -4.0f)) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(40.0f, 1.0f, 40.0f));
  Object wall;
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, -4.5f)) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(40.0f, 4.0f, 1.0f));
  scene.objects = {floor, wall};
  scene.sun.color = glm::vec3(0.0f);
  scene.ambientColor = glm::vec3(1.0f);
  scene.ambientOcclusion = ambientOcclusion;
  return scene;
}

// Green channel averaged over rows [y0, y1), away from the side columns.
double bandBrightness(const ImageRGBA8& image, std::uint32_t y0, std::uint32_t y1) {
  double sum = 0.0;
  for (std::uint32_t y = y0; y < y1; ++y)
    for (std::uint32_t x = 8; x < image.width - 8; ++x) sum += image.at(x, y)[1];
  return sum / double((y1 - y0) * (image.width - 16));
}

// The corner is the farthest point of the center column (the wall's foot).
std::uint32_t cornerRow(const DepthImage& depth) {
  std::uint32_t best = 0;
  float farthest = 0.0f;
  for (std::uint32_t y = 0; y < depth.height; ++y) {
    float d = *depth.at(depth.width / 2, y);
    if (std::isfinite(d) && d > farthest) {
      farthest = d;
      best = y;
    }
  }
  return best;
}

TEST_F(DeferredRendererTest, AmbientOcclusionDarkensTheCornerButNotTheOpenFloor) {
  // Brightness differences below 2 levels are rounding noise at this size.
  DeferredRenderer renderer(context(), kWidth, kHeight);
  const float aspect = float(kWidth) / float(kHeight);
  Scene withOcclusion = cornerScene(true), without = cornerScene(false);
  renderer.setScene(without);
  renderer.render(centerViewMatrices(without, aspect));
  const ImageRGBA8 plain = renderer.readDisplayColor();
  const std::uint32_t corner = cornerRow(renderer.readLinearDepth());
  ASSERT_GT(corner, 2u);
  ASSERT_LT(corner + 3, kHeight - 4);
  renderer.setScene(withOcclusion);
  renderer.render(centerViewMatrices(withOcclusion, aspect));
  const ImageRGBA8 occluded = renderer.readDisplayColor();
  EXPECT_LT(bandBrightness(occluded, corner - 1, corner + 2), bandBrightness(plain, corner - 1, corner + 2) - 2.0);
  EXPECT_NEAR(bandBrightness(occluded, kHeight - 3, kHeight), bandBrightness(plain, kHeight - 3, kHeight), 2.0);
}

TEST_F(DeferredRendererTest, DisabledAmbientOcclusionDoesNotRunItsPass) {
  Scene scene = cornerScene(false);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  std::vector<std::string> names = passNames(renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight))));
  EXPECT_EQ(std::count(names.begin(), names.end(), "ssao"), 0);
}

}  // namespace
}  // namespace s3d::renderer

namespace s3d::renderer {
namespace {

TEST_F(DeferredRendererTest, TransparentMaskCoversTheTransparentPaneOnly) {
  // The wall scene plus a half-opaque pane in front of the left half of the view: the mask (the error
  // metrics' transparent region) is set on the left, clear on the right, and all clear without the pane.
  Scene scene = makeWallScene(5.0f, false);
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  const std::vector<std::uint8_t> none = renderer.readTransparentMask();
  EXPECT_EQ(std::count(none.begin(), none.end(), std::uint8_t(1)), 0);

  Object pane;
  pane.transform = glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f, 0.0f, -2.0f)) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 8.0f, 0.02f));  // x in [-4, 0] at 2 m
  pane.material.opacity = 0.3f;
  scene.objects.push_back(pane);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  const std::vector<std::uint8_t> mask = renderer.readTransparentMask();
  ASSERT_EQ(mask.size(), std::size_t(kWidth) * kHeight);
  EXPECT_EQ(mask[std::size_t(kHeight / 2) * kWidth + 4], 1);           // left: behind the pane
  EXPECT_EQ(mask[std::size_t(kHeight / 2) * kWidth + kWidth - 5], 0);  // right: open
}

}  // namespace
}  // namespace s3d::renderer
