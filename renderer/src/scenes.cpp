// Built-in procedural scenes, each a hard case for stereo image displacement. Every scene has a world layer, the
// same first-person weapon (Layer::FirstPerson, view-space transforms) and a camera path of 24-48 frames.
//  - courtyard: the default stereo test scene. Camera at (0, 1.7, 6) looking down -Z into a 20 m x 28 m
//    courtyard open on the camera side; world depths from ~1.55 m (front of a pedestal box, lower left) to
//    ~32 m (back wall), sky above the walls; thin occluders (pole, slatted fence) in front of bright
//    backgrounds (sky, a pale panel); weapon in the lower right.
//  - glass: the courtyard with transparent panes in front of it.
//  - fence: many thin occluders 2.5-3.5 m ahead (3 cm slats with 3 cm gaps; a chain-link-like diamond grid of
//    1.2 cm wires) in front of bright walls 9-16 m away and the sky; the camera moves sideways past them.
//  - cover: the player stands 0.6 m in front of a wall (cover) with the weapon raised; crates, pillars and a
//    building 5-20 m away show past the wall's right edge. The camera walks up from 4 m and back.
//  - depth-range: a small box on a post 0.3 m from the eye (lower left), objects from 2.5 m to 1.2 km, and
//    mountains ~10 km away; far plane 100 km. The camera turns slowly left.
// Each make...Scene lists its scene's objects, lights and camera path in one function, as data read top to bottom:
// splitting a listing would scatter one scene over several places, so these run past the usual length.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/scene.h"

#include "s3d/number_text.h"

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

// Box centred at `centre` with full size `size` (in its own axes), rotated by `angle` about `axis` through its centre.
glm::mat4 rotatedBoxAt(glm::vec3 centre, float angle, glm::vec3 axis, glm::vec3 size) {
  return glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), centre), angle, axis), size);
}

// Upright cylinder (unit cylinder mesh: radius 1, height 1, base at y = 0).
glm::mat4 cylinderAt(glm::vec3 base, float radius, float height) {
  return glm::scale(glm::translate(glm::mat4(1.0f), base), glm::vec3(radius, height, radius));
}

// Horizontal cylinder along +X from `start` (the unit cylinder's +Y axis turned onto +X).
glm::mat4 cylinderAlongX(glm::vec3 start, float radius, float length) {
  const glm::mat4 turned =
      glm::rotate(glm::translate(glm::mat4(1.0f), start), -glm::half_pi<float>(), glm::vec3(0.0f, 0.0f, 1.0f));
  return glm::scale(turned, glm::vec3(radius, length, radius));
}

