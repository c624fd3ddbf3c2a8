// Hybrid stereo: the classification score (which eye pixels displacement gets wrong, ranked by expected error)
// and the composite rule, shared by the stereo_hybrid_*.comp shaders and the C++ reference (hybrid.h).
#ifndef S3D_HYBRID_SHARED_H
#define S3D_HYBRID_SHARED_H

#include "s3d/gpu/shared.h"
#include "s3d/stereo/stereo_shared.h"

S3D_GPU_BEGIN

#define S3D_HYBRID_GROUP_SIZE 8
#define S3D_HYBRID_BINS 256           // score histogram per eye; bin 0 = no depth change near the pixel
#define S3D_HYBRID_BINS_PER_PIXEL 8.0f // score resolution: 1/8 pixel of parallax jump
#define S3D_HYBRID_MIN_JUMP_PX 0.0625f // parallax steps below this are a smooth surface, not an error source
#define S3D_HYBRID_NO_PIXEL 256       // threshold bin that masks nothing

// Push constants of both hybrid passes; scalars only, so the std430 and C++ layouts agree.
struct HybridConstants {
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units
  int cropBegin;               // columns [cropBegin, cropEnd) are classified and composited
  int cropEnd;
  int width;
  int height;
  int windowPx;      // center columns each side of a pixel whose depth steps can land on it
  int thresholdBin;  // composite: eye pixels whose bin is >= this take the rendered eye's color
};

// Parallax in pixels of the (sanitized) linear depth.
S3D_INLINE float hybridParallaxPx(float linearDepth, float maxSeparation, float zeroParallaxDistance, int width) {
  return parallaxFromDepth(maxSeparation, zeroParallaxDistance, sanitizedDepth(linearDepth, zeroParallaxDistance)) *
         float(width);
}

// Expected error at an eye pixel from one step of the center depth between adjacent columns: the step's
// surfaces land `landA` and `landB` (eye columns) apart, and the eye pixels between them are disoccluded
// (or overlapped) and filled from the wrong surface; pixels `d` columns outside that interval pick the wrong
// surface less often (filter footprint, a gather's taps), so the score falls off as 1 / (1 + d / 2).
S3D_INLINE float hybridStepScore(float eyeX, float landA, float landB, float jumpPx) {
  if (jumpPx < S3D_HYBRID_MIN_JUMP_PX) return 0.0f;
  float lo = min(landA, landB) - 0.5f;
  float hi = max(landA, landB) + 0.5f;
  float outside = max(max(lo - eyeX, eyeX - hi), 0.0f);
  return jumpPx / (1.0f + 0.5f * outside);
}

// Histogram bin of a score: 0 only for no step near the pixel, then 1/8 px wide, the top bin open-ended.
S3D_INLINE uint hybridScoreBin(float score) {
  if (!(score > 0.0f)) return 0u;
  return uint(min(score * S3D_HYBRID_BINS_PER_PIXEL, float(S3D_HYBRID_BINS - 2))) + 1u;
}

S3D_GPU_END

#endif  // S3D_HYBRID_SHARED_H
