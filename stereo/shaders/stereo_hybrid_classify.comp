#version 450
// Hybrid, pass 1: every eye pixel's score bin (hybrid_shared.h: disoccluded, or the gather base's source not the
// visible surface), a histogram of the bins per eye (global, summed in shared memory first so the atomics stay
// few) and each row's own histogram (the threshold pass splits the ties of one bin by rows).
//
// One workgroup per row, in linear time: each pair of neighbouring center texels scatters its terms into the eye
// pixels it reaches (shared-memory atomics), the change pairs' landing intervals are swept along the row for the
// nearest boundary (a running maximum and minimum, each invocation along its own run of pixels, then across the
// runs), then every pixel's coverage is complete. The row is walked in chunks of eye pixels; a chunk takes the pairs
// whose landings can reach it or lie within the separation window of it (bounded by the row's parallax range). The
// row group, the chunk and the runs' independence are specialization constants (hybrid_shared.h). Shared slots
// (GPUs): the group's two halves take the two eyes at once; a small half walks its runs' extremes with one
// invocation (four barriers per chunk), a large one scans them in parallel (two barriers per doubling).
// Independent runs (CPU devices: lavapipe scalarizes every shared-memory atomic per SIMD lane and switches between
// invocations at each barrier): each invocation classifies its run of the chunk alone, one eye then the other, as a
// chunk of its own (its pairs, window included), in private slots with plain reads and writes and no barrier.
// Every order of the atomics and scans, and every split into runs, gives the same bits.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(constant_id = 0) const int kGroup = S3D_HYBRID_ROW_GROUP;  // invocations per row
layout(constant_id = 1) const int kChunk = S3D_HYBRID_CHUNK;      // eye pixels per step along the row
// Each invocation classifies its own run of the chunk alone (private slots, no atomics, no barriers)
layout(constant_id = 2) const bool kIndependentRuns = false;
// The gather base's tap array as compiled (detail/base_tap_pipelines.h): short for the seed and short searches
layout(constant_id = 3) const int kBaseTapCapacity = S3D_STEREO_MAX_TAPS;
layout(local_size_x_id = 0) in;

layout(binding = 0, r32f) uniform readonly image2D linearDepth;
layout(binding = 1, r32ui) uniform writeonly uimage2D leftBins;
layout(binding = 2, r32ui) uniform writeonly uimage2D rightBins;
layout(binding = 3, r32ui) uniform uimage2D histogram;               // S3D_HYBRID_BINS x 2: row 0 left eye, row 1 right
layout(binding = 4, r32ui) uniform writeonly uimage2D rowHistograms;  // 2 S3D_HYBRID_BINS x height: left bins, right bins

layout(push_constant) uniform Push { HybridConstants c; };

shared uint groupHistogram[2 * S3D_HYBRID_BINS];
// Shared slots: the group's two halves classify the two eyes at once, each eye's chunk on its own slots (the left
// eye's first), so the row's barriers and memory latencies are paid once for both eyes. Independent runs: each
// invocation classifies the two eyes in turn.
const int kLanes = kIndependentRuns ? kGroup : kGroup / 2;  // invocations per eye
// Per chunk pixel of each eye, as order-preserving bits of floats, shared by the eye's invocations (one slot each
// with independent runs):
const int kSharedSlots = kIndependentRuns ? 1 : 2 * kChunk;
shared uint coverBits[kSharedSlots];         // the smallest covering parallax (+inf: none)
shared uint holeBits[kSharedSlots];          // the largest straddling step
shared uint edgeBits[kSharedSlots];          // the largest edge band score
shared uint farthestEndBits[kSharedSlots];   // change pairs starting at this pixel: the largest end (then a running maximum)
shared uint nearestStartBits[kSharedSlots];  // change pairs starting just after it: the smallest start (then a running minimum)
// The same per pixel of an independent run, in the invocation's private memory (on lavapipe about twice as fast
// as shared memory); one slot each otherwise. The chunk is a multiple of the group.
const int kRunSlots = kIndependentRuns ? kChunk / kGroup : 1;
uint runCoverBits[kRunSlots], runHoleBits[kRunSlots], runEdgeBits[kRunSlots];
uint runFarthestEndBits[kRunSlots], runNearestStartBits[kRunSlots];
shared uint runEnd[kGroup], runStart[kGroup];  // each invocation's run: its largest end, its smallest start (by eye)
// Step interiors each eye's invocations write together (S3D_HYBRID_INTERIOR_CAP per eye): x the first slot | the
// last << 15 | whether the step is between two surfaces << 30, y the step's ordered bits. The count may pass the
// cap: those are written by the invocation that found them.
const int kInteriorSlots = kIndependentRuns ? 1 : S3D_HYBRID_INTERIOR_CAP;
shared uvec2 interiors[2 * kInteriorSlots];
shared uint interiorCount[2];
const int kTeam = kLanes < 32 ? kLanes : 32;  // invocations per queued interior: a GPU's SIMD group (a warp)
shared uint rowParallaxMin, rowParallaxMax;    // the row's parallax range, as ordered bits

