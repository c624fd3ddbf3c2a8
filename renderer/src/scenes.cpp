// Built-in procedural scenes. The courtyard is the default stereo test scene:
//  - camera at (0, 1.7, 6) looking down -Z into a 20 m x 28 m courtyard open on the camera side,
//  - world depths from ~1.55 m (front of a pedestal box, lower left) to ~32 m (back wall), sky above the walls,
//  - thin occluders (pole, slatted fence) in front of bright backgrounds (sky, a pale panel),
//  - a first-person weapon (Layer::FirstPerson, view-space transforms) in the lower right.
#include <stdexcept>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {
namespace {

Material material(glm::vec3 albedo, float glossiness, glm::vec3 f0 = glm::vec3(0.04f)) {
  Material m;
  m.albedo = albedo;
  m.specularColor = f0;
  m.glossiness = glossiness;
  return m;
}

// Axis-aligned box of full size `size` whose bottom face centre is `base` (unit box mesh, half extent 0.5).
glm::mat4 boxOnGround(glm::vec3 base, glm::vec3 size) {
  return glm::scale(glm::translate(glm::mat4(1.0f), base + glm::vec3(0.0f, 0.5f * size.y, 0.0f)), size);
}

// Box centred at `centre` with full size `size`.
glm::mat4 boxAt(glm::vec3 centre, glm::vec3 size) {
  return glm::scale(glm::translate(glm::mat4(1.0f), centre), size);
}

// Upright cylinder (unit cylinder mesh: radius 1, height 1, base at y = 0).
glm::mat4 cylinderAt(glm::vec3 base, float radius, float height) {
  return glm::scale(glm::translate(glm::mat4(1.0f), base), glm::vec3(radius, height, radius));
}

}  // namespace

