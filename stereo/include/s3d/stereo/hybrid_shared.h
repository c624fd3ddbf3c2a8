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

#define S3D_HYBRID_GROUP_SIZE 8        // the composite and the mask pass: 8 x 8 workgroups (of pixels, of cells)
// The classification: one workgroup per row, each invocation owning a run of its pixels. Its
// invocations, the classification's chunk of eye pixels and whether the runs are classified independently are
// specialization constants, chosen per device (hybridRowShapeFor): a CPU driver such as lavapipe scalarizes
// shared-memory atomics per SIMD lane and switches between invocations at every barrier, so it gets one SIMD
// batch of invocations, each classifying its run alone in private memory; a GPU needs many rows' worth of warps
// in flight, so it gets many invocations per row sharing the chunk's slots in shared memory.
#define S3D_HYBRID_ROW_GROUP 16       // the fallback: invocations per row (half per eye)
#define S3D_HYBRID_CHUNK 256          // the fallback: the classification's eye pixels per step along its row
#define S3D_HYBRID_CPU_ROW_GROUP 8    // CPU devices: one SIMD batch of lavapipe's, each invocation a run of its own
#define S3D_HYBRID_CPU_CHUNK 2048     // CPU devices: a 1920-pixel row in one chunk per eye (private slots: no limit)
#define S3D_HYBRID_CPU_MASK_RUN 16    // CPU devices: the mask pass's cells per invocation (one on a GPU)
#define S3D_HYBRID_GPU_ROW_GROUP 512  // GPUs: fastest measured (RESULTS.md "Both eyes at once in the classification")
#define S3D_HYBRID_GPU_CHUNK 1024     // a row of 2x2 cells at 1920 px in one chunk per eye (48 KiB shared memory)
#define S3D_HYBRID_BINS 256           // score histogram per eye; bin 0 = nothing expected wrong
#define S3D_HYBRID_FINE_BINS 64       // scores below 1 px: 1/64 px per bin (the edge band's ranks)
#define S3D_HYBRID_BINS_PER_PIXEL 8.0f // scores from 1 px on: 1/8 px per bin, the top bin open-ended
#define S3D_HYBRID_MIN_JUMP_PX 0.015625f // expected errors below this (pixels of parallax) are none: 1/64 px
#define S3D_HYBRID_NO_PIXEL 256       // threshold bin that masks nothing
#define S3D_HYBRID_THRESHOLD_GROUP 256 // the threshold pass: one invocation per bin, one workgroup per eye
// Per eye: threshold bin, masked pixels, split bin, split pixels, the split's last cell's row and column.
#define S3D_HYBRID_THRESHOLD_FIELDS 6
// Shared slots: the depth steps whose interior (hybridPairInterior) the row group writes together, 32 invocations
// to a step, instead of the one invocation that found it looping alone while its neighbours wait (two words each);
// steps beyond these, and interiors shorter than S3D_HYBRID_SHARED_INTERIOR_PX, the finding invocation writes.
#define S3D_HYBRID_INTERIOR_CAP 120  // per eye
#define S3D_HYBRID_SHARED_INTERIOR_PX 4
// The classification's shared memory for a row group and its shared slots (both eyes' chunks; 1 with independent
// runs): five per-pixel arrays, both histograms, each invocation's run extremes, the row's parallax range and, with
// shared slots, each eye's list of step interiors and its count (HybridPass checks the device's limit).
#define S3D_HYBRID_CLASSIFY_SHARED_BYTES(group, slots)               \
  (4 * (5 * (slots) + 2 * S3D_HYBRID_BINS + 2 * (group) + 2 +         \
        ((slots) > 1 ? 2 * (2 * S3D_HYBRID_INTERIOR_CAP + 1) : 6)))

// Push constants of the hybrid passes; scalars only, so the std430 and C++ layouts agree.
struct HybridConstants {
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units
  int cropBegin;               // columns [cropBegin, cropEnd) are classified and composited
  int cropEnd;
  int width;
  int height;
  int windowPx;         // the separation window: the largest parallax behind the screen + 1 px (the nearness tier's reach)
  uint maskedPixelCap;  // the budget: at most this many pixels per eye are masked (hybridPixelCap in hybrid.h)
  int baseTapCount;     // a gather base (seed, search): its taps, so its choice of source can be checked;
                        // 0 for a base that lands on the visible surface by design (iterative, forward)
  int cell;             // the classification's cell, pixels per side: 1 every pixel, 2 each 2x2 block (hybridGridSize)
  int minimumBin;       // below budget 1, cells in lower bins are never masked (StereoParameters::hybridScoreFloor)
  int padding2;
  int baseTapOffsetPx[S3D_STEREO_MAX_TAPS];  // the gather's depth taps in whole pixels
};

