// Shadows (seed 003 8.5.3, 000 4.3.3): sun cascades, point-light faces and spot-light views, all looked up by
// the lighting pass; the split scheme and texel snapping; shadow maps scheduled only when a
// caster is in reach. Tiny scenes, 64x36 pixels, small shadow maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/shadows.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kWidth = 64, kHeight = 36;
constexpr float kAspect = float(kWidth) / float(kHeight);

// A ground plane seen from 8 m above, looking almost straight down, with a 1 m box floating over it.
// Sun, point and spot light are off; each test turns on the light it checks.
Scene makeBoxOverGroundScene(glm::vec3 boxCentre) {
  Scene scene;
  scene.name = "box-over-ground";
  scene.meshes.push_back(makeGroundPlane(50.0f));
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  Object ground;
  ground.material.albedo = glm::vec3(0.6f, 0.5f, 0.4f);
  ground.material.glossiness = 0.3f;
  scene.objects.push_back(ground);
  Object box;
  box.mesh = 1;
  box.transform = glm::translate(glm::mat4(1.0f), boxCentre);
  scene.objects.push_back(box);
  scene.sun.color = glm::vec3(0.0f);
  scene.ambientColor = glm::vec3(0.2f, 0.25f, 0.3f);
  scene.ambientOcclusion = false;  // SSAO would darken by its own estimate; these tests check direct light only
  scene.camera.position = glm::vec3(0.0f, 8.0f, 1.5f);
  scene.camera.pitchRadians = -1.4f;
  scene.camera.verticalFovRadians = 1.0f;
  scene.exposure = 1.0f;
  return scene;
}

struct Rendered {
  ImageRGBA32F hdr;
  DepthImage depth;
  std::vector<std::string> passes;
};

Rendered render(vk::Context& context, const Scene& scene) {
  DeferredRenderer renderer(context, kWidth, kHeight);
  renderer.setScene(scene);
  Rendered result;
  for (const PassTiming& pass : renderer.render(centerViewMatrices(scene, kAspect)).passes)
    result.passes.push_back(pass.name);
  result.hdr = renderer.readHdrColor();
  result.depth = renderer.readLinearDepth();
  return result;
}

// The view depth of a world point (what the linear-depth output holds).
double viewDepth(const Scene& scene, glm::dvec3 world) {
  return -(glm::dmat4(cameraView(scene.camera)) * glm::dvec4(world, 1.0)).z;
}

bool ran(const Rendered& frame, const std::string& pass) {
  return std::find(frame.passes.begin(), frame.passes.end(), pass) != frame.passes.end();
}

// The pixel whose centre sees `world`, and the ground point that pixel centre actually sees (y = 0).
struct Probe {
  std::uint32_t x = 0, y = 0;
  glm::dvec3 ground{0.0};
};

Probe probeAt(const Scene& scene, glm::vec3 world) {
  const ViewMatrices view = centerViewMatrices(scene, kAspect);
  const glm::vec4 clip = view.worldProjection * view.worldView * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  Probe probe;
  probe.x = std::uint32_t((ndc.x * 0.5f + 0.5f) * float(kWidth));
  probe.y = std::uint32_t((ndc.y * 0.5f + 0.5f) * float(kHeight));
  const double tanHalfFov = std::tan(double(scene.camera.verticalFovRadians) / 2.0);
  const double px = (probe.x + 0.5) / kWidth * 2.0 - 1.0, py = (probe.y + 0.5) / kHeight * 2.0 - 1.0;
  const glm::dvec3 viewRay(px * tanHalfFov * kAspect, -py * tanHalfFov, -1.0);  // Vulkan: +y is down the image
  const glm::dvec3 worldRay = glm::dmat3(glm::inverse(glm::dmat4(view.worldView))) * viewRay;
  const glm::dvec3 eye(scene.camera.position);
  probe.ground = eye + worldRay * (-eye.y / worldRay.y);
  return probe;
}