// Smooth 0 -> 1 ramp with zero slope at both ends (peak slope 1.5).
float easeInOut(float t) {
  t = glm::clamp(t, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The meshes every built-in scene shares, stored once per scene; objects scale them through their transforms.
struct SceneMeshes {
  std::uint32_t ground = 0;    // makeGroundPlane(groundHalfSize), centred on the origin
  std::uint32_t box = 0;       // unit cube centred on its origin
  std::uint32_t cylinder = 0;  // unit cylinder, base at y = 0
};

SceneMeshes addSceneMeshes(Scene& scene, float groundHalfSize) {
  SceneMeshes m;
  m.ground = static_cast<std::uint32_t>(scene.meshes.size());
  scene.meshes.push_back(makeGroundPlane(groundHalfSize));
  m.box = static_cast<std::uint32_t>(scene.meshes.size());
  scene.meshes.push_back(makeBox(glm::vec3(0.5f)));
  m.cylinder = static_cast<std::uint32_t>(scene.meshes.size());
  scene.meshes.push_back(makeCylinder(1.0f, 1.0f, 32));
  return m;
}

enum class WeaponPose {
  Lowered,  // lower right of the view (courtyard, fence, depth-range)
  Raised,   // 5 cm further in and 3 cm higher, the muzzle near the aim point (cover)
};

// The first-person weapon: body, barrel and grip in view space (x right, y up, -z forward), 0.27-0.6 m away.
void addFirstPersonWeapon(Scene& scene, const SceneMeshes& meshes, WeaponPose pose) {
  const glm::mat4 hold =
      pose == WeaponPose::Raised ? glm::translate(glm::mat4(1.0f), glm::vec3(-0.05f, 0.03f, 0.0f)) : glm::mat4(1.0f);
  auto add = [&scene, &hold](std::uint32_t mesh, const Material& m, const glm::mat4& transform) {
    scene.objects.push_back({mesh, m, hold * transform, Layer::FirstPerson});
  };
  const Material gunmetal = material({0.07f, 0.07f, 0.08f}, 0.70f, glm::vec3(0.45f, 0.46f, 0.48f));
  const Material barrelSteel = material({0.04f, 0.04f, 0.04f}, 0.90f, glm::vec3(0.60f, 0.60f, 0.62f));
  const Material gripPolymer = material({0.30f, 0.18f, 0.09f}, 0.30f);
  // Body: 6 cm x 7.5 cm x 20 cm, depth 0.27..0.47 m, top face at y = -0.0425 (lowered pose).
  add(meshes.box, gunmetal, boxAt({0.14f, -0.08f, -0.37f}, {0.06f, 0.075f, 0.20f}));
  // Barrel: radius 1.3 cm, lying on the body top from z = -0.32 to -0.60 (cylinder axis +Y rotated onto -Z).
  add(meshes.cylinder, barrelSteel,
      glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.14f, -0.030f, -0.32f}), -glm::half_pi<float>(),
                             glm::vec3(1.0f, 0.0f, 0.0f)),
                 glm::vec3(0.013f, 0.28f, 0.013f)));
  // Grip: under the body, its bottom tilted back towards the eye by 0.3 rad.
  add(meshes.box, gripPolymer,
      glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.14f, -0.10f, -0.37f}), -0.3f,
                             glm::vec3(1.0f, 0.0f, 0.0f)),
                 glm::vec3(0.05f, 0.08f, 0.055f)));
}

Camera eyeCamera(glm::vec3 position, float yawRadians, float nearPlane, float farPlane) {
  Camera c;
  c.position = position;
  c.yawRadians = yawRadians;
  c.pitchRadians = 0.0f;
  c.verticalFovRadians = 1.0f;
  c.nearPlane = nearPlane;
  c.farPlane = farPlane;
  return c;
}

float frameFraction(std::size_t frame, std::size_t frames) {  // 0 at the first frame, 1 at the last
  return static_cast<float>(frame) / static_cast<float>(frames - 1);
}

}  // namespace

