// Hybrid stereo: the classification score (which eye pixels displacement gets wrong, ranked by expected error)
// and the composite rule, shared by the stereo_hybrid_*.comp shaders and the C++ reference (hybrid.h).
#ifndef S3D_HYBRID_SHARED_H
#define S3D_HYBRID_SHARED_H

#include "s3d/gpu/shared.h"
#include "s3d/stereo/stereo_shared.h"

#ifdef __cplusplus
namespace s3d::gpu {
using glm::abs;
using glm::floor;
}  // namespace s3d::gpu
#endif

S3D_GPU_BEGIN

#define S3D_HYBRID_GROUP_SIZE 8        // threshold-free passes (mask, composite): 8 x 8 workgroups
#define S3D_HYBRID_ROW_RUN 64          // the classification: one workgroup per run of 64 pixels of a row
#define S3D_HYBRID_ROW_MARGIN 96       // columns each side of the run held in shared memory (wider windows read the image)
#define S3D_HYBRID_ROW_SPAN (S3D_HYBRID_ROW_RUN + 2 * S3D_HYBRID_ROW_MARGIN)
#define S3D_HYBRID_BINS 256           // score histogram per eye; bin 0 = nothing expected wrong
#define S3D_HYBRID_FINE_BINS 64       // scores below 1 px: 1/64 px per bin (the edge band's ranks)
#define S3D_HYBRID_BINS_PER_PIXEL 8.0f // scores from 1 px on: 1/8 px per bin, the top bin open-ended
#define S3D_HYBRID_MIN_JUMP_PX 0.015625f // expected errors below this (pixels of parallax) are none: 1/64 px
#define S3D_HYBRID_NO_PIXEL 256       // threshold bin that masks nothing
#define S3D_HYBRID_THRESHOLD_GROUP 256 // the threshold pass: one invocation per bin, one workgroup per eye

// Push constants of the hybrid passes; scalars only, so the std430 and C++ layouts agree.
struct HybridConstants {
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units
  int cropBegin;               // columns [cropBegin, cropEnd) are classified and composited
  int cropEnd;
  int width;
  int height;
  int windowPx;         // center columns each side of a pixel whose content can land on it
  uint maskedPixelCap;  // the budget: at most this many pixels per eye are masked (hybridPixelCap in hybrid.h)
  int baseTapCount;     // a gather base (seed, search): its taps, so its choice of source can be checked;
  int padding0;         // 0 for a base that lands on the visible surface by design (iterative, forward)
  int padding1;
  int padding2;
  int baseTapOffsetPx[S3D_STEREO_MAX_TAPS];  // the gather's depth taps in whole pixels
};

// Parallax in pixels of the (sanitized) linear depth.
S3D_INLINE float hybridParallaxPx(float linearDepth, float maxSeparation, float zeroParallaxDistance, int width) {
  return parallaxFromDepth(maxSeparation, zeroParallaxDistance, sanitizedDepth(linearDepth, zeroParallaxDistance)) *
         float(width);
}

// What the center view's columns show at one eye pixel x. Center texel i (texel centers at integers) lands at
// l_i = i - direction * P_i in the eye (direction +1 left, -1 right; P the parallax in pixels). A texel covers
// the eye pixels within half a pixel of its landing; two neighbouring texels that land in order at most
// S3D_HYBRID_SPAN_PX apart are one surface and cover what lies between (the forward method's rule). The
// nearest covering surface (the smallest parallax) is visible; an eye pixel nothing covers is disoccluded, and
// the depth step that opened the hole says how wide it is. Where two surfaces meet (depths more than
// S3D_HYBRID_SURFACE_CHANGE apart), the pixels within a pixel of the step's landings show their boundary,
// which a displacement resamples where the eye camera rasterizes: the edge band.
#define S3D_HYBRID_SPAN_PX 2.0f
#define S3D_HYBRID_SURFACE_CHANGE 0.005f  // relative depth step between two surfaces (the metrics' same-surface rule)
struct HybridCoverage {
  bool covered;
  float visibleParallaxPx;  // of the nearest covering surface
  float holeJumpPx;         // the largest parallax step whose landings straddle the pixel
  float edgeScore;          // the edge band's: 0.25 to 0.5 px by the step (up to 2 px), halved a pixel away
  float nearestChangePx;    // distance to the nearest landing of a step between two surfaces (infinite: none)
};

S3D_INLINE HybridCoverage hybridCoverageBegin() {
  HybridCoverage coverage;
  coverage.covered = false;
  coverage.visibleParallaxPx = S3D_INFINITY;
  coverage.holeJumpPx = 0.0f;
  coverage.edgeScore = 0.0f;
  coverage.nearestChangePx = S3D_INFINITY;
  return coverage;
}

