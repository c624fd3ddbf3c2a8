#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/view_matrices.h"
#include "s3d/renderer/shadows.h"

namespace s3d::renderer {
namespace {

// Vulkan's clip-space y points down: flips an OpenGL-style projection like vulkanPerspective does.
glm::mat4 flipY(const glm::mat4& projection) {
  glm::mat4 flip(1.0f);
  flip[1][1] = -1.0f;
  return flip * projection;
}

// A light space of fixed world orientation looking along the sunlight (seed 000 4.3.3: "the orientation for each
// shadow frustum is fixed in world space"), so texel snapping in it is independent of the camera.
glm::mat4 sunLightView(const glm::vec3& directionToSun) {
  const glm::vec3 toSun = glm::normalize(directionToSun);
  const glm::vec3 up = std::abs(toSun.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::lookAt(glm::vec3(0.0f), -toSun, up);
}

// Rounds a radius up to one of 16 steps per octave, so small changes of the slice (a turning off-axis eye,
// float noise) leave the cascade's scale, and with it its texel grid, unchanged.
float quantizeRadius(float radius) {
  const float step = std::exp2(std::floor(std::log2(radius)) - 4.0f);
  return std::ceil(radius / step) * step;
}

}  // namespace

std::vector<float> cascadeSplitDistances(float nearPlane, float farPlane, std::uint32_t cascadeCount, float logWeight) {
  if (!(nearPlane > 0.0f && farPlane > nearPlane && std::isfinite(farPlane)))
    throw std::invalid_argument("cascade splits need 0 < near < far (got near " + std::to_string(nearPlane) +
                                ", far " + std::to_string(farPlane) + ")");
  if (cascadeCount < 1 || cascadeCount > 4)
    throw std::invalid_argument("sun cascade count must be 1..4 (got " + std::to_string(cascadeCount) + ")");
  if (!(logWeight >= 0.0f && logWeight <= 1.0f))
    throw std::invalid_argument("cascade log weight must be in [0, 1] (got " + std::to_string(logWeight) + ")");
  std::vector<float> splits(cascadeCount + 1);
  for (std::uint32_t i = 0; i <= cascadeCount; ++i) {
    const double t = double(i) / double(cascadeCount);
    const double logarithmic = double(nearPlane) * std::pow(double(farPlane) / double(nearPlane), t);
    const double uniform = double(nearPlane) + (double(farPlane) - double(nearPlane)) * t;
    splits[i] = float(double(logWeight) * logarithmic + (1.0 - double(logWeight)) * uniform);
  }
  splits.front() = nearPlane;
  splits.back() = farPlane;
  return splits;
}

BoundingSphere objectBounds(const Mesh& mesh, const glm::mat4& objectToWorld) {
  if (mesh.vertices.empty()) return {glm::vec3(objectToWorld[3]), 0.0f};
  glm::vec3 lo(mesh.vertices.front().position), hi(lo);
  for (const Vertex& vertex : mesh.vertices) {
    lo = glm::min(lo, vertex.position);
    hi = glm::max(hi, vertex.position);
  }
  const float scale = std::max({glm::length(glm::vec3(objectToWorld[0])), glm::length(glm::vec3(objectToWorld[1])),
                                glm::length(glm::vec3(objectToWorld[2]))});
  return {glm::vec3(objectToWorld * glm::vec4(0.5f * (lo + hi), 1.0f)), 0.5f * glm::length(hi - lo) * scale};
}

bool sphereTouchesFrustum(const glm::mat4& viewProjection, const BoundingSphere& sphere) {
  // Gribb-Hartmann planes of the zero-to-one clip volume: w +- x >= 0, w +- y >= 0, z >= 0, w - z >= 0.
  const glm::mat4 m = glm::transpose(viewProjection);  // rows of the matrix as columns
  const glm::vec4 planes[] = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[2], m[3] - m[2]};
  for (const glm::vec4& plane : planes) {
    const float length = glm::length(glm::vec3(plane));
    if (length <= 0.0f) continue;
    if ((glm::dot(glm::vec3(plane), sphere.center) + plane.w) / length < -sphere.radius) return false;
  }
  return true;
}

std::vector<SunCascade> sunCascades(const glm::mat4& worldView, const glm::mat4& projection,
                                    std::span<const float> splits, const glm::vec3& directionToSun,
                                    std::uint32_t shadowMapSize, std::span<const BoundingSphere> casters) {
  if (splits.size() < 2) throw std::invalid_argument("sunCascades: need at least two split distances");
  if (shadowMapSize == 0) throw std::invalid_argument("sunCascades: zero shadow-map size");
  const glm::mat4 worldFromView = glm::inverse(worldView);
  const glm::mat4 lightView = sunLightView(directionToSun);
  // View-space rays through the screen corners at depth 1, off-axis aware (as the light pass reconstructs them).
  glm::vec3 corners[4];
  glm::vec2 axis(0.0f);
  for (int corner = 0; corner < 4; ++corner) {
    const glm::vec2 ndc((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f);
    corners[corner] = glm::vec3((ndc.x + projection[2][0]) / projection[0][0],
                                (ndc.y + projection[2][1]) / projection[1][1], -1.0f);
    axis += 0.25f * glm::vec2(corners[corner]);
  }
  float spread = 0.0f;  // squared tangent of the widest corner ray around the axis
  for (const glm::vec3& corner : corners) spread = std::max(spread, glm::dot(glm::vec2(corner) - axis, glm::vec2(corner) - axis));

  std::vector<SunCascade> cascades;
  for (std::size_t i = 0; i + 1 < splits.size(); ++i) {
    const float nearDepth = splits[i], farDepth = splits[i + 1];
    // The sphere around the slice with its centre on the axis: equidistant to the near and far corners, or at the
    // far plane when the slice is wider than deep.
    const float centreDepth = std::min(farDepth, 0.5f * (nearDepth + farDepth) * (1.0f + spread));
    const glm::vec3 viewCentre = glm::vec3(axis, -1.0f) * centreDepth;
    float radius = 0.0f;
    for (const glm::vec3& corner : corners)
      radius = std::max({radius, glm::length(corner * nearDepth - viewCentre), glm::length(corner * farDepth - viewCentre)});
    // Slack of two texels so the snapped map (moved by under a texel per axis) still covers the whole slice.
    radius = quantizeRadius(radius * (1.0f + 4.0f / float(shadowMapSize)));

    glm::vec3 lightCentre = glm::vec3(lightView * worldFromView * glm::vec4(viewCentre, 1.0f));
    const float texel = 2.0f * radius / float(shadowMapSize);
    lightCentre.x = std::floor(lightCentre.x / texel) * texel;
    lightCentre.y = std::floor(lightCentre.y / texel) * texel;

    // Light-space depth runs along -z; casters towards the sun (smaller depth) must land in the map too.
    float zNear = -lightCentre.z - radius;
    const float zFar = -lightCentre.z + radius;
    for (const BoundingSphere& caster : casters) {
      const glm::vec3 c = glm::vec3(lightView * glm::vec4(caster.center, 1.0f));
      if (std::abs(c.x - lightCentre.x) > radius + caster.radius || std::abs(c.y - lightCentre.y) > radius + caster.radius)
        continue;
      zNear = std::min(zNear, -c.z - caster.radius);
    }
    const glm::mat4 ortho = glm::orthoRH_ZO(lightCentre.x - radius, lightCentre.x + radius, lightCentre.y - radius,
                                            lightCentre.y + radius, zNear, zFar);
    cascades.push_back({flipY(ortho) * lightView, nearDepth, farDepth, texel});
  }
  return cascades;
}

glm::mat4 pointLightFaceViewProjection(const PointLight& light, std::uint32_t face) {
  static const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  if (face >= 6) throw std::invalid_argument("point light face must be 0..5 (got " + std::to_string(face) + ")");
  const glm::mat4 view = glm::lookAt(light.position, light.position + axes[face], ups[face]);
  return vulkanPerspective(glm::half_pi<float>(), 1.0f, kLocalShadowNearPlane, light.radius) * view;
}

glm::mat4 spotLightViewProjection(const SpotLight& light) {
  const glm::vec3 direction = glm::normalize(light.direction);
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::mat4 view = glm::lookAt(light.position, light.position + direction, up);
  return vulkanPerspective(2.0f * light.outerConeRadians, 1.0f, kLocalShadowNearPlane, light.radius) * view;
}

}  // namespace s3d::renderer