// Whether the segment from p to q passes through the axis-aligned box (slab test).
bool segmentHitsBox(glm::dvec3 p, glm::dvec3 q, glm::dvec3 lo, glm::dvec3 hi) {
  double t0 = 0.0, t1 = 1.0;
  const glm::dvec3 d = q - p;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(d[axis]) < 1e-12) {
      if (p[axis] < lo[axis] || p[axis] > hi[axis]) return false;
      continue;
    }
    double a = (lo[axis] - p[axis]) / d[axis], b = (hi[axis] - p[axis]) / d[axis];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

// The analytic exposed radiance of the ground at `surface`: hemisphere ambient plus, unless shadowed, one light
// arriving from `toLight` with radiance `incoming` (normalized Blinn-Phong + Schlick, as in test_lighting).
glm::dvec3 groundRadiance(const Scene& scene, glm::dvec3 surface, glm::dvec3 toLight, glm::dvec3 incoming) {
  const Material& material = scene.objects[0].material;
  const glm::dvec3 normal(0.0, 1.0, 0.0);
  const glm::dvec3 toEye = glm::normalize(glm::dvec3(scene.camera.position) - surface);
  const double nDotL = std::max(glm::dot(normal, toLight), 0.0);
  const double nDotH = std::max(glm::dot(normal, glm::normalize(toLight + toEye)), 0.0);
  const double nDotV = std::clamp(glm::dot(normal, toEye), 0.0, 1.0);
  const double exponent = std::exp2(10.0 * material.glossiness + 1.0);
  const double lobe = (exponent + 8.0) / 8.0 * std::pow(nDotH, exponent);
  const glm::dvec3 f0(material.specularColor);
  const glm::dvec3 fresnel = f0 + (1.0 - f0) * std::pow(1.0 - nDotV, 5.0);
  const glm::dvec3 ambient = glm::dvec3(scene.ambientColor);  // N.y = 1: (N.y * 0.7 + 0.3) = 1
  return glm::dvec3(material.albedo) * (ambient + incoming * nDotL) + fresnel * (incoming * nDotL * lobe);
}

glm::dvec3 ambientOnly(const Scene& scene, glm::dvec3 surface) {
  return groundRadiance(scene, surface, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0));
}

// Radiance of a point or spot light at `surface` before shadowing (falloff as in renderer_shared.h).
glm::dvec3 localIncoming(glm::dvec3 surface, glm::dvec3 position, glm::dvec3 color, double radius) {
  const double distance = glm::length(position - surface);
  const double ratio = std::min(distance / radius, 1.0);
  const double window = (1.0 - ratio * ratio) * (1.0 - ratio * ratio);
  return color * (window / (1.0 + distance * distance));
}

// Tolerance 1 % relative, as for the lit plane in test_lighting: RGBA16F light and HDR buffers, and a specular
// exponent of 16 amplifying the normal buffer's rounding. The probes lie at least 0.3 m (over 4 texels of the
// finest map used) from a shadow edge, so the PCF footprint sees only lit or only shadowed texels.
void expectRadiance(const Rendered& frame, const Probe& probe, glm::dvec3 expected, const char* what) {
  const float* rendered = frame.hdr.at(probe.x, probe.y);
  for (int channel = 0; channel < 3; ++channel)
    EXPECT_NEAR(rendered[channel], expected[channel], 0.01 * expected[channel])
        << what << " at pixel (" << probe.x << ", " << probe.y << ") channel " << channel;
}

class ShadowTest : public test::VulkanTest {};

// Sun from +x: the box floating at y 1..2 shadows the ground at x in [-2.17, -0.33], z in [-0.5, 0.5].
Scene makeSunScene() {
  Scene scene = makeBoxOverGroundScene({0.0f, 1.5f, 0.0f});
  scene.sun.directionToSun = glm::normalize(glm::vec3(1.0f, 1.2f, 0.0f));
  scene.sun.color = glm::vec3(2.0f, 1.8f, 1.6f);
  scene.sun.castsShadows = true;
  scene.sun.cascadeCount = 2;
  scene.sun.shadowMapSize = 256;
  scene.sun.shadowDistance = 20.0f;
  return scene;
}

