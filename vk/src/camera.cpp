#include "s3d/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace s3d {

glm::mat4 cameraView(const Camera& camera) {
  glm::vec3 forward(-std::sin(camera.yawRadians) * std::cos(camera.pitchRadians), std::sin(camera.pitchRadians),
                    -std::cos(camera.yawRadians) * std::cos(camera.pitchRadians));
  return glm::lookAt(camera.position, camera.position + forward, glm::vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace s3d
