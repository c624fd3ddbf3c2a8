// The forward (scatter) method's parameters and per-pixel math, shared by the stereo_forward_*.comp shaders and
// the C++ implementation (forward_reference.cpp).
//
// Every center pixel s with known depth moves to x(s) = s + 0.5 - direction * P(d(s)) in an eye (direction +1:
// left eye, -1: right eye; P = parallaxFromDepth * width, bounded to +-maxParallaxPx), the inverse of the gather
// methods' mapping. Neighbours s, s + 1 whose positions stay in order and at most S3D_FORWARD_MAX_GAP_PX apart
// are one surface: the eye pixels whose centers fall in [x(s), x(s + 1)) (left eye; (x(s), x(s + 1)] in the
// right eye, forwardFirstColumn) show the center row filtered at s + the fraction of the way (sub-pixel
// placement, exact on flat and slanted surfaces). An open end (a depth edge) covers half a pixel. Each covered eye pixel keeps the nearest surface: a 32-bit key of the depth's
// upper float bits above the source's column offset, reduced with an atomic minimum (z-buffer). Eye pixels
// no surface covers are disocclusions. When the center row between the sources of the hole's two edges holds
// pixels behind both edges (a gap between occluders, whose background the eye sees elsewhere), the hole takes
// the mean of up to S3D_FORWARD_FILL_TAPS of the farthest of them; otherwise the mean of the first ones of the
// surface on the far (background) side of the hole, from its edge on. With maxSeparation 0 every pixel lands on
// itself: the center view bit for bit.
#ifndef S3D_STEREO_FORWARD_SHARED_H
#define S3D_STEREO_FORWARD_SHARED_H

#include "s3d/stereo/stereo_shared.h"

#ifdef __cplusplus
#include <bit>
#define S3D_PRECISE
namespace s3d::gpu {
using glm::ceil;
S3D_INLINE uint floatBitsToUint(float value) { return std::bit_cast<uint>(value); }
}  // namespace s3d::gpu
#else
// As in the iterative pass: the GPU must not fuse the position's multiply-add, or a pixel could change hands.
#define S3D_PRECISE precise
#endif

S3D_GPU_BEGIN

#define S3D_FORWARD_GROUP_SIZE 8  // the key-image kernel's 8x8 workgroups
// The row kernel: one workgroup of this many invocations per image row (Vulkan guarantees 128), holding the
// row's depth and both eyes' z-buffers in shared memory (4 B each per column).
#define S3D_FORWARD_ROW_GROUP_SIZE 128
#define S3D_FORWARD_ROW_SHARED_BYTES_PER_COLUMN 12
#define S3D_FORWARD_ROW_CAPACITY_STEP 256  // the shared arrays hold the width rounded up to a multiple of this
#define S3D_FORWARD_MAX_GAP_PX 2.0f  // neighbours further apart in the eye are a depth edge, not one slanted surface
#define S3D_FORWARD_OFFSET_BITS 12u  // the key's low bits: source column - eye column + S3D_FORWARD_OFFSET_BIAS
#define S3D_FORWARD_OFFSET_BIAS 2048
#define S3D_FORWARD_EMPTY 0xffffffffu  // no surface landed here (yet)
#define S3D_FORWARD_FILL_SKIP 0  // background pixels skipped at a hole's edge (skipping 1 or 2 measured worse: RESULTS.md)
#define S3D_FORWARD_FILL_TAPS 3  // background pixels averaged (1: the plain warp's rule; 3 best SSIM, RESULTS.md)
#define S3D_FORWARD_SCAN_CHUNK 4  // the GPU hole fill reads this many keys or depths of its scans at once

// Push constants of the forward pass; scalars only, so the std430 and C++ layouts agree.
struct ForwardConstants {
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units, same as the linear depth
  float maxParallaxPx;         // maxSeparation * width: the bound of every displacement
  int cropBegin;               // columns [0, cropBegin) are written black
  int cropEnd;                 // columns [cropEnd, width) are written black
  int width;
  int height;
  int fillSearchPx;  // how far a hole pixel looks for its edges: the widest hole two parallaxes can open
};

// Depth the forward pass cannot place (NaN, zero, negative): such a pixel is never splatted.
S3D_INLINE bool forwardKnownDepth(float linearDepth) { return linearDepth > 0.0f; }

// Parallax in pixels, bounded to [-maxParallaxPx, maxParallaxPx] (comparisons, not min/max: NaN-safe).
S3D_INLINE float forwardParallaxPx(ForwardConstants c, float linearDepth) {
  float p = parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, linearDepth) * float(c.width);
  if (p >= -c.maxParallaxPx && p <= c.maxParallaxPx) return p;
  return p > c.maxParallaxPx ? c.maxParallaxPx : -c.maxParallaxPx;
}

// Where center pixel `source` (its center) lands in the eye.
S3D_INLINE float forwardPosition(ForwardConstants c, int source, float direction, float linearDepth) {
  S3D_PRECISE float shift = direction * forwardParallaxPx(c, linearDepth);
  S3D_PRECISE float position = (float(source) + 0.5f) - shift;
  return position;
}

// Whether neighbours at eye positions a (left) and b (right), both known, are one surface.
S3D_INLINE bool forwardConnected(float a, float b) {
  float gap = b - a;
  return gap > 0.0f && gap <= S3D_FORWARD_MAX_GAP_PX;
}

// First eye column whose center is right of `position`, or at it in the left eye (direction > 0). A column
// whose center falls exactly on a footprint boundary goes to the pixel on the side where disocclusions open, so
// a surface's edge pixel shows there instead of a fill: in the right eye nearer surfaces move left and open
// holes at their right ends, so the column goes to the pixel left of the boundary; the left eye mirrors it.
S3D_INLINE int forwardFirstColumn(float position, float direction) {
  return direction > 0.0f ? int(ceil(position - 0.5f)) : int(floor(position - 0.5f)) + 1;
}

// The z-buffer key: nearer depth first (positive float bits order like the values), then the source offset.
S3D_INLINE uint forwardKey(float linearDepth, int source, int column) {
  uint depthBits = floatBitsToUint(linearDepth) >> S3D_FORWARD_OFFSET_BITS;
  return (depthBits << S3D_FORWARD_OFFSET_BITS) | uint(source - column + S3D_FORWARD_OFFSET_BIAS);
}

S3D_INLINE int forwardKeySource(uint key, int column) {
  return column + int(key & ((1u << S3D_FORWARD_OFFSET_BITS) - 1u)) - S3D_FORWARD_OFFSET_BIAS;
}

// The depth part of a key: larger is farther.
S3D_INLINE uint forwardKeyDepth(uint key) { return key >> S3D_FORWARD_OFFSET_BITS; }

// The center-row position the eye pixel `column` shows, given the winning source s, its position xs, and the
// position of s + 1 when the two are one surface (connected); an open end shows s itself.
S3D_INLINE float forwardSourcePosition(int column, int source, float xs, bool connected, float xNext) {
  float center = float(column) + 0.5f;
  if (!connected || center < xs) return float(source);
  float fraction = (center - xs) / (xNext - xs);
  return float(source) + (fraction < 1.0f ? fraction : 1.0f);
}

S3D_GPU_END

#endif  // S3D_STEREO_FORWARD_SHARED_H
