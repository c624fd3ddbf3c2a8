#pragma once
// Scene description consumed by the deferred renderer (the tools hand its world layer to comfort's Embree world
// queries).
// Conventions: right-handed, Y up, camera looks down -Z in view space, metres.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/camera.h"

namespace s3d::renderer {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  // triangle list, counter-clockwise seen from outside
  // Optional per-vertex texture coordinates and tangents (both empty, or one per vertex). Tangents are
  // glTF-style: xyz the direction of +u, w = +-1 the handedness (bitangent = w * cross(normal, tangent)).
  std::vector<glm::vec2> texCoords;
  std::vector<glm::vec4> tangents;
};

// An 8-bit RGBA texture, rows top to bottom (texture coordinate v = 0 is the first row).
struct Texture {
  enum class Encoding : std::uint32_t {
    Srgb,    // colour (base color): sampled through an sRGB format, so shaders read linear values
    Linear,  // data (normal maps)
  };
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes
  Encoding encoding = Encoding::Srgb;
};

constexpr std::int32_t kNoTexture = -1;

// Where a material samples a texture (glTF KHR_texture_transform): uv' = T * R * S * uv with T the offset, R the
// rotation (radians, counter-clockwise in glTF's uv space, v pointing down: u' = cos u + sin v, v' = -sin u +
// cos v, as Khronos's TextureTransformTest model checks), S the scale. The default is the identity.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};

  glm::mat3 matrix() const;            // T * R * S (column-major, acting on (u, v, 1))
  glm::vec2 apply(glm::vec2 uv) const;  // matrix() * (uv, 1)
  bool isIdentity() const { return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f); }
};

struct Material {
  glm::vec3 albedo{0.5f};          // linear diffuse reflectance
  glm::vec3 specularColor{0.04f};  // Fresnel reflectance at normal incidence (F0)
  float glossiness = 0.3f;         // 0..1, mapped to a Blinn-Phong exponent
  float opacity = 1.0f;            // < 1: glass-like, drawn alpha-blended after shading and writing no depth
  bool alphaBlend = false;         // drawn in the transparent pass even at opacity 1 (texture alpha, glTF BLEND)
  // Indices into Scene::textures (kNoTexture: none). Base color multiplies albedo (and opacity by its alpha);
  // the normal map is tangent space and needs the mesh's texCoords and tangents.
  std::int32_t baseColorTexture = kNoTexture;
  std::int32_t normalTexture = kNoTexture;
  float normalScale = 1.0f;  // scales the normal map's x and y (glTF normalTexture.scale)
  TextureTransform baseColorTransform;  // where the base-colour texture is sampled
  TextureTransform normalTransform;     // where the normal map is sampled
  // Alpha cut-out (glTF alphaMode MASK), for foliage and fences: 0 means none; in (0, 1] a fragment whose
  // coverage alpha (cutoutAlpha x the base-colour texel's alpha) is below alphaCutoff is not drawn in any pass
  // that writes depth (G-buffer, shadow maps), and where it is drawn the surface is opaque. A cut-out material
  // needs opacity 1 and no alphaBlend.
  float alphaCutoff = 0.0f;
  float cutoutAlpha = 1.0f;  // 0..1: the base colour's alpha (glTF baseColorFactor[3]) a cut-out tests
  // Drawn without back-face culling in every pass; back faces are shaded with the normal flipped toward the
  // viewer (glTF doubleSided). Applies to opaque and cut-out objects; transparent ones are always drawn
  // two-sided in their own pass as before.
  bool doubleSided = false;
  // Light the surface emits, linear HDR radiance added to its lit colour (glTF emissiveFactor x
  // KHR_materials_emissive_strength), >= 0 per channel.
  glm::vec3 emissive{0.0f};

  bool isTransparent() const { return opacity < 1.0f || alphaBlend; }
  bool isCutout() const { return alphaCutoff > 0.0f; }
};

enum class Layer : std::uint32_t {
  World = 0,        // drawn with the scene camera
  FirstPerson = 1,  // drawn in camera space with its own field of view and depth range (Listing 4.3)
};

struct Object {
  std::uint32_t mesh = 0;
  Material material;
  glm::mat4 transform{1.0f};  // World: object -> world. FirstPerson: object -> camera (view) space.
  Layer layer = Layer::World;
  bool castsShadow = true;  // opaque world-layer objects only: the first-person layer and glass never cast
};

struct SunLight {
  glm::vec3 directionToSun{0.0f, 1.0f, 0.0f};  // unit vector
  glm::vec3 color{1.0f};                       // linear radiance scale
  // Cascaded shadow maps (seed 003 8.5.3.5): `cascadeCount` square maps of `shadowMapSize` texels covering
  // the view from the near plane to `shadowDistance` (clamped to the far plane); beyond it the sun is unshadowed.
  // Map sizes (this and Scene::localShadowMapSize) are capped at twice the image's longer side (at least 256).
  bool castsShadows = false;
  float shadowDistance = 60.0f;  // world units
  std::uint32_t cascadeCount = 3;  // 1..4
  std::uint32_t shadowMapSize = 1024;
};

