#pragma once
// The scene camera, shared by the renderer (it draws from it) and comfort (it casts its rays from it).
// Conventions: right-handed, Y up, the camera looks down -Z in view space, metres.
#include <glm/glm.hpp>

namespace s3d {

struct Camera {
  glm::vec3 position{0.0f, 1.7f, 0.0f};
  float yawRadians = 0.0f;    // rotation about +Y; 0 looks down -Z
  float pitchRadians = 0.0f;  // positive looks up
  float verticalFovRadians = 1.0f;
  float nearPlane = 0.1f;
  float farPlane = 1000.0f;
};

glm::mat4 cameraView(const Camera& camera);  // world -> view

}  // namespace s3d
