// Light accumulation and shading checked against the analytic model (section 4.3.3): hemisphere ambient,
// a sun with normalized Blinn-Phong specular and Schlick Fresnel, evaluated here by hand in double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {

constexpr std::uint32_t kWidth = 64, kHeight = 36;

// A camera 2 m above an open ground plane, looking down at it, lit by a sun close to the mirror direction so
// the specular lobe contributes as much as the diffuse term at the probed pixel.
Scene makeLitPlaneScene() {
  Scene scene;
  scene.name = "lit-plane";
  scene.meshes.push_back(makeGroundPlane(200.0f));
  Object ground;
  ground.material.albedo = glm::vec3(0.6f, 0.5f, 0.4f);
  ground.material.specularColor = glm::vec3(0.04f);
  ground.material.glossiness = 0.3f;  // Blinn-Phong exponent 2^(10 * 0.3 + 1) = 16
  scene.objects.push_back(ground);
  scene.sun.directionToSun = glm::normalize(glm::vec3(0.1f, 0.6f, -0.8f));
  scene.sun.color = glm::vec3(2.0f, 1.8f, 1.6f);
  scene.ambientColor = glm::vec3(0.2f, 0.25f, 0.3f);
  scene.ambientOcclusion = false;  // SSAO would darken by its own estimate; this test checks the lighting model
  scene.camera.position = glm::vec3(0.0f, 2.0f, 0.0f);
  scene.camera.pitchRadians = -0.5f;
  scene.camera.verticalFovRadians = 0.8f;
  scene.exposure = 1.0f;
  return scene;
}

// The analytic exposed HDR radiance of the ground plane seen through pixel (x, y).
glm::dvec3 analyticPlaneRadiance(const Scene& scene, std::uint32_t x, std::uint32_t y) {
  const Camera& camera = scene.camera;
  const double aspect = double(kWidth) / double(kHeight);
  const double tanHalfFov = std::tan(double(camera.verticalFovRadians) / 2.0);
  const double ndcX = (x + 0.5) / kWidth * 2.0 - 1.0;
  const double ndcY = (y + 0.5) / kHeight * 2.0 - 1.0;  // Vulkan: +y is down the image
  const glm::dvec3 viewRay(ndcX * tanHalfFov * aspect, -ndcY * tanHalfFov, -1.0);
  const glm::dmat4 worldFromView = glm::inverse(glm::dmat4(cameraView(camera)));
  const glm::dvec3 worldRay = glm::dmat3(worldFromView) * viewRay;
  const glm::dvec3 eye(camera.position);
  const glm::dvec3 surface = eye + worldRay * (-eye.y / worldRay.y);  // hit on y = 0

  const Material& material = scene.objects[0].material;
  const glm::dvec3 normal(0.0, 1.0, 0.0);
  const glm::dvec3 toLight = glm::normalize(glm::dvec3(scene.sun.directionToSun));
  const glm::dvec3 toEye = glm::normalize(eye - surface);
  const double nDotL = std::max(glm::dot(normal, toLight), 0.0);
  const double nDotH = std::max(glm::dot(normal, glm::normalize(toLight + toEye)), 0.0);
  const double nDotV = std::clamp(glm::dot(normal, toEye), 0.0, 1.0);
  const double exponent = std::exp2(10.0 * material.glossiness + 1.0);
  const double specularLobe = (exponent + 8.0) / 8.0 * std::pow(nDotH, exponent);
  const glm::dvec3 sun(scene.sun.color);
  const glm::dvec3 ambient = glm::dvec3(scene.ambientColor) * (normal.y * 0.7 + 0.3);
  const glm::dvec3 f0(material.specularColor);
  const glm::dvec3 fresnel = f0 + (1.0 - f0) * std::pow(1.0 - nDotV, 5.0);
  const glm::dvec3 radiance =
      glm::dvec3(material.albedo) * (ambient + sun * nDotL) + fresnel * (sun * nDotL * specularLobe);
  return radiance * double(scene.exposure);
}

class LightingTest : public test::VulkanTest {};