// The built-in scenes are data written as code: each make*Scene lists its scene's objects, lights and camera path
// in one place, so a scene reads top to bottom (which makes three of them longer than 80 lines).
Scene makeCourtyardScene() {
  Scene scene;
  scene.name = "courtyard";

  const SceneMeshes meshes = addSceneMeshes(scene, 30.0f);  // 60 m x 60 m ground
  const std::uint32_t kGround = meshes.ground, kBox = meshes.box, kCylinder = meshes.cylinder;

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

  addFirstPersonWeapon(scene, meshes, WeaponPose::Lowered);

  // Lighting.
  scene.sun.directionToSun = glm::normalize(glm::vec3(-0.45f, 0.75f, 0.5f));
  scene.sun.color = glm::vec3(3.0f, 2.75f, 2.4f);
  // Sun shadows over the courtyard's depth (back wall at 32 m): three 1024-texel cascades out to 40 m.
  scene.sun.castsShadows = true;
  scene.sun.shadowDistance = 40.0f;
  scene.sun.cascadeCount = 3;
  scene.sun.shadowMapSize = 1024;
  scene.ambientColor = glm::vec3(0.26f, 0.30f, 0.36f);
  scene.pointLights.push_back({{-4.0f, 1.4f, -1.2f}, {2.0f, 1.1f, 0.4f}, 6.0f});   // warm, on the pale panel
  // Cyan, between pillars; its six shadow views throw the pillars' shadows on the ground and walls.
  scene.pointLights.push_back({{3.4f, 1.2f, -3.2f}, {0.3f, 0.8f, 1.6f}, 5.0f, true});
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

  // Sequence: 36 frames (3 s at 12 fps), a sideways sway of +-0.5 m while turning +-0.06 rad towards the
  // side it moves to, so the view keeps roughly centred on the courtyard; frame 0 is `camera`.
  constexpr std::size_t kFrames = 36;
  for (std::size_t i = 0; i < kFrames; ++i) {
    const float phase = glm::two_pi<float>() * static_cast<float>(i) / static_cast<float>(kFrames);
    Camera c = scene.camera;
    c.position.x += 0.5f * std::sin(phase);
    c.yawRadians -= 0.06f * std::sin(phase);
    scene.cameraPath.push_back(c);
  }
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

namespace {

Scene makeFenceScene() {
  Scene scene;
  scene.name = "fence";
  const SceneMeshes meshes = addSceneMeshes(scene, 40.0f);
  auto add = [&scene](std::uint32_t mesh, const Material& m, const glm::mat4& transform) {
    scene.objects.push_back({mesh, m, transform, Layer::World});
  };

  const Material gravel = material({0.40f, 0.38f, 0.35f}, 0.10f);
  const Material darkWood = material({0.16f, 0.10f, 0.06f}, 0.25f);  // dark slats: strongest contrast on bright walls
  const Material galvanized = material({0.22f, 0.23f, 0.24f}, 0.60f, glm::vec3(0.30f));
  const Material whitePlaster = material({0.90f, 0.89f, 0.85f}, 0.15f);
  const Material paleConcrete = material({0.80f, 0.80f, 0.78f}, 0.10f);
  const Material redLacquer = material({0.60f, 0.06f, 0.05f}, 0.85f);
  const Material blueCrate = material({0.10f, 0.22f, 0.60f}, 0.30f);
  const Material yellowPaint = material({0.75f, 0.62f, 0.10f}, 0.55f);
  const Material marble = material({0.80f, 0.80f, 0.76f}, 0.75f, glm::vec3(0.05f));

  add(meshes.ground, gravel, glm::mat4(1.0f));

  // Slatted fence 2.5 m ahead (the camera starts at z = 0): 72 slats 3 cm wide with 3 cm gaps, 2.3 m tall
  // (above the eye, so their tops stand against the sky), x in [-4.415, -0.125], on two rails behind them.
  constexpr int kSlats = 72;
  constexpr float kSlatPitch = 0.06f, kSlatWidth = 0.03f, kFenceZ = -2.5f;
  for (int i = 0; i < kSlats; ++i) {
    const float x = -4.4f + kSlatPitch * static_cast<float>(i);
    add(meshes.box, darkWood, boxOnGround({x, 0.0f, kFenceZ}, {kSlatWidth, 2.3f, 0.02f}));
  }
  for (float railY : {0.35f, 1.95f})
    add(meshes.box, darkWood, boxAt({-2.27f, railY, kFenceZ - 0.03f}, {4.29f, 0.06f, 0.04f}));

  // Chain-link panel 3.5 m ahead, x in [0.1, 4.5], y in [0.1, 2.3]: two families of 1.2 cm wires at +-45 degrees,
  // 7 cm apart (measured across the wires), clipped to the panel; posts and top/bottom pipes frame it.
  constexpr float kLinkZ = -3.5f, kX0 = 0.1f, kX1 = 4.5f, kY0 = 0.1f, kY1 = 2.3f, kWire = 0.012f;
  const float step = 0.07f * glm::root_two<float>();  // spacing of the lines' intercepts
  for (int family = 0; family < 2; ++family) {
    // family 0: y = x + c (rising to the right); family 1: y = c - x (falling), 1 cm behind so crossings don't z-fight.
    const float cMin = family == 0 ? kY0 - kX1 : kX0 + kY0;
    const float cMax = family == 0 ? kY1 - kX0 : kX1 + kY1;
    for (float c = cMin + 0.5f * step; c < cMax; c += step) {
      const float lo = family == 0 ? std::max(kX0, kY0 - c) : std::max(kX0, c - kY1);
      const float hi = family == 0 ? std::min(kX1, kY1 - c) : std::min(kX1, c - kY0);
      if (hi - lo < 0.03f) continue;  // a corner stub
      const float xMid = 0.5f * (lo + hi);
      const float yMid = family == 0 ? xMid + c : c - xMid;
      const float length = (hi - lo) * glm::root_two<float>();
      const float angle = family == 0 ? -0.25f * glm::pi<float>() : 0.25f * glm::pi<float>();  // box +Y onto the wire
      add(meshes.box, galvanized,
          rotatedBoxAt({xMid, yMid, kLinkZ - 0.01f * static_cast<float>(family)}, angle, glm::vec3(0.0f, 0.0f, 1.0f),
                       {kWire, length, kWire}));
    }
  }
  for (float postX : {kX0, 0.5f * (kX0 + kX1), kX1})
    add(meshes.cylinder, galvanized, cylinderAt({postX, 0.0f, kLinkZ - 0.04f}, 0.03f, kY1 + 0.05f));
  for (float pipeY : {kY0, kY1})
    add(meshes.cylinder, galvanized, cylinderAlongX({kX0, pipeY, kLinkZ - 0.03f}, 0.018f, kX1 - kX0));

  // Things at middle depths, seen through the gaps.
  add(meshes.box, redLacquer, boxOnGround({-2.0f, 0.0f, -5.5f}, glm::vec3(0.9f)));
  add(meshes.cylinder, blueCrate, cylinderAt({-0.9f, 0.0f, -6.5f}, 0.35f, 1.0f));
  add(meshes.box, yellowPaint, boxOnGround({2.5f, 0.0f, -7.0f}, glm::vec3(1.0f)));
  add(meshes.cylinder, marble, cylinderAt({4.0f, 0.0f, -10.0f}, 0.3f, 3.5f));

  // Bright backgrounds: a white plaster wall 9 m away behind the slats, a pale concrete wall 16 m away behind the
  // chain link (both hide the ground's far edge); the sky above them.
  add(meshes.box, whitePlaster, boxOnGround({-4.75f, 0.0f, -9.1f}, {12.5f, 2.8f, 0.2f}));   // x in [-11, 1.5]
  add(meshes.box, paleConcrete, boxOnGround({10.5f, 0.0f, -16.1f}, {19.0f, 1.8f, 0.2f}));  // x in [1, 20]

  scene.sun.directionToSun = glm::normalize(glm::vec3(-0.35f, 0.7f, 0.6f));  // lights the walls' camera-facing sides
  scene.sun.color = glm::vec3(3.0f, 2.75f, 2.4f);
  scene.ambientColor = glm::vec3(0.26f, 0.30f, 0.36f);
  scene.pointLights.push_back({{-2.5f, 1.5f, -7.5f}, {2.0f, 1.1f, 0.4f}, 5.0f});  // warm, on the white wall
  scene.pointLights.push_back({{2.0f, 1.0f, -5.0f}, {0.3f, 0.8f, 1.6f}, 4.0f});   // cyan, behind the chain link

  addFirstPersonWeapon(scene, meshes, WeaponPose::Lowered);

  // Sequence: 40 frames, the camera moves 1.8 m to the right along the fences (4.6 cm a frame) while turning
  // 0.08 rad left; frame 0 (centred between the slats and the chain link) is `camera`.
  constexpr std::size_t kFrames = 40;
  for (std::size_t i = 0; i < kFrames; ++i) {
    const float t = frameFraction(i, kFrames);
    scene.cameraPath.push_back(eyeCamera({1.8f * t, 1.7f, 0.0f}, 0.08f * t, 0.1f, 1000.0f));
  }
  scene.camera = scene.cameraPath.front();
  scene.exposure = 0.6f;
  scene.crosshairDistance = 8.0f;
  return scene;
}

Scene makeCoverScene() {
  Scene scene;
  scene.name = "cover";
  const SceneMeshes meshes = addSceneMeshes(scene, 40.0f);
  auto add = [&scene](std::uint32_t mesh, const Material& m, const glm::mat4& transform) {
    scene.objects.push_back({mesh, m, transform, Layer::World});
  };

  const Material asphalt = material({0.30f, 0.30f, 0.31f}, 0.15f);
  const Material concrete = material({0.36f, 0.35f, 0.33f}, 0.10f);
  const Material conduit = material({0.12f, 0.12f, 0.13f}, 0.70f, glm::vec3(0.40f));
  const Material yellowPaint = material({0.75f, 0.62f, 0.10f}, 0.55f);
  const Material darkStone = material({0.22f, 0.24f, 0.27f}, 0.45f);
  const Material woodCrate = material({0.45f, 0.30f, 0.16f}, 0.20f);
  const Material redLacquer = material({0.60f, 0.06f, 0.05f}, 0.85f);
  const Material oliveTruck = material({0.25f, 0.30f, 0.14f}, 0.40f);
  const Material marble = material({0.80f, 0.80f, 0.76f}, 0.75f, glm::vec3(0.05f));
  const Material brick = material({0.50f, 0.22f, 0.16f}, 0.12f);
  const Material poleMetal = material({0.06f, 0.06f, 0.06f}, 0.80f, glm::vec3(0.56f, 0.57f, 0.58f));

  add(meshes.ground, asphalt, glm::mat4(1.0f));

  // The cover: a 2.6 m concrete wall whose camera-facing side is 0.6 m in front of the eye at the cover frame
  // (camera at the origin), x in [-5, 0.1], so its right edge is just right of the view centre; a capping beam,
  // and on its face (at most 5 cm proud) a conduit, a junction box and formwork joints, so it is not a blank plane.
  add(meshes.box, concrete, boxOnGround({-2.45f, 0.0f, -0.75f}, {5.1f, 2.6f, 0.3f}));
  add(meshes.box, darkStone, boxOnGround({-2.45f, 2.6f, -0.75f}, {5.2f, 0.12f, 0.4f}));
  add(meshes.cylinder, conduit, cylinderAlongX({-5.0f, 1.45f, -0.575f}, 0.02f, 5.05f));
  add(meshes.box, yellowPaint, boxAt({-0.35f, 1.45f, -0.58f}, {0.16f, 0.22f, 0.04f}));
  for (float jointX : {-4.2f, -3.0f, -1.8f, -0.6f})
    add(meshes.box, darkStone, boxAt({jointX, 1.3f, -0.598f}, {0.012f, 2.6f, 0.008f}));
  for (float jointY : {0.65f, 1.95f})
    add(meshes.box, darkStone, boxAt({-2.45f, jointY, -0.597f}, {5.1f, 0.012f, 0.008f}));

  // Past the wall's right edge, 5-20 m away.
  add(meshes.box, woodCrate, boxOnGround({3.6f, 0.0f, -5.6f}, glm::vec3(1.2f)));                      // 5 m
  add(meshes.box, woodCrate, boxOnGround({3.7f, 1.2f, -5.7f}, glm::vec3(0.7f)));                      // stacked
  add(meshes.cylinder, redLacquer, cylinderAt({1.0f, 0.0f, -7.0f}, 0.35f, 1.0f));                     // 7 m, barrel
  add(meshes.cylinder, marble, cylinderAt({2.6f, 0.0f, -11.0f}, 0.35f, 4.0f));                        // 11 m, pillar
  add(meshes.box, oliveTruck, boxOnGround({6.0f, 0.0f, -14.0f}, {2.5f, 2.2f, 5.0f}));                 // 11.5 m, truck
  add(meshes.cylinder, poleMetal, cylinderAt({4.4f, 0.0f, -16.0f}, 0.05f, 6.0f));                     // 16 m, lamp post
  add(meshes.box, brick, boxOnGround({7.0f, 0.0f, -20.25f}, {18.0f, 7.0f, 0.5f}));                    // 20 m, building
  add(meshes.box, darkStone, boxOnGround({7.0f, 7.0f, -20.25f}, {18.4f, 0.3f, 0.7f}));                // its cornice

  scene.sun.directionToSun = glm::normalize(glm::vec3(0.7f, 0.6f, 0.35f));  // grazing the wall from the right
  scene.sun.color = glm::vec3(3.0f, 2.75f, 2.4f);
  scene.sun.castsShadows = true;  // the wall's shadow, the truck's and the building's (out to 30 m)
  scene.sun.shadowDistance = 30.0f;
  scene.sun.cascadeCount = 3;
  scene.sun.shadowMapSize = 1024;
  scene.ambientColor = glm::vec3(0.26f, 0.30f, 0.36f);
  scene.pointLights.push_back({{2.4f, 1.5f, -4.0f}, {2.0f, 1.1f, 0.4f}, 5.0f});   // warm, by the crates
  scene.pointLights.push_back({{4.4f, 5.8f, -15.6f}, {1.2f, 1.2f, 1.6f}, 8.0f});  // the lamp
  // A shadowed floodlight aimed past the barrel, on ground seen past the wall's edge (over the sunlit ground its
  // light and the barrel's shadow in it are faint after tone mapping).
  SpotLight flood;
  flood.position = glm::vec3(-0.5f, 3.5f, -5.0f);
  flood.direction = glm::normalize(glm::vec3(1.4f, 0.0f, -8.0f) - flood.position);
  flood.color = glm::vec3(6.0f, 5.2f, 4.0f);
  flood.radius = 9.0f;
  flood.innerConeRadians = 0.35f;
  flood.outerConeRadians = 0.55f;
  flood.castsShadows = true;
  scene.spotLights.push_back(flood);

  addFirstPersonWeapon(scene, meshes, WeaponPose::Raised);

  // Sequence: 48 frames. Frames 0-19 walk up from 4 m to 0.6 m in front of the wall (eased, at most 0.27 m a
  // frame), frames 20-27 stay in cover and glance 0.08 rad right past the edge and back, frames 28-47 walk back.
  // `camera` is frame 20, the first in cover.
  constexpr std::size_t kApproach = 20, kHold = 8, kFrames = 48;
  constexpr float kFarZ = 3.4f;  // 4 m from the wall's face at z = -0.6
  for (std::size_t i = 0; i < kFrames; ++i) {
    float z = 0.0f, yaw = 0.0f;
    if (i < kApproach) {
      z = kFarZ * (1.0f - easeInOut(frameFraction(i, kApproach)));
    } else if (i < kApproach + kHold) {
      yaw = -0.08f * std::sin(glm::pi<float>() * static_cast<float>(i - kApproach) / static_cast<float>(kHold));
    } else {
      z = kFarZ * easeInOut(frameFraction(i - kApproach - kHold, kFrames - kApproach - kHold));
    }
    scene.cameraPath.push_back(eyeCamera({0.0f, 1.7f, z}, yaw, 0.1f, 1000.0f));
  }
  scene.camera = scene.cameraPath[kApproach];
  scene.exposure = 0.6f;
  scene.crosshairDistance = 8.0f;
  return scene;
}

Scene makeDepthRangeScene() {
  Scene scene;
  scene.name = "depth-range";
  const SceneMeshes meshes = addSceneMeshes(scene, 30000.0f);  // 60 km x 60 km: the ground reaches the mountains
  auto add = [&scene](std::uint32_t mesh, const Material& m, const glm::mat4& transform) {
    scene.objects.push_back({mesh, m, transform, Layer::World});
  };

  const Material grass = material({0.20f, 0.30f, 0.12f}, 0.10f);
  const Material woodCrate = material({0.45f, 0.30f, 0.16f}, 0.20f);
  const Material yellowPaint = material({0.75f, 0.62f, 0.10f}, 0.55f);
  const Material poleMetal = material({0.06f, 0.06f, 0.06f}, 0.80f, glm::vec3(0.56f, 0.57f, 0.58f));
  const Material redLacquer = material({0.60f, 0.06f, 0.05f}, 0.85f);
  const Material marble = material({0.80f, 0.80f, 0.76f}, 0.75f, glm::vec3(0.05f));
  const Material blueCrate = material({0.10f, 0.22f, 0.60f}, 0.30f);
  const Material whitePlaster = material({0.90f, 0.89f, 0.85f}, 0.15f);
  const Material rock = material({0.10f, 0.12f, 0.16f}, 0.10f);  // bluish: a hint of aerial perspective
  const Material paleRock = material({0.24f, 0.24f, 0.27f}, 0.10f);
  const Material redRock = material({0.30f, 0.20f, 0.14f}, 0.10f);

  add(meshes.ground, grass, glm::mat4(1.0f));

  // 0.3 m: a 6 cm box on a thin post, lower left of the view (camera at (0, 1.7, 0) looking down -Z).
  add(meshes.box, yellowPaint, boxAt({-0.14f, 1.61f, -0.33f}, glm::vec3(0.06f)));  // front face 0.3 m away
  add(meshes.cylinder, poleMetal, cylinderAt({-0.14f, 0.0f, -0.33f}, 0.012f, 1.58f));

  // Middle distances: 2.5 m to 1.2 km.
  add(meshes.box, woodCrate, boxOnGround({0.9f, 0.0f, -2.9f}, glm::vec3(0.8f)));                 // 2.5 m
  add(meshes.cylinder, marble, cylinderAt({-1.8f, 0.0f, -6.0f}, 0.3f, 3.0f));                    // 6 m
  add(meshes.box, redLacquer, boxOnGround({2.5f, 0.0f, -12.0f}, glm::vec3(1.5f)));              // 12 m
  add(meshes.box, blueCrate, boxOnGround({-6.0f, 0.0f, -30.0f}, {3.0f, 2.5f, 3.0f}));           // 30 m
  add(meshes.cylinder, whitePlaster, cylinderAt({40.0f, 0.0f, -150.0f}, 4.0f, 45.0f));          // 150 m, tower
  add(meshes.box, whitePlaster, boxOnGround({-120.0f, 0.0f, -400.0f}, {60.0f, 25.0f, 30.0f}));  // 400 m, hall
  add(meshes.cylinder, poleMetal, cylinderAt({250.0f, 0.0f, -1200.0f}, 2.0f, 120.0f));          // 1.2 km, mast

  // Mountains 9-12 km away, spread over the bearings the path sees (bearing > 0: left of -Z): ridges are boxes
  // turned 45 degrees about their long axis and half buried (a triangular section), mesas are wide cylinders.
  struct Ridge { float bearingDeg, distance, width, length, headingDeg; };
  constexpr Ridge ridges[] = {
      {-38.0f, 10500.0f, 2200.0f, 7000.0f, 20.0f},  {-14.0f, 9500.0f, 2600.0f, 6000.0f, -10.0f},
      {8.0f, 11500.0f, 3000.0f, 8000.0f, 5.0f},     {30.0f, 10000.0f, 2000.0f, 5000.0f, -25.0f},
      {55.0f, 9000.0f, 2400.0f, 6500.0f, 35.0f},
  };
  for (const Ridge& r : ridges) {
    const float bearing = glm::radians(r.bearingDeg);
    const glm::vec3 centre(-std::sin(bearing) * r.distance, 0.0f, -std::cos(bearing) * r.distance);
    const glm::mat4 heading = glm::rotate(glm::translate(glm::mat4(1.0f), centre), glm::radians(r.headingDeg),
                                          glm::vec3(0.0f, 1.0f, 0.0f));
    // Long axis along local X; the 45 degree turn about it makes the section a diamond with its top 0.71 w up.
    add(meshes.box, r.bearingDeg > 0.0f ? rock : paleRock,
        glm::scale(glm::rotate(heading, 0.25f * glm::pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f)),
                   {r.length, r.width, r.width}));
  }
  struct Mesa { float bearingDeg, distance, radius, height; };
  constexpr Mesa mesas[] = {{-25.0f, 12000.0f, 1500.0f, 700.0f}, {20.0f, 12500.0f, 1800.0f, 900.0f}};
  for (const Mesa& m : mesas) {
    const float bearing = glm::radians(m.bearingDeg);
    add(meshes.cylinder, redRock,
        cylinderAt({-std::sin(bearing) * m.distance, 0.0f, -std::cos(bearing) * m.distance}, m.radius, m.height));
  }

  scene.sun.directionToSun = glm::normalize(glm::vec3(0.55f, 0.5f, 0.45f));  // from the right: lit and shaded flanks
  scene.sun.color = glm::vec3(3.0f, 2.75f, 2.4f);
  scene.ambientColor = glm::vec3(0.26f, 0.30f, 0.36f);
  scene.pointLights.push_back({{0.3f, 1.9f, -0.6f}, {1.6f, 1.2f, 0.8f}, 2.0f});  // a lamp by the near box

  addFirstPersonWeapon(scene, meshes, WeaponPose::Lowered);

  // Sequence: 48 frames turning in place from yaw 0 to 0.3 rad (left), eased; frame 0 is `camera`.
  constexpr std::size_t kFrames = 48;
  for (std::size_t i = 0; i < kFrames; ++i)
    scene.cameraPath.push_back(
        eyeCamera({0.0f, 1.7f, 0.0f}, 0.3f * easeInOut(frameFraction(i, kFrames)), 0.1f, 100000.0f));
  scene.camera = scene.cameraPath.front();
  scene.exposure = 0.6f;
  scene.crosshairDistance = 8.0f;
  return scene;
}

}  // namespace