// Two sanitized linear depths belong to different surfaces (sky against a surface too).
S3D_INLINE bool hybridSurfaceChange(float depthA, float depthB) {
  if (depthA == S3D_INFINITY || depthB == S3D_INFINITY) return depthA != depthB;
  return abs(depthA - depthB) > S3D_HYBRID_SURFACE_CHANGE * min(depthA, depthB);
}

// Texel i (parallax pA, landing landA, sanitized depth depthA) and its right neighbour, for eye pixel eyeX.
S3D_INLINE HybridCoverage hybridConsiderColumns(HybridCoverage coverage, float eyeX, float landA, float pA,
                                                float depthA, float landB, float pB, float depthB) {
  if (abs(eyeX - landA) <= 0.5f && pA < coverage.visibleParallaxPx) {
    coverage.covered = true;
    coverage.visibleParallaxPx = pA;
  }
  float lo = min(landA, landB), hi = max(landA, landB);
  if (eyeX >= lo && eyeX <= hi) {
    if (landB > landA && landB - landA <= S3D_HYBRID_SPAN_PX) {  // one surface, resampled between the texels
      float p = mix(pA, pB, (eyeX - landA) / (landB - landA));
      if (p < coverage.visibleParallaxPx) {
        coverage.covered = true;
        coverage.visibleParallaxPx = p;
      }
    } else {  // a depth step: what lies between its landings belongs to neither side
      coverage.holeJumpPx = max(coverage.holeJumpPx, abs(pA - pB));
    }
  }
  float outside = max(max(lo - eyeX, eyeX - hi), 0.0f);
  if (hybridSurfaceChange(depthA, depthB)) {
    coverage.nearestChangePx = min(coverage.nearestChangePx, outside);
    if (outside <= 1.0f)
      coverage.edgeScore = max(coverage.edgeScore, (0.25f + 0.125f * min(abs(pA - pB), 2.0f)) * (1.0f - 0.5f * outside));
  }
  return coverage;
}

// A gather base's source for the pixel: the color is filtered at u between texels floor(u) and floor(u) + 1,
// whose parallaxes are pLow and pHigh; the surface it shows is the nearest texel's (parallax pNearest), which
// lands `residualPx` from the pixel. The source is wrong when that surface is not the visible one (by more than
// half a pixel of parallax) or does not land on the pixel; a filter footprint across a depth step blends two
// surfaces and is half as wrong.
S3D_INLINE float hybridGatherErrorPx(HybridCoverage coverage, float pNearest, float residualPx, float pLow, float pHigh,
                                     float fraction) {
  float error = 0.0f;
  float wrongSurface = coverage.covered ? abs(pNearest - coverage.visibleParallaxPx) : 0.0f;
  if (wrongSurface > 0.5f || residualPx > 0.75f) error = max(wrongSurface, residualPx);
  bool blended = fraction > 0.125f && fraction < 0.875f;
  if (blended && abs(pLow - pHigh) > 1.0f) error = max(error, 0.5f * abs(pLow - pHigh));
  return error;
}

// Expected error of an eye pixel, in pixels of parallax, in tiers: a disoccluded pixel the width of its hole
// (at least 1: the center never saw it); a covered pixel what its base's source got wrong (0 for a base that
// lands on the visible surface by design), at least its edge band score; below those, a pixel near a boundary
// between surfaces (within windowPx: screen-space shading and resampling differ most there), up to 0.2 px
// falling with the distance; 0 for a pixel with no boundary in its window. Scores below S3D_HYBRID_MIN_JUMP_PX
// count as 0.
S3D_INLINE float hybridPixelScore(HybridCoverage coverage, float gatherErrorPx, int windowPx) {
  float near = 0.2f * max(1.0f - coverage.nearestChangePx / float(windowPx), 0.0f);
  float score = coverage.covered ? max(max(gatherErrorPx, coverage.edgeScore), near) : max(coverage.holeJumpPx, 1.0f);
  return score >= S3D_HYBRID_MIN_JUMP_PX ? score : 0.0f;
}

// Histogram bin of a score: 0 only for a pixel the displacement gets right; scores below 1 px in 1/64 px bins
// (1..64), larger ones in 1/8 px bins from 65 on, the top bin open-ended.
S3D_INLINE uint hybridScoreBin(float score) {
  if (!(score > 0.0f)) return 0u;
  if (score < 1.0f) return uint(score * float(S3D_HYBRID_FINE_BINS)) + 1u;
  return uint(min((score - 1.0f) * S3D_HYBRID_BINS_PER_PIXEL, float(S3D_HYBRID_BINS - S3D_HYBRID_FINE_BINS - 2))) +
         uint(S3D_HYBRID_FINE_BINS) + 1u;
}

S3D_GPU_END

#endif  // S3D_HYBRID_SHARED_H