TEST_F(ShadowTest, AGroundPointInTheBoxsSunShadowGetsOnlyAmbient) {
  const Scene scene = makeSunScene();
  const Probe probe = probeAt(scene, {-1.25f, 0.0f, 0.0f});
  const glm::dvec3 toSun = glm::normalize(glm::dvec3(scene.sun.directionToSun));
  // The sun ray from the probe crosses the box well inside (box shrunk by 0.3 m), and the camera sees the ground.
  ASSERT_TRUE(segmentHitsBox(probe.ground, probe.ground + 10.0 * toSun, {-0.2, 1.3, -0.2}, {0.2, 1.7, 0.2}));
  const Rendered frame = render(context(), scene);
  ASSERT_NEAR(*frame.depth.at(probe.x, probe.y), viewDepth(scene, probe.ground), 0.01);  // the ground, not the box
  EXPECT_TRUE(ran(frame, "shadow-sun-cascade-0"));
  EXPECT_TRUE(ran(frame, "lighting"));  // which looks the cascades up itself (no screen-space mask pass)
  const glm::dvec3 unshadowed = groundRadiance(scene, probe.ground, toSun, glm::dvec3(scene.sun.color));
  ASSERT_GT(unshadowed.g, 3.0 * ambientOnly(scene, probe.ground).g);  // so a missing shadow cannot pass
  expectRadiance(frame, probe, ambientOnly(scene, probe.ground), "sun shadow");
}

TEST_F(ShadowTest, AGroundPointOutsideTheSunShadowGetsTheUnshadowedSunlight) {
  const Scene scene = makeSunScene();
  const Probe probe = probeAt(scene, {1.5f, 0.0f, 0.5f});
  const glm::dvec3 toSun = glm::normalize(glm::dvec3(scene.sun.directionToSun));
  ASSERT_FALSE(segmentHitsBox(probe.ground, probe.ground + 10.0 * toSun, {-0.8, 0.7, -0.8}, {0.8, 2.3, 0.8}));
  const Rendered frame = render(context(), scene);
  expectRadiance(frame, probe, groundRadiance(scene, probe.ground, toSun, glm::dvec3(scene.sun.color)), "sunlit ground");
}

// A light at (1.2, 3.6, 0) over a box centred at (0.4, 1.8, 0): the box's shadow is centred at (-0.4, 0, 0).
constexpr glm::vec3 kLightPosition{1.2f, 3.6f, 0.0f};
constexpr glm::vec3 kLocalBoxCentre{0.4f, 1.8f, 0.0f};
constexpr glm::vec3 kLocalShadowProbe{-0.4f, 0.0f, 0.0f};
constexpr glm::vec3 kLocalLitProbe{2.5f, 0.0f, 1.5f};

Scene makePointLightScene() {
  Scene scene = makeBoxOverGroundScene(kLocalBoxCentre);
  PointLight light;
  light.position = kLightPosition;
  light.color = glm::vec3(12.0f, 11.0f, 10.0f);
  light.radius = 10.0f;
  light.castsShadows = true;
  scene.pointLights.push_back(light);
  scene.localShadowMapSize = 128;
  return scene;
}

Scene makeSpotLightScene() {
  Scene scene = makeBoxOverGroundScene(kLocalBoxCentre);
  SpotLight light;
  light.position = kLightPosition;
  light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  light.color = glm::vec3(12.0f, 11.0f, 10.0f);
  light.radius = 10.0f;
  light.innerConeRadians = 0.6f;  // both probes lie inside the inner cone (0.42 and 0.50 rad off the axis)
  light.outerConeRadians = 0.75f;
  light.castsShadows = true;
  scene.spotLights.push_back(light);
  scene.localShadowMapSize = 128;
  return scene;
}