// This invocation's eye (0 left, 1 right), its place among the eye's invocations, and the eye's first shared slot.
int laneEye = 0, lane = 0, slotBase = 0;

// Floats as unsigned integers in the same order (negative ones too), for atomicMin / atomicMax.
uint orderedBits(float value) {
  uint bits = floatBitsToUint(value);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}
float orderedFloat(uint bits) { return uintBitsToFloat((bits & 0x80000000u) != 0u ? bits & 0x7fffffffu : ~bits); }

// Column x's sanitized depth (beyond the image's edges, the edge column's). Read from the image rather than
// staged in shared memory: on a CPU driver a shared-memory load costs about twice an image load.
float sanitizedDepthAt(int x, int y) {
  return sanitizedDepth(imageLoad(linearDepth, ivec2(clamp(x, 0, c.width - 1), y)).r, c.zeroParallaxDistance);
}

float parallaxFromSanitized(float depth) {
  return hybridParallaxPx(depth, c.maxSeparation, c.zeroParallaxDistance, c.width);
}

float parallaxAt(int x, int y) { return parallaxFromSanitized(sanitizedDepthAt(x, y)); }

// A slot's terms joined with one pair's: shared-memory atomics where the group's invocations share the slots,
// plain reads and writes where each invocation owns its run's slots.
void lowerCover(int at, uint bits) {
  if (kIndependentRuns) runCoverBits[at] = min(runCoverBits[at], bits);
  else atomicMin(coverBits[slotBase + at], bits);
}
void raiseHole(int at, uint bits) {
  if (kIndependentRuns) runHoleBits[at] = max(runHoleBits[at], bits);
  else atomicMax(holeBits[slotBase + at], bits);
}
void raiseEdge(int at, uint bits) {
  if (kIndependentRuns) runEdgeBits[at] = max(runEdgeBits[at], bits);
  else atomicMax(edgeBits[slotBase + at], bits);
}
void raiseFarthestEnd(int at, uint bits) {
  if (kIndependentRuns) runFarthestEndBits[at] = max(runFarthestEndBits[at], bits);
  else atomicMax(farthestEndBits[slotBase + at], bits);
}
void lowerNearestStart(int at, uint bits) {
  if (kIndependentRuns) runNearestStartBits[at] = min(runNearestStartBits[at], bits);
  else atomicMin(nearestStartBits[slotBase + at], bits);
}

// A pair's terms into the eye pixels [from, to] (slots from x0), each evaluated.
void scatterTerms(HybridPair pair, int x0, int from, int to) {
  for (int x = from; x <= to; ++x) {
    HybridPairTerms terms = hybridPairTerms(pair, float(x));
    if (terms.coverParallaxPx < S3D_INFINITY) lowerCover(x - x0, orderedBits(terms.coverParallaxPx));
    if (terms.holeJumpPx > 0.0f) raiseHole(x - x0, orderedBits(terms.holeJumpPx));
    if (terms.edgeScore > 0.0f) raiseEdge(x - x0, orderedBits(terms.edgeScore));
  }
}

// A step's interior slots first, first + stride, ... up to last: the step's terms for each, without evaluating them
// (the step's ordered bits; the edge band's base when it lies between two surfaces).
void writeInterior(int first, int last, int stride, uint stepBits, bool betweenSurfaces) {
  uint edge = orderedBits(hybridEdgeBase(orderedFloat(stepBits)));
  for (int at = first; at <= last; at += stride) {
    raiseHole(at, stepBits);
    if (betweenSurfaces) raiseEdge(at, edge);
  }
}