// The classification's grid: cells of `cell` x `cell` pixels from the image's top left (the last row and column of
// cells may be partial), each classified as one pixel of an image of the cells' nearest depths, so a 2-pixel cell
// classifies a quarter of the pixels with the same row walk. A cell is classified when any of its columns lies in
// the crop; its pixels inside the crop take its mask.
S3D_INLINE int hybridGridSize(int pixels, int cell) { return (pixels + cell - 1) / cell; }
S3D_INLINE int hybridGridCropBegin(int cropBegin, int cell) { return cropBegin / cell; }
S3D_INLINE int hybridGridCropEnd(int cropEnd, int cell) { return (cropEnd + cell - 1) / cell; }

// Parallax in pixels of the (sanitized) linear depth.
S3D_INLINE float hybridParallaxPx(float linearDepth, float maxSeparation, float zeroParallaxDistance, int width) {
  return parallaxFromDepth(maxSeparation, zeroParallaxDistance, sanitizedDepth(linearDepth, zeroParallaxDistance)) *
         float(width);
}

// What the center view's columns show at one eye pixel x. Center texel i (texel centers at integers; beyond the
// image's edges the edge column repeats, out to windowPx columns) lands at l_i = i - direction * P_i in the eye
// (direction +1 left, -1 right; P the parallax in pixels). A texel covers the eye pixels within half a pixel of
// its landing; two neighbouring texels that land in order at most S3D_HYBRID_SPAN_PX apart are one surface and
// cover what lies between (the forward method's rule). The nearest covering surface (the smallest parallax) is
// visible; an eye pixel nothing covers is disoccluded, and the depth step that opened the hole says how wide it
// is. Where two surfaces meet (depths more than S3D_HYBRID_SURFACE_CHANGE apart), the pixels within a pixel of
// the step's landings show their boundary, which a displacement resamples where the eye camera rasterizes: the
// edge band.
//
// Every term is one pair of neighbouring texels' (hybridPairTerms), and a pair reaches only the eye pixels
// within a pixel of its landings (hybridPairReach), so a row is classified by scattering each pair into the
// pixels it reaches, linear in the row plus the width of its holes, where testing every pixel against every
// column that might land on it cost the row times the window.
#define S3D_HYBRID_SPAN_PX 2.0f
#define S3D_HYBRID_SURFACE_CHANGE 0.005f  // relative depth step between two surfaces (the metrics' same-surface rule)
struct HybridCoverage {
  bool covered;
  float visibleParallaxPx;  // of the nearest covering surface
  float holeJumpPx;         // the largest parallax step whose landings straddle the pixel
  float edgeScore;          // the edge band's: 0.25 to 0.5 px by the step (up to 2 px), halved a pixel away
  float nearestChangePx;    // distance to the nearest landing of a step between two surfaces (infinite: none)
};

// Two sanitized linear depths belong to different surfaces (sky against a surface too).
S3D_INLINE bool hybridSurfaceChange(float depthA, float depthB) {
  if (depthA == S3D_INFINITY || depthB == S3D_INFINITY) return depthA != depthB;
  return abs(depthA - depthB) > S3D_HYBRID_SURFACE_CHANGE * min(depthA, depthB);
}

// A pair of neighbouring center texels seen from one eye: texel i (parallax pA, landing landA) and its right
// neighbour, with what does not depend on the eye pixel worked out once.
struct HybridPair {
  float landA, pA, landB, pB;
  float lo, hi;    // the landings in order
  bool span;       // one surface, resampled between the texels: landings in order, at most S3D_HYBRID_SPAN_PX apart
  float jumpPx;    // the parallax step |pA - pB|
  float edgeBase;  // a pair between two surfaces: the edge band's score at its landings (0.25 to 0.5 px by the
                   // step, up to 2 px); 0 for a pair on one surface
};

// The edge band's score at the landings of a step of jumpPx between two surfaces: 0.25 to 0.5 px by the step.
S3D_INLINE float hybridEdgeBase(float jumpPx) { return 0.25f + 0.125f * min(jumpPx, 2.0f); }