void expectLocalShadowedAndLit(vk::Context& context, const Scene& scene, glm::dvec3 color, const char* shadowPass) {
  const glm::dvec3 lightPosition(kLightPosition);
  const Probe shadowed = probeAt(scene, kLocalShadowProbe), lit = probeAt(scene, kLocalLitProbe);
  const glm::dvec3 boxLo = glm::dvec3(kLocalBoxCentre) - 0.5, boxHi = glm::dvec3(kLocalBoxCentre) + 0.5;
  ASSERT_TRUE(segmentHitsBox(shadowed.ground, lightPosition, boxLo + 0.25, boxHi - 0.25));
  ASSERT_FALSE(segmentHitsBox(lit.ground, lightPosition, boxLo - 0.3, boxHi + 0.3));
  const Rendered frame = render(context, scene);
  EXPECT_TRUE(ran(frame, shadowPass));
  ASSERT_NEAR(*frame.depth.at(shadowed.x, shadowed.y), viewDepth(scene, shadowed.ground), 0.01);  // not the box

  const glm::dvec3 toLightShadowed = glm::normalize(lightPosition - shadowed.ground);
  const glm::dvec3 unshadowed = groundRadiance(scene, shadowed.ground, toLightShadowed,
                                               localIncoming(shadowed.ground, lightPosition, color, 10.0));
  ASSERT_GT(unshadowed.g, 3.0 * ambientOnly(scene, shadowed.ground).g);  // so a missing shadow cannot pass
  expectRadiance(frame, shadowed, ambientOnly(scene, shadowed.ground), "shadowed ground");
  const glm::dvec3 toLightLit = glm::normalize(lightPosition - lit.ground);
  expectRadiance(frame, lit,
                 groundRadiance(scene, lit.ground, toLightLit, localIncoming(lit.ground, lightPosition, color, 10.0)),
                 "lit ground");
}

TEST_F(ShadowTest, APointLightsBoxShadowGetsOnlyAmbientAndALitPointTheUnshadowedLight) {
  const Scene scene = makePointLightScene();
  expectLocalShadowedAndLit(context(), scene, glm::dvec3(scene.pointLights[0].color), "shadow-point-0");
}

TEST_F(ShadowTest, ASpotLightsBoxShadowGetsOnlyAmbientAndALitPointTheUnshadowedLight) {
  const Scene scene = makeSpotLightScene();
  expectLocalShadowedAndLit(context(), scene, glm::dvec3(scene.spotLights[0].color), "shadow-spot-0");
}

TEST_F(ShadowTest, APointLightsShadowMapRendersOncePerSceneAndLaterFramesKeepIt) {
  // The second frame runs no point-light pass and shades exactly as the first (the kept map); a moved box
  // (setScene) renders it again, so its shadow moves with it.
  Scene scene = makePointLightScene();
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  auto frame = [&] {
    Rendered result;
    for (const PassTiming& pass : renderer.render(centerViewMatrices(scene, kAspect)).passes) result.passes.push_back(pass.name);
    result.hdr = renderer.readHdrColor();
    return result;
  };
  const Rendered first = frame();
  const Rendered second = frame();
  EXPECT_TRUE(ran(first, "shadow-point-0"));
  EXPECT_FALSE(ran(second, "shadow-point-0"));
  EXPECT_EQ(first.hdr.pixels, second.hdr.pixels);
  scene.objects[1].transform = glm::translate(scene.objects[1].transform, glm::vec3(0.0f, 0.0f, 2.5f));
  renderer.setScene(scene);
  const Rendered moved = frame();
  EXPECT_TRUE(ran(moved, "shadow-point-0"));
  EXPECT_NE(moved.hdr.pixels, first.hdr.pixels);
}

bool anyShadowPass(const Rendered& frame) {
  return std::any_of(frame.passes.begin(), frame.passes.end(),
                     [](const std::string& name) { return name.rfind("shadow-", 0) == 0; });
}