// A long step interior (slots first..last) onto the group's list; false: the caller writes it.
bool queueInterior(HybridPair pair, int first, int last) {
  if (last - first + 1 < S3D_HYBRID_SHARED_INTERIOR_PX) return false;
  uint entry = atomicAdd(interiorCount[laneEye], 1u);
  if (entry >= uint(S3D_HYBRID_INTERIOR_CAP)) return false;
  uint bounds = uint(first) | (uint(last) << 15) | (pair.edgeBase > 0.0f ? 1u << 30 : 0u);
  interiors[laneEye * S3D_HYBRID_INTERIOR_CAP + int(entry)] = uvec2(bounds, orderedBits(pair.jumpPx));
  return true;
}

// The eye's queued step interiors into its slots, each by a team of kTeam invocations (after the scatter's barrier).
void writeQueuedInteriors() {
  int team = lane / kTeam, teams = kLanes / kTeam;
  if (team >= teams) return;
  uint queued = min(interiorCount[laneEye], uint(S3D_HYBRID_INTERIOR_CAP));
  for (uint entry = uint(team); entry < queued; entry += uint(teams)) {
    uvec2 interior = interiors[laneEye * S3D_HYBRID_INTERIOR_CAP + int(entry)];
    int first = int(interior.x & 0x7fffu), last = int((interior.x >> 15) & 0x7fffu);
    writeInterior(first + lane % kTeam, last, kTeam, interior.y, (interior.x & (1u << 30)) != 0u);
  }
}

// Shared slots: a step's interior takes its constant terms (hybridPairInterior), queued for the group when long,
// so no invocation loops across a hole while its SIMD group waits; its ends, and a span, are evaluated per pixel.
void scatterSplit(HybridPair pair, int x0, int x1, int from, int to) {
  vec2 interior = hybridPairInterior(pair);
  int insideFrom = int(clamp(interior.x, float(x0), float(x1)));
  int insideTo = int(clamp(interior.y, float(x0 - 1), float(x1 - 1)));
  if (insideFrom > insideTo) {
    scatterTerms(pair, x0, from, to);
    return;
  }
  scatterTerms(pair, x0, from, insideFrom - 1);
  if (!queueInterior(pair, insideFrom - x0, insideTo - x0))
    writeInterior(insideFrom - x0, insideTo - x0, 1, orderedBits(pair.jumpPx), pair.edgeBase > 0.0f);
  scatterTerms(pair, x0, insideTo + 1, to);
}

// Pair (i, i + 1), its sanitized depths and parallaxes given, into the eye pixels [x0, x1) (slots from 0) of the
// eye looking along `direction`.
void scatterPair(float direction, int x0, int x1, int i, float dA, float pA, float dB, float pB) {
  precise float landA = float(i) - direction * pA;
  precise float landB = float(i + 1) - direction * pB;
  HybridPair pair = hybridPair(landA, pA, dA, landB, pB, dB);
  vec2 reach = hybridPairReach(pair);
  int from = int(clamp(reach.x, float(x0), float(x1)));
  int to = int(clamp(reach.y, float(x0 - 1), float(x1 - 1)));
  if (kIndependentRuns) {  // one loop per pair: on a CPU device the split below costs more than it saves
    scatterTerms(pair, x0, from, to);
  } else {
    scatterSplit(pair, x0, x1, from, to);
  }
  if (pair.edgeBase > 0.0f) {  // a pair between two surfaces: its landings for the nearest boundary
    float start = ceil(pair.lo);  // the first pixel at or after lo (hybridChangeDistancePx's two extremes)
    if (start <= float(x1 - 1)) raiseFarthestEnd(int(max(start, float(x0))) - x0, orderedBits(pair.hi));
    if (start - 1.0f >= float(x0))
      lowerNearestStart(int(min(start - 1.0f, float(x1 - 1))) - x0, orderedBits(pair.lo));
  }
}

float depthAt(int x, int y) { return sanitizedDepthAt(x, y); }
#undef S3D_STEREO_TAP_CAPACITY
#define S3D_STEREO_TAP_CAPACITY kBaseTapCapacity
#define S3D_GATHER_TAP_COUNT c.baseTapCount
#define S3D_GATHER_TAP_OFFSET_PX c.baseTapOffsetPx
#include "stereo_gather_source.glsl"

