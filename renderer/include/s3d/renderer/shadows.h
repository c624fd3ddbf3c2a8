#pragma once
// Shadow geometry shared by the renderer's shadow passes and the tests: cascade splits, the snapped sun
// cascade projections, the point-light faces and spot-light views, and which casters reach which view.
// All projections use Vulkan clip space (y down, depth 0..1) like the camera's.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// Weight of the logarithmic split in the practical split scheme (seed 000 4.3.3, "logarithmic distribution"):
// 1 is purely logarithmic (too little resolution far away), 0 uniform (too little nearby); 0.75 keeps most of the
// logarithmic density near the eye.
inline constexpr float kCascadeLogWeight = 0.75f;

// The view-depth bounds of `cascadeCount` cascades between nearPlane and farPlane: count + 1 values, the first
// nearPlane and the last farPlane; split i = w * n (f / n)^(i / N) + (1 - w) * (n + (f - n) i / N).
// Throws std::invalid_argument for 0 < n < f violated, a count outside 1..4, or a weight outside [0, 1].
std::vector<float> cascadeSplitDistances(float nearPlane, float farPlane, std::uint32_t cascadeCount,
                                         float logWeight = kCascadeLogWeight);

struct BoundingSphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// A conservative world-space sphere around the object's mesh.
BoundingSphere objectBounds(const Mesh& mesh, const glm::mat4& objectToWorld);

// Whether the sphere touches the frustum of a Vulkan-style view-projection (clip x, y in [-w, w], z in [0, w]).
bool sphereTouchesFrustum(const glm::mat4& viewProjection, const BoundingSphere& sphere);

struct SunCascade {
  glm::mat4 viewProjection{1.0f};  // world -> clip of the cascade's orthographic shadow map
  float nearDepth = 0.0f;          // camera view-depth range of the slice the cascade covers
  float farDepth = 0.0f;
  float texelWorldSize = 0.0f;     // world size of one shadow-map texel
};

// One orthographic cascade per slice [splits[i], splits[i+1]] of the camera frustum (worldView, projection:
// the view's matrices, possibly off-axis). Each covers a bounding sphere of its slice, so its size does not
// change as the camera turns; its centre is snapped to whole texels in a light space of fixed world orientation
// (seed 003 8.5.3.5: "we simply snapped the projections per shadow map texel"), so a moving camera moves the map
// by whole texels and edges do not shimmer. Its depth range reaches back to the farthest caster towards the sun.
std::vector<SunCascade> sunCascades(const glm::mat4& worldView, const glm::mat4& projection,
                                    std::span<const float> splits, const glm::vec3& directionToSun,
                                    std::uint32_t shadowMapSize, std::span<const BoundingSphere> casters);

// Near plane of the point- and spot-light shadow views.
inline constexpr float kLocalShadowNearPlane = 0.05f;

// The view-projection of face `face` (0..5: +X, -X, +Y, -Y, +Z, -Z) of a point light: a 90-degree frustum
// looking along that axis out to the light's radius. The light pass picks the face by the dominant axis.
glm::mat4 pointLightFaceViewProjection(const PointLight& light, std::uint32_t face);

// The spot light's shadow view: a square frustum of half angle outerConeRadians along its direction.
glm::mat4 spotLightViewProjection(const SpotLight& light);

}  // namespace s3d::renderer
