#pragma once
// The matrices of one rendered view (the center view, a reference eye) and the projections they are made of;
// defined in view_matrices.cpp. The renderer's passes plan and draw from them.
#include <optional>

#include <glm/glm.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// Seed 4.6.2: the first-person layer's depth is offset and scaled (pushed into the screen) in the linear
// depth handed to the stereo pass: pushed = offset + scale * depth. Rendering and lighting are unchanged.
// {0, 1} leaves it where it is.
struct FirstPersonDepthPush {
  float offset = 0.0f;  // world units
  float scale = 1.0f;
};

// The camera a frame's shadow maps are planned for: the sun's cascades cover the slices of its frustum (seed 000
// 4.3.3) and the point and spot lights it can see get their maps.
struct ShadowFit {
  glm::mat4 worldView{1.0f};
  glm::mat4 worldProjection{1.0f};
  bool operator==(const ShadowFit&) const = default;
};

// Matrices of one rendered view. Vulkan clip space (y down, depth 0..1).
struct ViewMatrices {
  glm::mat4 worldView{1.0f};        // world -> view of the world layer
  glm::mat4 worldProjection{1.0f};  // may be off-axis (two-pass reference eyes)
  glm::mat4 firstPersonView{1.0f};  // camera space -> first-person view (identity for the center view)
  glm::mat4 firstPersonProjection{1.0f};
  glm::mat4 worldFromCamera{1.0f};  // inverse of the center camera's view: places first-person objects for lighting
  FirstPersonDepthPush firstPersonDepthPush;  // applied to linearDepth() only
  // Where the shadow maps are planned from; empty: this view's own world camera. A stereo frame's eye views name
  // their center view's camera, so every view of the frame has the same shadow maps (the eyes see what the center
  // sees inside the compared columns, whose cascades cover it) and an eye render can reuse the center frame's
  // (DeferredRenderer::render with a shadow source).
  std::optional<ShadowFit> shadowFit;
};

// The camera `view`'s shadow maps are planned from: its shadowFit, else its own world camera.
ShadowFit shadowFitOf(const ViewMatrices& view);

// Perspective projection with Vulkan's downward y and zero-to-one depth.
glm::mat4 vulkanPerspective(float verticalFovRadians, float aspect, float nearPlane, float farPlane);
// The scene camera's center view at the given aspect ratio (width / height).
// Nearest and farthest camera-space depth of the first-person layer's vertices (nullopt: no such layer).
std::optional<glm::vec2> firstPersonDepthRange(const Scene& scene);

// Throws std::invalid_argument for a negative/non-finite offset or a non-positive/non-finite scale.
ViewMatrices centerViewMatrices(const Scene& scene, float aspect, FirstPersonDepthPush push = {});

// Reversed-Z (near/far swapped in the projection): see reversedDepthProjection.
glm::mat4 reversedDepthProjection(const glm::mat4& projection, float nearPlane, float farPlane);

}  // namespace s3d::renderer