// The score of eye pixel x (chunk slot `at`) in the eye looking along `direction`, the nearest boundary's extremes
// given.
float pixelScore(int x, int y, int at, float direction, float farthestEnd, float nearestStart) {
  precise float eyeX = float(x);
  HybridCoverage coverage;
  coverage.visibleParallaxPx = orderedFloat(kIndependentRuns ? runCoverBits[at] : coverBits[slotBase + at]);
  coverage.covered = coverage.visibleParallaxPx < S3D_INFINITY;
  coverage.holeJumpPx = orderedFloat(kIndependentRuns ? runHoleBits[at] : holeBits[slotBase + at]);
  coverage.edgeScore = orderedFloat(kIndependentRuns ? runEdgeBits[at] : edgeBits[slotBase + at]);
  coverage.nearestChangePx = hybridChangeDistancePx(eyeX, farthestEnd, nearestStart);
  float gatherError = 0.0f;
  if (c.baseTapCount > 0) {  // the gather's own choice of source column (stereo_gather_source.glsl)
    int side = int(direction);
    precise float u = gatherSourceColumn(x, side, minDepthOverTaps(x, y, side));
    float base = floor(u);
    float fraction = u - base;
    float pLow = parallaxAt(int(base), y), pHigh = parallaxAt(int(base) + 1, y);
    float pNearest = fraction < 0.5f ? pLow : pHigh;
    precise float landing = u - direction * pNearest;
    gatherError = hybridGatherErrorPx(coverage, pNearest, abs(landing - eyeX), pLow, pHigh, fraction);
  }
  return hybridPixelScore(coverage, gatherError, c.windowPx);
}

void clearSharedSlot(int index) {
  coverBits[index] = orderedBits(S3D_INFINITY);
  holeBits[index] = orderedBits(0.0f);
  edgeBits[index] = orderedBits(0.0f);
  farthestEndBits[index] = orderedBits(-S3D_INFINITY);
  nearestStartBits[index] = orderedBits(S3D_INFINITY);
}

void clearSlot(int at) {
  if (kIndependentRuns) {
    runCoverBits[at] = orderedBits(S3D_INFINITY);
    runHoleBits[at] = orderedBits(0.0f);
    runEdgeBits[at] = orderedBits(0.0f);
    runFarthestEndBits[at] = orderedBits(-S3D_INFINITY);
    runNearestStartBits[at] = orderedBits(S3D_INFINITY);
  } else {
    clearSharedSlot(slotBase + at);
  }
}

uint unscoredPixels[2];  // this invocation's pixels in bin 0, per eye

// The pairs whose landings can reach the eye pixels [x0, x1) or lie within the separation window of them, on the
// edge-extended row: texel i lands within [i - P_max, i + 1 - P_min] (left eye; mirrored right).
ivec2 pairRange(int eye, int x0, int x1, float parallaxMin, float parallaxMax) {
  float reachBefore = eye == 0 ? -parallaxMin : parallaxMax, reachAfter = eye == 0 ? parallaxMax : -parallaxMin;
  int first = int(max(float(x0 - c.windowPx - 3) - max(reachBefore, 0.0f), float(-c.windowPx)));
  int last = int(min(float(x1 + c.windowPx + 2) + max(reachAfter, 0.0f), float(c.width + c.windowPx - 2)));
  return ivec2(first, last);
}

// Eye pixel x's bin into the images and the group's histogram.
void storeBin(int eye, int x, int y, uint bin) {
  if (eye == 0) imageStore(leftBins, ivec2(x, y), uvec4(bin));
  else imageStore(rightBins, ivec2(x, y), uvec4(bin));
  if (bin != 0u) atomicAdd(groupHistogram[eye * S3D_HYBRID_BINS + int(bin)], 1u);
  else ++unscoredPixels[eye];  // most pixels: counted privately, one atomic per invocation at the end
}