std::vector<std::string> builtInSceneNames() { return {"courtyard", "glass", "fence", "cover", "depth-range"}; }

Scene makeBuiltInScene(const std::string& name) {
  if (name == "courtyard") return makeCourtyardScene();
  if (name == "glass") return makeGlassScene();
  if (name == "fence") return makeFenceScene();
  if (name == "cover") return makeCoverScene();
  if (name == "depth-range") return makeDepthRangeScene();
  std::string choices;
  for (const std::string& n : builtInSceneNames()) choices += (choices.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown scene '" + name + "' (choices: " + choices + ")");
}

std::string depthRangeProblem(double nearPlane, double farPlane) {
  if (!(nearPlane > 0.0) || !(farPlane > nearPlane) || !(farPlane <= double(std::numeric_limits<float>::max())))
    return "its depth range " + numberText(nearPlane) + " to " + numberText(farPlane) +
           " is not 0 < near < far within single precision";
  if (farPlane / nearPlane > kMaxDepthRangeRatio)
    return "its depth range " + numberText(nearPlane) + " to " + numberText(farPlane) + " spans a far/near ratio of " +
           numberText(farPlane / nearPlane) + ", past the " + numberText(kMaxDepthRangeRatio) +
           " a 32-bit depth buffer resolves (the frame would be empty): raise near or lower far";
  return "";
}

Camera cameraForFrame(const Scene& scene, std::size_t frame) {
  if (scene.cameraPath.empty() && (frame == 0 || scene.animation)) return scene.camera;
  if (frame < scene.cameraPath.size()) return scene.cameraPath[frame];
  const std::size_t count = scene.cameraPath.empty() ? 1 : scene.cameraPath.size();
  throw std::out_of_range("frame " + std::to_string(frame) + " is out of range: scene '" + scene.name +
                          "' has " + std::to_string(count) + (count == 1 ? " frame" : " frames") + " (0.." +
                          std::to_string(count - 1) + ")");
}

std::uint64_t trianglesDrawn(const Scene& scene) {
  std::uint64_t triangles = 0;
  for (const Object& object : scene.objects) triangles += scene.meshes[object.mesh].indices.size() / 3;
  return triangles;
}

}  // namespace s3d::renderer
