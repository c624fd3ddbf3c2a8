// One eye's camera motion between two frames and the reprojection of an eye pixel with its depth, shared by the
// previous-frame fill (stereo_previous_fill.comp, previous_frame_fill.cpp) and the temporal metric (temporal.cpp).
//
// An eye camera is a view matrix and a Vulkan projection with x_ndc = P00 X / d - P20, y_ndc = P11 Y / d - P21
// for a view-space point (X, Y, -d). The pixel position u (continuous, pixel centres at +0.5) of a point at
// depth d gives its ray (X / d, Y / d, -1); the point is that ray times d, in homogeneous form (ray, 1 / d), so
// the sky (1 / d = 0) moves with the rotation only. Inverse depth is what moves linearly, and what is compared.
#ifndef S3D_STEREO_REPROJECTION_SHARED_H
#define S3D_STEREO_REPROJECTION_SHARED_H

#include "s3d/gpu/shared.h"

#ifdef __cplusplus
#define S3D_PRECISE_REPROJECTION
namespace s3d::gpu {
using glm::abs;
using glm::floor;
using glm::ivec2;
}  // namespace s3d::gpu
#else
// The GPU must not fuse the multiply-adds C++ rounds separately: a position one ulp apart can pick another texel.
#define S3D_PRECISE_REPROJECTION precise
#endif

S3D_GPU_BEGIN

// Two texels show the same surface when their inverse depths differ by at most this share of the larger: the
// neighbours of a slanted floor at 20 m differ by about 2 % per row, an occluder and its background by far more.
#define S3D_REPROJECTION_SAME_SURFACE 0.05f
// Bilinear taps lighter than this are skipped: a position a rounding error off a texel centre must not let the
// neighbour (possibly another surface) decide whether the surface was seen.
#define S3D_REPROJECTION_MIN_WEIGHT (1.0f / 256.0f)

// The motion of one eye from the current frame to the previous one; scalars and float arrays only, so the
// std430 and C++ layouts agree.
struct EyeMotion {
  float current[4];      // P00, P11, P20, P21 of the current frame's eye projection
  float previous[4];     // the same of the previous frame's
  float rotation[9];     // previous view from current view, column-major (element (r, c) at [3 c + r])
  float translation[3];  // previous view from current view
};

// The point eye pixel position `pixel` shows at inverse depth `inverseDepth` in the current frame, in the previous
// frame: (pixel x, pixel y, inverse depth); the inverse depth is negative when the point lies behind that camera.
S3D_INLINE vec3 reprojectToPrevious(EyeMotion m, vec2 pixel, float inverseDepth, int width, int height) {
  S3D_PRECISE_REPROJECTION float tx = ((2.0f * pixel.x / float(width) - 1.0f) + m.current[2]) / m.current[0];
  S3D_PRECISE_REPROJECTION float ty = ((2.0f * pixel.y / float(height) - 1.0f) + m.current[3]) / m.current[1];
  S3D_PRECISE_REPROJECTION float x =
      m.rotation[0] * tx + m.rotation[3] * ty - m.rotation[6] + m.translation[0] * inverseDepth;
  S3D_PRECISE_REPROJECTION float y =
      m.rotation[1] * tx + m.rotation[4] * ty - m.rotation[7] + m.translation[1] * inverseDepth;
  S3D_PRECISE_REPROJECTION float z =
      m.rotation[2] * tx + m.rotation[5] * ty - m.rotation[8] + m.translation[2] * inverseDepth;
  S3D_PRECISE_REPROJECTION float depth = -z;  // the previous depth per current depth
  if (!(depth > 0.0f)) return vec3(0.0f, 0.0f, -1.0f);
  S3D_PRECISE_REPROJECTION float u = (m.previous[0] * (x / depth) - m.previous[2] + 1.0f) * 0.5f * float(width);
  S3D_PRECISE_REPROJECTION float v = (m.previous[1] * (y / depth) - m.previous[3] + 1.0f) * 0.5f * float(height);
  return vec3(u, v, inverseDepth / depth);
}

// The inverse: a previous-frame pixel position and inverse depth in the current frame.
S3D_INLINE vec3 reprojectToCurrent(EyeMotion m, vec2 pixel, float inverseDepth, int width, int height) {
  S3D_PRECISE_REPROJECTION float tx = ((2.0f * pixel.x / float(width) - 1.0f) + m.previous[2]) / m.previous[0];
  S3D_PRECISE_REPROJECTION float ty = ((2.0f * pixel.y / float(height) - 1.0f) + m.previous[3]) / m.previous[1];
  S3D_PRECISE_REPROJECTION float a = tx - m.translation[0] * inverseDepth;
  S3D_PRECISE_REPROJECTION float b = ty - m.translation[1] * inverseDepth;
  S3D_PRECISE_REPROJECTION float c = -1.0f - m.translation[2] * inverseDepth;
  S3D_PRECISE_REPROJECTION float x = m.rotation[0] * a + m.rotation[1] * b + m.rotation[2] * c;
  S3D_PRECISE_REPROJECTION float y = m.rotation[3] * a + m.rotation[4] * b + m.rotation[5] * c;
  S3D_PRECISE_REPROJECTION float z = m.rotation[6] * a + m.rotation[7] * b + m.rotation[8] * c;
  S3D_PRECISE_REPROJECTION float depth = -z;
  if (!(depth > 0.0f)) return vec3(0.0f, 0.0f, -1.0f);
  S3D_PRECISE_REPROJECTION float u = (m.current[0] * (x / depth) - m.current[2] + 1.0f) * 0.5f * float(width);
  S3D_PRECISE_REPROJECTION float v = (m.current[1] * (y / depth) - m.current[3] + 1.0f) * 0.5f * float(height);
  return vec3(u, v, inverseDepth / depth);
}

// Inverse depth of a linear depth image's value: 0 for the sky (+inf), negative for unknown depth (NaN, <= 0).
S3D_INLINE float inverseDepthOf(float linearDepth) { return linearDepth > 0.0f ? 1.0f / linearDepth : -1.0f; }

// Whether a texel of inverse depth `texel` shows the surface expected at inverse depth `expected` (both known).
S3D_INLINE bool sameSurface(float expected, float texel) {
  return expected >= 0.0f && texel >= 0.0f && abs(expected - texel) <= S3D_REPROJECTION_SAME_SURFACE * max(expected, texel);
}

// The bilinear footprint of a continuous pixel position (texel centres at +0.5): its top-left texel, and the
// weights of the four texels (top-left, top-right, bottom-left, bottom-right).
S3D_INLINE ivec2 bilinearTopLeft(vec2 position) {
  return ivec2(int(floor(position.x - 0.5f)), int(floor(position.y - 0.5f)));
}
S3D_INLINE vec4 bilinearWeights(vec2 position) {
  S3D_PRECISE_REPROJECTION float fx = position.x - 0.5f;
  S3D_PRECISE_REPROJECTION float fy = position.y - 0.5f;
  S3D_PRECISE_REPROJECTION float ax = fx - floor(fx);
  S3D_PRECISE_REPROJECTION float ay = fy - floor(fy);
  return vec4((1.0f - ax) * (1.0f - ay), ax * (1.0f - ay), (1.0f - ax) * ay, ax * ay);
}

S3D_GPU_END

#endif  // S3D_STEREO_REPROJECTION_SHARED_H