// Independent runs: this invocation's run of the eye pixels [x0, x1) of row y, classified alone in its private
// slots (cleared here): its pairs walked in order (each pair's right texel is the next one's left), the nearest
// boundary swept backwards then forwards along the run.
void classifyRun(int eye, int x0, int x1, int y, float parallaxMin, float parallaxMax) {
  int local = int(gl_LocalInvocationIndex);
  float direction = eye == 0 ? 1.0f : -1.0f;
  int n = x1 - x0, runLength = (n + kGroup - 1) / kGroup;
  int runX0 = x0 + min(local * runLength, n), runX1 = x0 + min(local * runLength + runLength, n);
  if (runX0 == runX1) return;  // a chunk narrower than the group leaves some invocations none
  int slots = runX1 - runX0;
  for (int at = 0; at < slots; ++at) clearSlot(at);
  ivec2 pairs = pairRange(eye, runX0, runX1, parallaxMin, parallaxMax);
  float dA = sanitizedDepthAt(pairs.x, y), pA = parallaxFromSanitized(dA);
  for (int i = pairs.x; i <= pairs.y; ++i) {
    float dB = sanitizedDepthAt(i + 1, y), pB = parallaxFromSanitized(dB);
    scatterPair(direction, runX0, runX1, i, dA, pA, dB, pB);
    dA = dB;
    pA = pB;
  }
  uint start = orderedBits(S3D_INFINITY);
  for (int at = slots - 1; at >= 0; --at) runNearestStartBits[at] = start = min(start, runNearestStartBits[at]);
  uint end = orderedBits(-S3D_INFINITY);
  uint sameBin = 0u, sameBinPixels = 0u;  // a stretch of neighbours in one scored bin: one histogram atomic
  for (int at = 0; at < slots; ++at) {
    end = max(end, runFarthestEndBits[at]);
    int x = runX0 + at;
    uint bin = hybridScoreBin(pixelScore(x, y, at, direction, orderedFloat(end), orderedFloat(runNearestStartBits[at])));
    if (eye == 0) imageStore(leftBins, ivec2(x, y), uvec4(bin));
    else imageStore(rightBins, ivec2(x, y), uvec4(bin));
    if (bin == 0u) {
      ++unscoredPixels[eye];
    } else if (bin == sameBin) {
      ++sameBinPixels;
    } else {
      if (sameBinPixels != 0u) atomicAdd(groupHistogram[eye * S3D_HYBRID_BINS + int(sameBin)], sameBinPixels);
      sameBin = bin;
      sameBinPixels = 1u;
    }
  }
  if (sameBinPixels != 0u) atomicAdd(groupHistogram[eye * S3D_HYBRID_BINS + int(sameBin)], sameBinPixels);
}

// The pixels [x0, x1) of row y of this invocation's eye, by the eye's invocations (the other half of the group
// classifies the other eye alongside); the slots are clear on entry and left clear.
void classifyChunk(int x0, int x1, int y, float parallaxMin, float parallaxMax) {
  int eye = laneEye, eyeRuns = laneEye * kLanes;  // the eye's first entry in runEnd and runStart
  float direction = eye == 0 ? 1.0f : -1.0f;
  ivec2 pairs = pairRange(eye, x0, x1, parallaxMin, parallaxMax);
  for (int i = pairs.x + lane; i <= pairs.y; i += kLanes) {
    float dA = sanitizedDepthAt(i, y), dB = sanitizedDepthAt(i + 1, y);
    scatterPair(direction, x0, x1, i, dA, parallaxFromSanitized(dA), dB, parallaxFromSanitized(dB));
  }
  barrier();
  writeQueuedInteriors();  // (the hole and edge slots are next read after the runs' barriers below)
  // The nearest boundary: each invocation runs along its own run of pixels, then takes the runs before and after.
  int n = x1 - x0, runLength = (n + kLanes - 1) / kLanes;
  int runBegin = min(lane * runLength, n), runStop = min(runBegin + runLength, n);
  uint end = orderedBits(-S3D_INFINITY), start = orderedBits(S3D_INFINITY);
  for (int at = slotBase + runBegin; at < slotBase + runStop; ++at)
    farthestEndBits[at] = end = max(end, farthestEndBits[at]);
  for (int at = slotBase + runStop - 1; at >= slotBase + runBegin; --at)
    nearestStartBits[at] = start = min(start, nearestStartBits[at]);
  runEnd[eyeRuns + lane] = end;
  runStart[eyeRuns + lane] = start;
  barrier();
  // Each run's extremes of itself and the runs before it (the end) or after it (the start): one invocation per eye
  // walks a few runs; many scan in parallel (Hillis-Steele).
  if (kLanes <= 32) {
    if (lane == 0) {
      for (int r = 1; r < kLanes; ++r) runEnd[eyeRuns + r] = max(runEnd[eyeRuns + r], runEnd[eyeRuns + r - 1]);
      for (int r = kLanes - 2; r >= 0; --r)
        runStart[eyeRuns + r] = min(runStart[eyeRuns + r], runStart[eyeRuns + r + 1]);
    }
    barrier();
  } else {
    for (int step = 1; step < kLanes; step <<= 1) {
      uint endBefore = lane >= step ? runEnd[eyeRuns + lane - step] : orderedBits(-S3D_INFINITY);
      uint startAfter = lane + step < kLanes ? runStart[eyeRuns + lane + step] : orderedBits(S3D_INFINITY);
      barrier();
      runEnd[eyeRuns + lane] = max(runEnd[eyeRuns + lane], endBefore);
      runStart[eyeRuns + lane] = min(runStart[eyeRuns + lane], startAfter);
      barrier();
    }
  }
  // Then every pixel in turn, with the runs before and after its own.
  for (int at = lane; at < n; at += kLanes) {
    int run = at / runLength;
    uint endBefore = run > 0 ? runEnd[eyeRuns + run - 1] : orderedBits(-S3D_INFINITY);
    uint startAfter = run + 1 < kLanes ? runStart[eyeRuns + run + 1] : orderedBits(S3D_INFINITY);
    float farthestEnd = orderedFloat(max(endBefore, farthestEndBits[slotBase + at]));
    float nearestStart = orderedFloat(min(startAfter, nearestStartBits[slotBase + at]));
    storeBin(eye, x0 + at, y, hybridScoreBin(pixelScore(x0 + at, y, at, direction, farthestEnd, nearestStart)));
    clearSlot(at);
  }
  if (lane == 0) interiorCount[eye] = 0u;  // read before the runs' barriers
  barrier();  // the slots are clear again, runEnd and runStart read
}

