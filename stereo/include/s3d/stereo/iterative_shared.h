// The iterative gather method's parameters and per-pixel math, shared by stereo_iterative.comp and the C++
// implementation (iterative_reference.cpp). Only the math lives here; each language fetches depth itself.
//
// The left eye shows at target pixel t the center content from the source s with s - P(d(s)) = t, where
// P = parallaxFromDepth * width (pixels) and d is the linear depth at s's nearest texel. It is solved by the
// fixed-point iteration s_{k+1} = t + P(d(s_k)) from two starts (the sky's displacement t + M and the
// nearest surface found by a few taps over the separation range); the right eye mirrors it (direction -1).
// Every tap and iterate is a candidate: among those that map onto t (within S3D_ITERATIVE_TOLERANCE_PX) the
// nearest surface wins (occlusion; the taps catch a surface the iterations jump over). When none does
// (disocclusion), the iterate that read the farthest depth is used, so the hole is filled from the
// background side and the foreground is not stretched.
#ifndef S3D_STEREO_ITERATIVE_SHARED_H
#define S3D_STEREO_ITERATIVE_SHARED_H

#include "s3d/stereo/stereo_shared.h"

#ifdef __cplusplus
#define S3D_PRECISE
namespace s3d::gpu {
using glm::abs;
using glm::clamp;
using glm::floor;
}  // namespace s3d::gpu
#else
// The GPU must not fuse t + direction * P into one multiply-add: C++ does not, and a one-ulp difference
// could move a position across a texel boundary and fetch another depth.
#define S3D_PRECISE precise
#endif

S3D_GPU_BEGIN

#define S3D_ITERATIVE_START_TAPS 8       // depth taps that look for the nearest surface of the near start
#define S3D_ITERATIVE_MAX_ITERATIONS 16  // fixed-point iterations per start, at most
#define S3D_ITERATIVE_GROUP_SIZE 8
// Residual (pixels) below which a candidate counts as a solution: half a texel covers a flat surface exactly,
// the slack admits slanted ones whose texels spread apart in the eye (0.75 measured best on the courtyard).
#define S3D_ITERATIVE_TOLERANCE_PX 0.75f

// Push constants of the iterative pass; scalars only, so the std430 and C++ layouts agree.
struct IterativeConstants {
  int startTapOffsetPx[S3D_ITERATIVE_START_TAPS];  // whole pixels in [0, maxParallaxPx], 0 (the target) first
  int startTapCount;
  int iterations;              // fixed-point iterations per start: a constant cost per pixel
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units, same as the linear depth
  float maxParallaxPx;         // maxSeparation * width: the sky's displacement and the bound of every step
  int cropBegin;               // columns [0, cropBegin) are written black
  int cropEnd;                 // columns [cropEnd, width) are written black
  int width;
  int height;
  int markFilled;  // 0: the center's alpha (the weapon mask) is carried; != 0: alpha is the fill flag (0 filled, 1 not)
  int padding0;
};

// Parallax in pixels, bounded to [-maxParallaxPx, maxParallaxPx]: the sky gives exactly maxParallaxPx, and a
// depth at or below zero or NaN (whose parallax is infinite or NaN) cannot throw the solver off the row.
// Written with comparisons, not min/max, because GLSL leaves min/max of a NaN undefined.
S3D_INLINE float iterativeParallaxPx(IterativeConstants c, float linearDepth) {
  float p = parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, linearDepth) * float(c.width);
  if (p >= -c.maxParallaxPx && p <= c.maxParallaxPx) return p;
  return p > c.maxParallaxPx ? c.maxParallaxPx : -c.maxParallaxPx;
}

// The column whose depth a (fractional) position reads: the nearest texel, clamped to the edge. Depth is
// never interpolated, so a position on an edge belongs to one surface.
S3D_INLINE int iterativeDepthTexel(IterativeConstants c, float position) {
  return clamp(int(floor(position + 0.5f)), 0, c.width - 1);
}

// One fixed-point step: where the content at depth linearDepth must come from to land on the target.
// direction is +1 for the left eye, -1 for the right eye.
S3D_INLINE float iterativeNextPosition(IterativeConstants c, float target, float direction, float linearDepth) {
  S3D_PRECISE float shift = direction * iterativeParallaxPx(c, linearDepth);
  S3D_PRECISE float next = target + shift;
  return next;
}

// Far start: the sky's displacement, the farthest any source can be (every parallax is at most it).
S3D_INLINE float iterativeFarStart(IterativeConstants c, float target, float direction) {
  return iterativeNextPosition(c, target, direction, S3D_INFINITY);
}

// The smaller of two depths; a NaN depth never wins (GLSL's min leaves NaN undefined).
S3D_INLINE float iterativeNearerDepth(float a, float b) { return b < a ? b : a; }

// The candidate choice over all iterates of both starts.
struct IterativeSearch {
  bool converged;          // some iterate maps onto the target within a pixel
  float position;          // the nearest such iterate's source position (its fixed-point update)
  float depth;             // and its depth
  float fallbackPosition;  // the iterate that read the farthest depth: the background side of a hole
  float fallbackDepth;
};

S3D_INLINE IterativeSearch iterativeBegin(IterativeConstants c, float target, float direction) {
  IterativeSearch search;
  search.converged = false;
  search.position = iterativeFarStart(c, target, direction);
  search.depth = S3D_INFINITY;
  search.fallbackPosition = search.position;  // finite even if every depth read were NaN
  search.fallbackDepth = -S3D_INFINITY;
  return search;
}

// Considers `position`, whose nearest texel has depth linearDepth, as a solution: its residual
// |position - next| is how far its content lands from the target.
S3D_INLINE IterativeSearch iterativeConsiderSolution(IterativeSearch search, IterativeConstants c, float target,
                                                     float direction, float position, float linearDepth) {
  float next = iterativeNextPosition(c, target, direction, linearDepth);
  if (abs(position - next) <= S3D_ITERATIVE_TOLERANCE_PX && (!search.converged || linearDepth < search.depth)) {
    search.converged = true;  // a solution: the nearest one is visible (occlusion)
    search.position = next;   // consistent with the depth it read, and exact on a flat surface
    search.depth = linearDepth;
  }
  return search;
}

// Considers an iterate of the fixed-point iteration: as a solution, and as the background side of a hole.
S3D_INLINE IterativeSearch iterativeConsider(IterativeSearch search, IterativeConstants c, float target, float direction,
                                             float position, float linearDepth) {
  search = iterativeConsiderSolution(search, c, target, direction, position, linearDepth);
  if (linearDepth > search.fallbackDepth) {
    search.fallbackPosition = position;  // where the far depth was read, not where its parallax points
    search.fallbackDepth = linearDepth;
  }
  return search;
}

// Source position to sample the color at (the nearest solution, or the background side of a hole).
S3D_INLINE float iterativeSourcePosition(IterativeSearch search) {
  return search.converged ? search.position : search.fallbackPosition;
}

S3D_GPU_END

#endif  // S3D_STEREO_ITERATIVE_SHARED_H