Scene makeCourtyardScene() {
  Scene scene;
  scene.name = "courtyard";

  // Meshes (deduplicated; objects scale them through their transforms).
  constexpr std::uint32_t kGround = 0, kBox = 1, kCylinder = 2;
  scene.meshes.push_back(makeGroundPlane(30.0f));                 // 60 m x 60 m, centred on the origin
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));               // unit cube centred on its origin
  scene.meshes.push_back(makeCylinder(1.0f, 1.0f, 32));           // unit cylinder, base at y = 0

  // Materials.
  const Material flagstones = material({0.42f, 0.40f, 0.36f}, 0.15f);
  const Material sandstone = material({0.62f, 0.52f, 0.40f}, 0.10f);
  const Material brick = material({0.50f, 0.22f, 0.16f}, 0.12f);
  const Material palePlaster = material({0.88f, 0.86f, 0.80f}, 0.20f);  // bright background for the fence
  const Material marble = material({0.80f, 0.80f, 0.76f}, 0.75f, glm::vec3(0.05f));
  const Material darkStone = material({0.22f, 0.24f, 0.27f}, 0.45f);
  const Material paintedWood = material({0.10f, 0.32f, 0.14f}, 0.35f);
  const Material poleMetal = material({0.06f, 0.06f, 0.06f}, 0.80f, glm::vec3(0.56f, 0.57f, 0.58f));
  const Material redLacquer = material({0.60f, 0.06f, 0.05f}, 0.85f);
  const Material blueCrate = material({0.10f, 0.22f, 0.60f}, 0.30f);
  const Material woodCrate = material({0.45f, 0.30f, 0.16f}, 0.20f);
  const Material brass = material({0.10f, 0.08f, 0.04f}, 0.90f, glm::vec3(0.91f, 0.78f, 0.42f));
  const Material yellowPaint = material({0.75f, 0.62f, 0.10f}, 0.55f);

  auto add = [&scene](std::uint32_t mesh, const Material& m, const glm::mat4& transform,
                      Layer layer = Layer::World) { scene.objects.push_back({mesh, m, transform, layer}); };

  // Ground.
  add(kGround, flagstones, glm::mat4(1.0f));

  // Courtyard walls: back wall 32 m from the camera, side walls at x = +-10, open towards +Z (camera side).
  add(kBox, sandstone, boxOnGround({0.0f, 0.0f, -26.0f}, {20.8f, 5.0f, 0.4f}));
  add(kBox, brick, boxOnGround({-10.0f, 0.0f, -12.0f}, {0.4f, 4.0f, 28.0f}));
  add(kBox, brick, boxOnGround({10.0f, 0.0f, -12.0f}, {0.4f, 4.0f, 28.0f}));

  // Pillars at several depths (camera z = 6, so depth = 6 - z).
  struct PillarSpec { float x, z, radius, height; };
  constexpr PillarSpec pillars[] = {
      {2.4f, 3.0f, 0.25f, 3.8f},     // 3 m, right
      {3.0f, -1.0f, 0.30f, 3.6f},    // 7 m, right
      {4.0f, -5.0f, 0.35f, 4.2f},    // 11 m, right
      {-3.0f, -10.0f, 0.35f, 4.0f},  // 16 m, centre left
      {5.0f, -14.0f, 0.40f, 4.5f},   // 20 m, right
      {-4.0f, -19.0f, 0.40f, 4.5f},  // 25 m, left
  };
  for (const PillarSpec& p : pillars) {
    add(kCylinder, marble, cylinderAt({p.x, 0.0f, p.z}, p.radius, p.height));
    add(kBox, darkStone, boxOnGround({p.x, p.height, p.z}, glm::vec3(2.6f * p.radius, 0.2f, 2.6f * p.radius)));
  }

  // Thin pole, 4 m away, rising out of the top of the view against the sky.
  add(kCylinder, poleMetal, cylinderAt({1.0f, 0.0f, 2.0f}, 0.035f, 4.5f));

  // Fence of thin vertical slats 5 m away (x in [-4.2, -1.32]) in front of a pale panel 8 m away.
  constexpr int kSlats = 25;
  for (int i = 0; i < kSlats; ++i) {
    const float x = -4.2f + 0.12f * static_cast<float>(i);
    add(kBox, paintedWood, boxOnGround({x, 0.0f, 1.0f}, {0.04f, 2.1f, 0.04f}));
  }
  for (float railY : {0.4f, 1.8f})
    add(kBox, paintedWood, boxAt({-2.76f, railY, 0.96f}, {2.96f, 0.06f, 0.04f}));
  add(kBox, palePlaster, boxOnGround({-4.6f, 0.0f, -2.0f}, {5.6f, 3.0f, 0.2f}));

  // Boxes from 1.8 m to 30 m.
  add(kBox, woodCrate, boxOnGround({-0.9f, 0.0f, 4.2f}, {0.5f, 1.1f, 0.5f}));                // 1.8 m, lower left
  add(kBox, redLacquer, boxOnGround({0.8f, 0.0f, -4.0f}, glm::vec3(1.0f)));                 // 10 m
  add(kBox, blueCrate, boxOnGround({-1.2f, 0.0f, -9.0f}, glm::vec3(1.5f)));                 // 15 m
  add(kBox, brass, boxOnGround({-1.2f, 1.5f, -9.0f}, glm::vec3(0.6f)));                     // 15 m, stacked
  add(kBox, yellowPaint, boxOnGround({-4.5f, 0.0f, -16.0f}, {1.2f, 2.0f, 1.2f}));           // 22 m
  add(kBox, darkStone, boxOnGround({1.5f, 0.0f, -24.0f}, glm::vec3(2.0f)));                 // 30 m

  // First-person weapon, in view space (x right, y up, -z forward), lower right of the view.
  const Material gunmetal = material({0.07f, 0.07f, 0.08f}, 0.70f, glm::vec3(0.45f, 0.46f, 0.48f));
  const Material barrelSteel = material({0.04f, 0.04f, 0.04f}, 0.90f, glm::vec3(0.60f, 0.60f, 0.62f));
  const Material gripPolymer = material({0.30f, 0.18f, 0.09f}, 0.30f);
  // Body: 6 cm x 7.5 cm x 20 cm, depth 0.27..0.47 m, top face at y = -0.0425.
  add(kBox, gunmetal, boxAt({0.14f, -0.08f, -0.37f}, {0.06f, 0.075f, 0.20f}), Layer::FirstPerson);
  // Barrel: radius 1.3 cm, lying on the body top from z = -0.32 to -0.60 (cylinder axis +Y rotated onto -Z).
  add(kCylinder, barrelSteel,
      glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.14f, -0.030f, -0.32f}), -glm::half_pi<float>(),
                             glm::vec3(1.0f, 0.0f, 0.0f)),
                 glm::vec3(0.013f, 0.28f, 0.013f)),
      Layer::FirstPerson);
  // Grip: under the body, its bottom tilted back towards the eye by 0.3 rad.
  add(kBox, gripPolymer,
      glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.14f, -0.10f, -0.37f}), -0.3f,
                             glm::vec3(1.0f, 0.0f, 0.0f)),
                 glm::vec3(0.05f, 0.08f, 0.055f)),
      Layer::FirstPerson);

  // Lighting.
  scene.sun.directionToSun = glm::normalize(glm::vec3(-0.45f, 0.75f, 0.5f));
  scene.sun.color = glm::vec3(3.0f, 2.75f, 2.4f);
  scene.ambientColor = glm::vec3(0.26f, 0.30f, 0.36f);
  scene.pointLights.push_back({{-4.0f, 1.4f, -1.2f}, {2.0f, 1.1f, 0.4f}, 6.0f});   // warm, on the pale panel
  scene.pointLights.push_back({{3.4f, 1.2f, -3.2f}, {0.3f, 0.8f, 1.6f}, 5.0f});    // cyan, between pillars
  scene.pointLights.push_back({{0.0f, 2.2f, -21.0f}, {1.2f, 0.4f, 1.0f}, 8.0f});   // magenta, near the back

  // Camera.
  scene.camera.position = glm::vec3(0.0f, 1.7f, 6.0f);
  scene.camera.yawRadians = 0.0f;
  scene.camera.pitchRadians = 0.0f;
  scene.camera.verticalFovRadians = 1.0f;
  scene.camera.nearPlane = 0.1f;
  scene.camera.farPlane = 1000.0f;
  scene.firstPerson = FirstPersonView{};  // fov 0.9, near 0.02, far 4, device depth max 0.1
  scene.exposure = 0.6f;  // the sun-lit light ground would clip at 1.0
  scene.crosshairDistance = 8.0f;
  return scene;
}