void main() {
  int local = int(gl_LocalInvocationIndex);
  int y = int(gl_WorkGroupID.x);
  if (!kIndependentRuns) {
    laneEye = local / kLanes;
    lane = local % kLanes;
    slotBase = laneEye * kChunk;
  }
  for (int i = local; i < 2 * S3D_HYBRID_BINS; i += kGroup) groupHistogram[i] = 0u;
  if (!kIndependentRuns)
    for (int index = local; index < kSharedSlots; index += kGroup) clearSharedSlot(index);
  if (local == 0) {
    rowParallaxMin = orderedBits(S3D_INFINITY);
    rowParallaxMax = orderedBits(-S3D_INFINITY);
    interiorCount[0] = interiorCount[1] = 0u;
  }
  unscoredPixels[0] = unscoredPixels[1] = 0u;
  barrier();
  // Columns outside the crop are not classified: bin 0, left out of the histograms. Every column's parallax
  // bounds where the row's texels land.
  float parallaxMin = S3D_INFINITY, parallaxMax = -S3D_INFINITY;
  for (int x = local; x < c.width; x += kGroup) {
    float p = parallaxAt(x, y);
    parallaxMin = min(parallaxMin, p);
    parallaxMax = max(parallaxMax, p);
    if (x < c.cropBegin || x >= c.cropEnd) {
      imageStore(leftBins, ivec2(x, y), uvec4(0u));
      imageStore(rightBins, ivec2(x, y), uvec4(0u));
    }
  }
  atomicMin(rowParallaxMin, orderedBits(parallaxMin));
  atomicMax(rowParallaxMax, orderedBits(parallaxMax));
  barrier();
  parallaxMin = orderedFloat(rowParallaxMin);
  parallaxMax = orderedFloat(rowParallaxMax);
  // (The reach is clamped to the edge-extended row, so an unbounded parallax costs time, never correctness.)
  parallaxMin = max(parallaxMin, -float(c.width + 2 * c.windowPx));
  parallaxMax = min(parallaxMax, float(c.width + 2 * c.windowPx));
  for (int x0 = c.cropBegin; x0 < c.cropEnd; x0 += kChunk) {
    int x1 = min(x0 + kChunk, c.cropEnd);
    if (kIndependentRuns) {
      classifyRun(0, x0, x1, y, parallaxMin, parallaxMax);
      classifyRun(1, x0, x1, y, parallaxMin, parallaxMax);
    } else {
      classifyChunk(x0, x1, y, parallaxMin, parallaxMax);
    }
  }
  if (unscoredPixels[0] != 0u) atomicAdd(groupHistogram[0], unscoredPixels[0]);
  if (unscoredPixels[1] != 0u) atomicAdd(groupHistogram[S3D_HYBRID_BINS], unscoredPixels[1]);
  barrier();
  for (int i = local; i < 2 * S3D_HYBRID_BINS; i += kGroup) {
    uint count = groupHistogram[i];
    imageStore(rowHistograms, ivec2(i, y), uvec4(count));
    if (count != 0u) imageAtomicAdd(histogram, ivec2(i % S3D_HYBRID_BINS, i / S3D_HYBRID_BINS), count);
  }
}
