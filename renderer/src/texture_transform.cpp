// KHR_texture_transform's definition (scene.h): uv' = T * R * S * uv.
#include <cmath>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

glm::mat3 TextureTransform::matrix() const {
  // Column-major: translation in the third column. The rotation turns uv counter-clockwise in glTF's uv space,
  // whose v axis points down: columns (cos, -sin) and (sin, cos). That is what the implementations and
  // Khronos's TextureTransformTest sample model agree on; the extension text's GLSL listing has the transpose
  // (counter-clockwise with v up), which that model shows as the wrong direction.
  const glm::mat3 translation(1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, offset.x, offset.y, 1.0f);
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 rotate(c, -s, 0.0f, s, c, 0.0f, 0.0f, 0.0f, 1.0f);
  const glm::mat3 scaling(scale.x, 0.0f, 0.0f, 0.0f, scale.y, 0.0f, 0.0f, 0.0f, 1.0f);
  return translation * rotate * scaling;
}

glm::vec2 TextureTransform::apply(glm::vec2 uv) const { return glm::vec2(matrix() * glm::vec3(uv, 1.0f)); }

}  // namespace s3d::renderer