TEST_F(ShadowTest, ASunWithoutCastersRunsNoShadowPass) {
  Scene scene = makeSunScene();
  for (Object& object : scene.objects) object.castsShadow = false;
  const Rendered frame = render(context(), scene);
  EXPECT_FALSE(anyShadowPass(frame));
  EXPECT_TRUE(ran(frame, "lighting"));
}

TEST_F(ShadowTest, APointLightWithItsOnlyCasterOutOfReachRunsNoShadowMap) {
  Scene scene = makePointLightScene();
  scene.objects[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(14.0f, 0.5f, 0.0f));  // 13 m away, radius 10
  scene.objects[0].castsShadow = false;  // the ground lies in every downward face
  const Rendered frame = render(context(), scene);
  EXPECT_FALSE(anyShadowPass(frame));
  EXPECT_TRUE(ran(frame, "lighting"));  // the light itself still lights the ground
}

TEST_F(ShadowTest, ASpotLightWithItsOnlyCasterOutsideTheConeRunsNoShadowMap) {
  Scene scene = makeSpotLightScene();
  scene.objects[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(7.0f, 0.5f, 0.0f));  // 61 degrees off axis
  scene.objects[0].castsShadow = false;
  const Rendered frame = render(context(), scene);
  EXPECT_FALSE(anyShadowPass(frame));
  EXPECT_TRUE(ran(frame, "lighting"));
}

// setScene's message for a scene, or "" when it is accepted.
std::string setSceneError(vk::Context& context, const Scene& scene) {
  DeferredRenderer renderer(context, kWidth, kHeight);
  try {
    renderer.setScene(scene);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST_F(ShadowTest, ASpotLightWithAConeOfNinetyDegreesOrMoreIsRejected) {
  Scene scene = makeSpotLightScene();
  scene.spotLights[0].outerConeRadians = 1.6f;
  EXPECT_NE(setSceneError(context(), scene).find("cone angles"), std::string::npos);
}

TEST_F(ShadowTest, MoreSunCascadesThanFourAreRejected) {
  Scene scene = makeSunScene();
  scene.sun.cascadeCount = 5;
  EXPECT_NE(setSceneError(context(), scene).find("sun cascade count must be 1..4"), std::string::npos);
}

TEST_F(ShadowTest, MoreShadowViewsThanTheAtlasHoldsAreRejected) {
  Scene scene = makePointLightScene();
  scene.pointLights.assign(9, scene.pointLights[0]);  // 54 views, the atlas holds 48
  EXPECT_NE(setSceneError(context(), scene).find("shadow views, at most 48"), std::string::npos);
}

TEST(CascadeSplits, FollowTheBlendOfLogarithmicAndUniformSplits) {
  const float nearPlane = 0.1f, farPlane = 60.0f;
  const std::vector<float> splits = cascadeSplitDistances(nearPlane, farPlane, 4, kCascadeLogWeight);
  ASSERT_EQ(splits.size(), 5u);
  for (std::size_t i = 0; i < splits.size(); ++i) {
    const double t = double(i) / 4.0;
    const double logarithmic = nearPlane * std::pow(double(farPlane) / nearPlane, t);
    const double uniform = nearPlane + (farPlane - nearPlane) * t;
    const double expected = kCascadeLogWeight * logarithmic + (1.0 - kCascadeLogWeight) * uniform;
    EXPECT_NEAR(splits[i], expected, 1e-5 * expected) << "split " << i;  // float rounding of the blend
  }
}

TEST(CascadeSplits, WeightOneIsGeometricAndWeightZeroIsUniform) {
  const std::vector<float> logarithmic = cascadeSplitDistances(0.5f, 512.0f, 3, 1.0f);
  const std::vector<float> uniform = cascadeSplitDistances(0.5f, 512.0f, 3, 0.0f);
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_NEAR(logarithmic[i + 1] / logarithmic[i], logarithmic[i] / logarithmic[i - 1], 1e-4);  // constant ratio
    EXPECT_NEAR(uniform[i + 1] - uniform[i], uniform[i] - uniform[i - 1], 1e-3);                   // constant step
  }
}

TEST(CascadeSplits, RejectABadRange) {
  EXPECT_THROW(cascadeSplitDistances(0.0f, 10.0f, 3), std::invalid_argument);
  EXPECT_THROW(cascadeSplitDistances(1.0f, 10.0f, 5), std::invalid_argument);
}

// Texel position of a world point in cascade `cascade`'s shadow map.
glm::dvec2 shadowTexel(const SunCascade& cascade, glm::vec3 world, std::uint32_t size) {
  const glm::dvec4 clip = glm::dmat4(cascade.viewProjection) * glm::dvec4(glm::dvec3(world), 1.0);
  return (glm::dvec2(clip) * 0.5 + 0.5) * double(size);
}

TEST(SunCascades, TexelSnappingKeepsTheTexelGridFixedUnderASubTexelCameraMove) {
  Scene scene = makeSunScene();
  scene.camera.position = glm::vec3(0.3f, 1.7f, 4.0f);
  scene.camera.pitchRadians = -0.2f;
  constexpr std::uint32_t kSize = 1024;
  const std::vector<float> splits = cascadeSplitDistances(0.1f, 40.0f, 3);
  const BoundingSphere caster{{0.0f, 1.5f, 0.0f}, 0.87f};
  auto cascadesFor = [&](const Scene& s) {
    const ViewMatrices view = centerViewMatrices(s, kAspect);
    return sunCascades(view.worldView, view.worldProjection, splits, s.sun.directionToSun, kSize, {&caster, 1});
  };
  const std::vector<SunCascade> before = cascadesFor(scene);
  Scene moved = scene;
  moved.camera.position += glm::vec3(0.37f * before[0].texelWorldSize, 0.0f, 0.21f * before[0].texelWorldSize);
  const std::vector<SunCascade> after = cascadesFor(moved);
  const glm::vec3 world(-0.8f, 0.0f, 1.3f);
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_FLOAT_EQ(after[i].texelWorldSize, before[i].texelWorldSize) << "cascade " << i;
    // The map may shift, but only by whole texels: a world point keeps its position within its texel.
    // Tolerance 1e-3 texel: float rounding of the light-space transform at ~1e3 texels.
    const glm::dvec2 shift = shadowTexel(after[i], world, kSize) - shadowTexel(before[i], world, kSize);
    EXPECT_NEAR(shift.x, std::round(shift.x), 1e-3) << "cascade " << i;
    EXPECT_NEAR(shift.y, std::round(shift.y), 1e-3) << "cascade " << i;
  }
}