S3D_INLINE HybridPair hybridPair(float landA, float pA, float depthA, float landB, float pB, float depthB) {
  HybridPair pair;
  pair.landA = landA;
  pair.pA = pA;
  pair.landB = landB;
  pair.pB = pB;
  pair.lo = min(landA, landB);
  pair.hi = max(landA, landB);
  pair.span = landB > landA && landB - landA <= S3D_HYBRID_SPAN_PX;
  pair.jumpPx = abs(pA - pB);
  pair.edgeBase = hybridSurfaceChange(depthA, depthB) ? hybridEdgeBase(pair.jumpPx) : 0.0f;
  return pair;
}

// What a pair tells eye pixel eyeX: the parallax of the surface it shows there (infinite: none), the parallax
// step of a hole or occlusion whose landings straddle the pixel (0: none), and the edge band's score (0: none). A
// pixel's coverage is the smallest parallax, the largest step and the largest edge score over all pairs.
struct HybridPairTerms {
  float coverParallaxPx;
  float holeJumpPx;
  float edgeScore;
};

S3D_INLINE HybridPairTerms hybridPairTerms(HybridPair pair, float eyeX) {
  HybridPairTerms terms;
  terms.coverParallaxPx = abs(eyeX - pair.landA) <= 0.5f ? pair.pA : S3D_INFINITY;
  terms.holeJumpPx = 0.0f;
  terms.edgeScore = 0.0f;
  if (eyeX >= pair.lo && eyeX <= pair.hi) {
    if (pair.span)  // one surface, resampled between the texels
      terms.coverParallaxPx =
          min(terms.coverParallaxPx, mix(pair.pA, pair.pB, (eyeX - pair.landA) / (pair.landB - pair.landA)));
    else  // a depth step: what lies between its landings belongs to neither side
      terms.holeJumpPx = pair.jumpPx;
  }
  if (pair.edgeBase > 0.0f) {
    float outside = max(max(pair.lo - eyeX, eyeX - pair.hi), 0.0f);
    if (outside <= 1.0f) terms.edgeScore = pair.edgeBase * (1.0f - 0.5f * outside);
  }
  return terms;
}

// The eye pixels a pair's terms can be non-empty at, as floats (the caller clamps): within half a pixel of its
// landings [lo, hi] (the covered half pixel and the straddled interval: integer bounds of lo - 0.5 and hi + 0.5,
// exact after rounding, as integers are representable), and for a pair between two surfaces the edge band's pixel
// each side too ([floor(lo) - 1, ceil(hi) + 1], whatever the rounding of the distances).
S3D_INLINE vec2 hybridPairReach(HybridPair pair) {
  if (pair.edgeBase > 0.0f) return vec2(floor(pair.lo) - 1.0f, -floor(-pair.hi) + 1.0f);
  return vec2(-floor(-(pair.lo - 0.5f)), floor(pair.hi + 0.5f));
}

// The eye pixels deep inside a depth step's landing interval: a pair that is not one surface (not a span) gives
// every pixel at least a pixel from both landings the same terms, hybridPairTerms' (no cover, the step, the edge
// band's base), so a row's scatter writes them without evaluating the terms per pixel; a hole is as wide as the
// parallax step, many times the few pixels at its ends. As floats (the caller clamps): [floor(lo) + 2,
// ceil(hi) - 2], empty (first > last) for a span or a narrow step. Within it eyeX - lo and hi - eyeX are at
// least 1 exactly (integers are representable), so the cover test's half pixel cannot round true.
S3D_INLINE vec2 hybridPairInterior(HybridPair pair) {
  if (pair.span) return vec2(1.0f, 0.0f);
  return vec2(floor(pair.lo) + 2.0f, -floor(-pair.hi) - 2.0f);
}

// The distance from eye pixel eyeX to the nearest landing interval [lo, hi] of a pair between two surfaces,
// from two running extremes along the row: `farthestEnd`, the largest hi among such pairs with lo <= eyeX (-inf:
// none), and `nearestStart`, the smallest lo among those with lo > eyeX (+inf: none). An interval starting at or
// before the pixel is max(eyeX - hi, 0) away, one starting after it lo - eyeX, so the nearest is the smaller of
// the two extremes' distances.
S3D_INLINE float hybridChangeDistancePx(float eyeX, float farthestEnd, float nearestStart) {
  return min(max(eyeX - farthestEnd, 0.0f), nearestStart - eyeX);
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
// between surfaces (a boundary's landing within windowPx: screen-space shading and resampling differ most there),
// up to 0.2 px falling with the distance; 0 for a pixel with no boundary that near. Scores below
// S3D_HYBRID_MIN_JUMP_PX count as 0.
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
