#include "s3d/tune/tune_state.h"

#include <algorithm>
#include <cmath>

namespace s3d::tune {

void moveCamera(renderer::Camera& camera, const FrameInput& input, float seconds) {
  camera.yawRadians -= input.lookPx.x * kLookRadiansPerPixel;
  camera.pitchRadians = std::clamp(camera.pitchRadians - input.lookPx.y * kLookRadiansPerPixel, -kMaxPitchRadians,
                                   kMaxPitchRadians);
  // renderer::cameraView looks along (-sin yaw, ., -cos yaw); right is that turned clockwise seen from above.
  const glm::vec3 forward(-std::sin(camera.yawRadians), 0.0f, -std::cos(camera.yawRadians));
  const glm::vec3 right(std::cos(camera.yawRadians), 0.0f, -std::sin(camera.yawRadians));
  glm::vec3 step(0.0f);
  step += forward * float(int(input.forward) - int(input.back));
  step += right * float(int(input.right) - int(input.left));
  step.y += float(int(input.up) - int(input.down));
  if (glm::dot(step, step) > 0.0f) camera.position += glm::normalize(step) * (kWalkSpeed * seconds);
}

}  // namespace s3d::tune