struct PointLight {
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};
  float radius = 5.0f;  // light reaches zero at this distance
  bool castsShadows = false;  // six 90-degree shadow views (seed 000 4.3.3: "six projected light sources")
};

// A projector: a point light limited to a cone, with a smooth edge between the inner and outer angles.
struct SpotLight {
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // where it points, unit vector
  glm::vec3 color{1.0f};
  float radius = 8.0f;               // light reaches zero at this distance
  float innerConeRadians = 0.35f;    // half angle of full intensity
  float outerConeRadians = 0.5f;     // half angle where it reaches zero, < pi/2
  bool castsShadows = false;         // one shadow view covering the outer cone
};

using s3d::Camera;  // s3d/camera.h: comfort casts its rays from the same camera
using s3d::cameraView;

// Largest far/near ratio a camera may have: past 2^24 a 32-bit float depth buffer cannot tell the far plane's
// depth from the cleared one, and the frame comes out empty.
inline constexpr double kMaxDepthRangeRatio = 16777216.0;
// Why a camera's depth range cannot render ("the far/near ratio 1e+60 is past ..."), or "" when it can.
std::string depthRangeProblem(double nearPlane, double farPlane);

// The first-person layer's own projection (Listing 4.2/4.3: different FOV and depth range).
struct FirstPersonView {
  float verticalFovRadians = 0.9f;
  float nearPlane = 0.02f;
  float farPlane = 4.0f;
  float deviceDepthMax = 0.1f;  // first-person depth lands in [0, deviceDepthMax], the world in [deviceDepthMax, 1]
};

struct Sky {
  glm::vec3 zenithColor{0.25f, 0.45f, 0.9f};  // linear HDR radiance
  glm::vec3 horizonColor{0.8f, 0.85f, 0.95f};
  glm::vec3 groundColor{0.3f, 0.28f, 0.25f};
};

struct SceneAnimation;  // scene_animation.h

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Object> objects;
  std::vector<Texture> textures;
  SunLight sun;
  glm::vec3 ambientColor{0.2f};  // hemisphere ambient, scaled by (N.y * 0.7 + 0.3)
  // Screen-space ambient occlusion on the ambient light only; off: the pass does not run.
  bool ambientOcclusion = true;
  float ambientOcclusionRadius = 0.5f;  // world units
  std::vector<PointLight> pointLights;
  std::vector<SpotLight> spotLights;
  std::uint32_t localShadowMapSize = 512;  // texels per point-light face / spot light shadow view
  Sky sky;
  Camera camera;
  std::vector<Camera> cameraPath;  // one camera per frame of the scene's sequence; empty: only `camera`
  FirstPersonView firstPerson;
  float exposure = 1.0f;
  float crosshairDistance = 8.0f;  // default HUD crosshair depth in metres
  // What a scene file holds that the renderer leaves out although the file allows it (an extension it uses but
  // does not require), one sentence each naming the file: a tool reports them as warnings.
  std::vector<std::string> warnings;
  // Skins and node animation (glTF files): what poseScene (scene_animation.h) poses the scene at a time with;
  // null for a static scene. Shared: copies of a scene pose from the same data.
  std::shared_ptr<const SceneAnimation> animation;

  bool hasLayer(Layer layer) const {
    for (const Object& o : objects)
      if (o.layer == layer) return true;
    return false;
  }
};

// Mesh builders: unit-consistent, outward normals, counter-clockwise winding.
Mesh makeBox(glm::vec3 halfExtents);
Mesh makeCylinder(float radius, float height, std::uint32_t segments);  // base at y=0, capped
Mesh makeGroundPlane(float halfSize);                                   // y=0, normal +Y

// Built-in procedural scenes.
Scene makeCourtyardScene();  // the default scene
Scene makeGlassScene();      // the courtyard with transparent panes in front of it
std::vector<std::string> builtInSceneNames();
Scene makeBuiltInScene(const std::string& name);  // throws std::invalid_argument naming the scene and the choices

// The camera of frame `frame` of the scene's sequence: cameraPath[frame], or `camera` for frame 0 of a scene
// without a path (any frame of an animated scene without a path: its animation moves, the camera stays). Throws std::out_of_range naming the frame and the scene's frame count.
Camera cameraForFrame(const Scene& scene, std::size_t frame);

// Triangles a center frame draws: every object's mesh, both layers (an instanced mesh counts per instance).
std::uint64_t trianglesDrawn(const Scene& scene);

}  // namespace s3d::renderer