TEST_F(LightingTest, ALitPlaneMatchesTheAnalyticBlinnPhongValue) {
  const Scene scene = makeLitPlaneScene();
  DeferredRenderer renderer(context(), kWidth, kHeight);
  renderer.setScene(scene);
  renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  const ImageRGBA32F hdr = renderer.readHdrColor();
  // The probe must see a strong specular lobe, or a wrong lobe would go unnoticed.
  Scene matte = scene;
  matte.objects[0].material.specularColor = glm::vec3(0.0f);
  ASSERT_GT(analyticPlaneRadiance(scene, kWidth / 2, kHeight / 2).g,
            1.05 * analyticPlaneRadiance(matte, kWidth / 2, kHeight / 2).g);
  // Tolerance 1 % relative: the HDR and normal buffers are RGBA16F (11-bit mantissa, 0.05 %), the lobe's
  // exponent 16 amplifies a normal error of 1e-3 to under 0.5 %, the packed albedo under 1e-5.
  for (std::uint32_t y : {kHeight / 2, kHeight * 3 / 4}) {
    for (std::uint32_t x : {kWidth / 4, kWidth / 2, kWidth * 3 / 4}) {
      const glm::dvec3 expected = analyticPlaneRadiance(scene, x, y);
      const float* rendered = hdr.at(x, y);
      for (int channel = 0; channel < 3; ++channel)
        EXPECT_NEAR(rendered[channel], expected[channel], 0.01 * expected[channel])
            << "pixel (" << x << ", " << y << ") channel " << channel;
    }
  }
}

// A wall 4 m ahead filling the view, and optionally a red half-transparent pane 2 m ahead over its left half.
Scene makePaneScene(bool withPane) {
  Scene scene;
  scene.name = "pane";
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  scene.ambientOcclusion = false;
  scene.camera.position = glm::vec3(0.0f, 0.0f, 0.0f);
  scene.sun.directionToSun = glm::normalize(glm::vec3(0.2f, 0.5f, 1.0f));
  Object wall;
  wall.material.albedo = glm::vec3(0.5f);
  wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -4.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(40.0f, 40.0f, 1.0f));
  scene.objects.push_back(wall);
  if (withPane) {
    Object pane;
    pane.material.albedo = glm::vec3(0.9f, 0.05f, 0.05f);
    pane.material.opacity = 0.5f;
    pane.transform = glm::translate(glm::mat4(1.0f), glm::vec3(-5.0f, 0.0f, -2.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(10.0f, 10.0f, 0.02f));
    scene.objects.push_back(pane);
  }
  return scene;
}

struct PaneFrame {
  std::vector<std::string> passes;
  ImageRGBA32F hdr;
  DepthImage depth;
};

PaneFrame renderPaneScene(vk::Context& context, bool withPane) {
  const Scene scene = makePaneScene(withPane);
  DeferredRenderer renderer(context, kWidth, kHeight);
  renderer.setScene(scene);
  PaneFrame frame;
  for (const PassTiming& pass : renderer.render(centerViewMatrices(scene, float(kWidth) / float(kHeight))).passes)
    frame.passes.push_back(pass.name);
  frame.hdr = renderer.readHdrColor();
  frame.depth = renderer.readLinearDepth();
  return frame;
}

TEST_F(LightingTest, AnOpaqueSceneDoesNotRunTheTransparentPass) {
  const PaneFrame frame = renderPaneScene(context(), false);
  EXPECT_EQ(std::count(frame.passes.begin(), frame.passes.end(), "transparent"), 0);
}

TEST_F(LightingTest, ATransparentPaneIsBlendedAfterLightingAndWritesNoDepth) {
  const PaneFrame opaque = renderPaneScene(context(), false);
  const PaneFrame glass = renderPaneScene(context(), true);
  const auto shading = std::find(glass.passes.begin(), glass.passes.end(), "lighting");
  const auto transparent = std::find(glass.passes.begin(), glass.passes.end(), "transparent");
  ASSERT_NE(transparent, glass.passes.end());
  EXPECT_LT(shading, transparent);
  const std::uint32_t behindPane = kWidth / 4, besidePane = kWidth * 3 / 4, row = kHeight / 2;
  // The stereo pass must see the wall through the glass (the seed's transparency case): depth is the wall's.
  EXPECT_FLOAT_EQ(*glass.depth.at(behindPane, row), *opaque.depth.at(behindPane, row));
  // Behind the red pane (a thin box: the view crosses two faces, each blended at opacity 0.5) a quarter of the
  // wall's green shows through, plus the pane's own dim green (albedo 0.05): between 0.25 and 0.5 of the wall's
  // green, while red dominates.
  const float* tinted = glass.hdr.at(behindPane, row);
  const float* plain = opaque.hdr.at(behindPane, row);
  EXPECT_GT(tinted[0], tinted[1] * 1.5f);
  EXPECT_GE(tinted[1], 0.25f * plain[1]);
  EXPECT_LE(tinted[1], 0.5f * plain[1]);
  // Beside the pane nothing changes.
  for (int channel = 0; channel < 3; ++channel)
    EXPECT_FLOAT_EQ(glass.hdr.at(besidePane, row)[channel], opaque.hdr.at(besidePane, row)[channel]);
}

}  // namespace
}  // namespace s3d::renderer
