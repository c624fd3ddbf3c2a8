// The previous-frame fill: the forward method's disocclusions (eye pixels no center pixel lands on) take what the
// previous frame's eye showed there, reprojected with its depth and the camera's motion; shared by
// stereo_previous_fill.comp and the C++ implementation (previous_fill_reference.cpp).
//
// Per hole pixel of the current eye, from the hole's background (the farther of its nearest covered neighbours in
// the row, a guess of the depth behind the occluder): the pixel is reprojected into the previous eye at that
// depth (reprojection_shared.h); if the previous eye's texels around the landing show a surface at the depth the
// point would have there, and it lies behind the hole's occluder, their colour (bilinear over those texels; the
// weapon's texels, which move with the camera, left out) fills the pixel. Otherwise the surface the
// previous eye shows at the landing is brought back into the current frame and its depth tried next, up to
// S3D_PREVIOUS_FILL_ITERATIONS times (a fixed-point search for the previous surface that lands on the pixel).
// What finds nothing keeps the forward method's fill. Each frame writes its eye and the depth of what every eye
// pixel shows (a covered pixel: its winning key's depth; a hole: the surface found or the background guess) as
// the next frame's history, so a surface seen once keeps filling the holes it reappears in while the camera moves.
#ifndef S3D_STEREO_PREVIOUS_FILL_SHARED_H
#define S3D_STEREO_PREVIOUS_FILL_SHARED_H

#include "s3d/stereo/forward_shared.h"
#include "s3d/stereo/reprojection_shared.h"

#ifdef __cplusplus
namespace s3d::gpu {
S3D_INLINE float uintBitsToFloat(uint bits) { return std::bit_cast<float>(bits); }
}  // namespace s3d::gpu
#endif

S3D_GPU_BEGIN

#define S3D_PREVIOUS_FILL_GROUP_SIZE 8
#define S3D_PREVIOUS_FILL_ITERATIONS 3  // depth hypotheses per hole pixel: the background guess and two refinements

// Push constants of one eye's dispatch; scalars, float arrays and a struct of them, so std430 and C++ agree.
struct PreviousFillConstants {
  EyeMotion motion;  // this eye from the current frame to the previous one
  int width;
  int height;
  int cropBegin;     // columns [cropBegin, cropEnd) are the eye; the others are black and hold no history
  int cropEnd;
  int edgeSearchPx;  // how far a hole pixel looks for its covered neighbours (the forward method's fillSearchPx)
  int hasHistory;    // 0: the first frame (or a new size): nothing to reproject, only the history is written
  int padding0;
  int padding1;
};

// The linear depth a forward key holds (its upper float bits; 11 mantissa bits, within 0.05 % of the depth).
S3D_INLINE float forwardKeyLinearDepth(uint key) { return uintBitsToFloat(forwardKeyDepth(key) << S3D_FORWARD_OFFSET_BITS); }

// From a hole pixel's nearest covered keys on its left and right in the row (S3D_FORWARD_EMPTY: none within the
// edge search): (background, occluder) depths. The background, the farther of the two, guesses the depth behind the
// occluder (0: nothing covered nearby); the occluder is the nearer one when the two are different surfaces (else 0).
S3D_INLINE vec2 previousFillEdges(uint left, uint right) {
  bool hasLeft = left != S3D_FORWARD_EMPTY, hasRight = right != S3D_FORWARD_EMPTY;
  if (!hasLeft && !hasRight) return vec2(0.0f, 0.0f);
  if (!hasLeft || !hasRight) return vec2(forwardKeyLinearDepth(hasLeft ? left : right), 0.0f);
  float a = forwardKeyLinearDepth(left), b = forwardKeyLinearDepth(right);
  float farther = a > b ? a : b, nearer = a > b ? b : a;
  return vec2(farther, sameSurface(inverseDepthOf(farther), inverseDepthOf(nearer)) ? 0.0f : nearer);
}

// A surface found for a hole must lie behind the hole's occluder (the nearer of its two covered neighbours, when
// they are different surfaces; occluderDepth 0: no such pair): the occluder, or the weapon, which moves with the
// camera and not with the world, must not fill its own disocclusion.
S3D_INLINE bool behindOccluder(float inverseDepth, float occluderDepth) {
  return !(occluderDepth > 0.0f) || inverseDepth * occluderDepth < 1.0f - S3D_REPROJECTION_SAME_SURFACE;
}

// The previous eye's first-person pixels (the weapon: the renderer's alpha 0, carried into the eyes) move with the
// camera, not with the world, so camera motion cannot reproject them: they never fill a hole.
#define S3D_PREVIOUS_FILL_WORLD_ALPHA 0.5f

S3D_INLINE bool previousFillInsideEye(PreviousFillConstants c, ivec2 texel) {
  return texel.y >= 0 && texel.y < c.height && texel.x >= c.cropBegin && texel.x < c.cropEnd;
}

S3D_GPU_END

#endif  // S3D_STEREO_PREVIOUS_FILL_SHARED_H
