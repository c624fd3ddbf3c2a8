#pragma once
// Camera motion between two frames of one eye (reprojection_shared.h), from the eye's view and projection.
#include <glm/glm.hpp>

#include "s3d/stereo/reprojection_shared.h"

namespace s3d::stereo {

// The motion from the current eye camera to the previous one (computed in double precision). The projections
// must be perspective (w = view depth); only P00, P11, P20 and P21 are used.
gpu::EyeMotion eyeMotion(const glm::mat4& currentView, const glm::mat4& currentProjection, const glm::mat4& previousView,
                         const glm::mat4& previousProjection);

// No motion: the same camera in both frames.
gpu::EyeMotion staticEyeMotion(const glm::mat4& projection);

}  // namespace s3d::stereo
