// The previous-frame fill: the forward method's disocclusions (eye pixels no center pixel lands on) take what the
// previous frame's eye showed there, reprojected with its depth and the camera's motion; shared by
// stereo_previous_fill.comp and the C++ implementation (previous_fill_reference.cpp).
//
// Per hole pixel of the current eye, from the hole's background (the farther of its nearest covered neighbours in
// the row, a guess of the depth behind the occluder): the pixel is reprojected into the previous eye at that
// depth (reprojection_shared.h); if the previous eye's texels around the landing show a surface at the depth the
// point would have there, their colour (bilinear over those texels) fills the pixel. Otherwise the surface the
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

S3D_INLINE bool previousFillInsideEye(PreviousFillConstants c, ivec2 texel) {
  return texel.y >= 0 && texel.y < c.height && texel.x >= c.cropBegin && texel.x < c.cropEnd;
}

S3D_GPU_END

#endif  // S3D_STEREO_PREVIOUS_FILL_SHARED_H