TEST(SunCascades, EachCascadeCoversItsWholeSlice) {
  const Scene scene = makeSunScene();
  const ViewMatrices view = centerViewMatrices(scene, kAspect);
  const std::vector<float> splits = cascadeSplitDistances(0.1f, 20.0f, 2);
  const BoundingSphere caster{{0.0f, 1.5f, 0.0f}, 0.87f};
  const std::vector<SunCascade> cascades =
      sunCascades(view.worldView, view.worldProjection, splits, scene.sun.directionToSun, 256, {&caster, 1});
  const glm::mat4 worldFromView = glm::inverse(view.worldView);
  for (std::size_t i = 0; i < cascades.size(); ++i)
    for (float depth : {splits[i], splits[i + 1]})
      for (glm::vec2 ndc : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(-1, 1), glm::vec2(1, 1)}) {
        const glm::vec3 viewPoint(ndc.x * depth / view.worldProjection[0][0], ndc.y * depth / view.worldProjection[1][1],
                                  -depth);
        const glm::vec4 clip = cascades[i].viewProjection * worldFromView * glm::vec4(viewPoint, 1.0f);
        EXPECT_LE(std::abs(clip.x), 1.0001f) << "cascade " << i;
        EXPECT_LE(std::abs(clip.y), 1.0001f) << "cascade " << i;
        EXPECT_GE(clip.z, -1e-4f);
        EXPECT_LE(clip.z, 1.0001f);
      }
}

}  // namespace
}  // namespace s3d::renderer