Scene makeGlassScene() {
  Scene scene = makeCourtyardScene();
  scene.name = "glass";
  constexpr std::uint32_t kBox = 1;
  // Panes that write no depth in front of geometry at other depths: the seed's transparency flaw.
  Material tintedGlass = material({0.55f, 0.75f, 0.85f}, 0.95f, glm::vec3(0.04f));
  tintedGlass.opacity = 0.35f;
  Material greenGlass = material({0.35f, 0.80f, 0.45f}, 0.95f, glm::vec3(0.04f));
  greenGlass.opacity = 0.5f;
  // A tall window 3 m ahead, left of the view axis, over the fence and the boxes behind it.
  scene.objects.push_back({kBox, tintedGlass, boxOnGround({-1.6f, 0.0f, 3.0f}, {2.2f, 2.6f, 0.02f}), Layer::World});
  // A smaller green pane 2 m ahead, right of centre, in front of the pole and the pillars.
  scene.objects.push_back({kBox, greenGlass, boxOnGround({0.9f, 0.6f, 4.0f}, {0.9f, 1.2f, 0.02f}), Layer::World});
  return scene;
}

std::vector<std::string> builtInSceneNames() { return {"courtyard", "glass"}; }

Scene makeBuiltInScene(const std::string& name) {
  if (name == "courtyard") return makeCourtyardScene();
  if (name == "glass") return makeGlassScene();
  std::string choices;
  for (const std::string& n : builtInSceneNames()) choices += (choices.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown scene '" + name + "' (choices: " + choices + ")");
}

}  // namespace s3d::renderer
