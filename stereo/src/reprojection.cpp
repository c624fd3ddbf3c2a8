#include "s3d/stereo/reprojection.h"

namespace s3d::stereo {
namespace {

void projectionTerms(const glm::mat4& projection, float* terms) {
  terms[0] = projection[0][0];
  terms[1] = projection[1][1];
  terms[2] = projection[2][0];
  terms[3] = projection[2][1];
}

}  // namespace

gpu::EyeMotion eyeMotion(const glm::mat4& currentView, const glm::mat4& currentProjection, const glm::mat4& previousView,
                         const glm::mat4& previousProjection) {
  gpu::EyeMotion motion{};
  projectionTerms(currentProjection, motion.current);
  projectionTerms(previousProjection, motion.previous);
  // previous view <- world <- current view; both views are rigid, so the inverse is exact in double.
  const glm::dmat4 previousFromCurrent = glm::dmat4(previousView) * glm::inverse(glm::dmat4(currentView));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) motion.rotation[3 * c + r] = float(previousFromCurrent[c][r]);
  for (int r = 0; r < 3; ++r) motion.translation[r] = float(previousFromCurrent[3][r]);
  return motion;
}

gpu::EyeMotion staticEyeMotion(const glm::mat4& projection) {
  return eyeMotion(glm::mat4(1.0f), projection, glm::mat4(1.0f), projection);
}

}  // namespace s3d::stereo
