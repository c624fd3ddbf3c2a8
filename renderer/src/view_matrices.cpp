// The cameras' view and projection matrices a renderer draws with (declared in view_matrices.h): Vulkan's
// clip conventions, reversed depth, the first-person layer's depth span, the center view.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/view_matrices.h"

namespace s3d::renderer {

glm::mat4 vulkanPerspective(float verticalFovRadians, float aspect, float nearPlane, float farPlane) {
  glm::mat4 projection = glm::perspectiveRH_ZO(verticalFovRadians, aspect, nearPlane, farPlane);
  projection[1][1] = -projection[1][1];  // Vulkan's clip-space y points down
  return projection;
}

glm::mat4 reversedDepthProjection(const glm::mat4& projection, float nearPlane, float farPlane) {
  // A zero-to-one perspective with near and far swapped: z_ndc = n / (n - f) + n f / ((f - n) d), 1 at the near
  // plane and 0 at the far plane. Only the depth row changes, so off-axis terms (P20, P21) stay; the two terms
  // are computed in double from n and f (not as w - z from the matrix, which would cancel to ~1e-4 relative).
  glm::mat4 reversed = projection;
  const double n = nearPlane, f = farPlane;
  reversed[2][2] = float(n / (f - n));
  reversed[3][2] = float(n * f / (f - n));
  return reversed;
}

std::optional<glm::vec2> firstPersonDepthRange(const Scene& scene) {
  std::optional<glm::vec2> range;
  for (const Object& object : scene.objects) {
    if (object.layer != Layer::FirstPerson) continue;
    for (const Vertex& vertex : scene.meshes.at(object.mesh).vertices) {
      float depth = -(object.transform * glm::vec4(vertex.position, 1.0f)).z;
      range = range ? glm::vec2(std::min(range->x, depth), std::max(range->y, depth)) : glm::vec2(depth);
    }
  }
  return range;
}

ViewMatrices centerViewMatrices(const Scene& scene, float aspect, FirstPersonDepthPush push) {
  if (!std::isfinite(push.offset) || push.offset < 0.0f)
    throw std::invalid_argument("weapon depth offset must be finite and >= 0 (got " + std::to_string(push.offset) + ")");
  if (!std::isfinite(push.scale) || push.scale <= 0.0f)
    throw std::invalid_argument("weapon depth scale must be finite and > 0 (got " + std::to_string(push.scale) + ")");
  ViewMatrices view;
  view.firstPersonDepthPush = push;
  view.worldView = cameraView(scene.camera);
  view.worldProjection =
      vulkanPerspective(scene.camera.verticalFovRadians, aspect, scene.camera.nearPlane, scene.camera.farPlane);
  view.firstPersonView = glm::mat4(1.0f);
  view.firstPersonProjection = vulkanPerspective(scene.firstPerson.verticalFovRadians, aspect,
                                                 scene.firstPerson.nearPlane, scene.firstPerson.farPlane);
  view.worldFromCamera = glm::inverse(view.worldView);
  return view;
}

ShadowFit shadowFitOf(const ViewMatrices& view) {
  return view.shadowFit ? *view.shadowFit : ShadowFit{view.worldView, view.worldProjection};
}

}  // namespace s3d::renderer
