#version 450
// Hybrid, pass 1: every eye pixel's score bin (hybrid_shared.h: disoccluded, or the gather base's source not the
// visible surface) and a histogram of the bins per eye, summed in shared memory per workgroup so the global
// atomics stay few.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

// A workgroup classifies a run of one row: the columns its pixels' windows reach are read once into shared
// memory (depth and parallax), and every window, tap and filter texel of the run is served from there.
layout(local_size_x = S3D_HYBRID_ROW_RUN) in;

layout(binding = 0, r32f) uniform readonly image2D linearDepth;
layout(binding = 1, r32ui) uniform writeonly uimage2D leftBins;
layout(binding = 2, r32ui) uniform writeonly uimage2D rightBins;
layout(binding = 3, r32ui) uniform uimage2D histogram;  // S3D_HYBRID_BINS x 2: row 0 left eye, row 1 right

layout(push_constant) uniform Push { HybridConstants c; };

shared uint groupHistogram[2 * S3D_HYBRID_BINS];
shared float rowDepth[S3D_HYBRID_ROW_SPAN];     // sanitized linear depth of columns [rowBegin, rowBegin + span)
shared float rowParallax[S3D_HYBRID_ROW_SPAN];  // their parallax in pixels
int rowBegin;

float imageDepthAt(int x, int y) {
  return sanitizedDepth(imageLoad(linearDepth, ivec2(clamp(x, 0, c.width - 1), y)).r, c.zeroParallaxDistance);
}

// Column x's sanitized depth and parallax: from shared memory inside the run's span, else from the image
// (windows wider than the span's margin).
float sanitizedDepthAt(int x, int y) {
  int at = x - rowBegin;
  return at >= 0 && at < S3D_HYBRID_ROW_SPAN ? rowDepth[at] : imageDepthAt(x, y);
}

float parallaxAt(int x, int y) {
  int at = x - rowBegin;
  return at >= 0 && at < S3D_HYBRID_ROW_SPAN ? rowParallax[at]
                                             : hybridParallaxPx(imageDepthAt(x, y), c.maxSeparation, c.zeroParallaxDistance, c.width);
}

// The score of eye pixel x in the eye looking along `direction` (+1 left, -1 right).
float pixelScore(int x, int y, float direction) {
  precise float eyeX = float(x);
  HybridCoverage coverage = hybridCoverageBegin();
  float dA = sanitizedDepthAt(x - c.windowPx, y);
  float pA = parallaxAt(x - c.windowPx, y);
  for (int i = x - c.windowPx; i < x + c.windowPx; ++i) {
    float dB = sanitizedDepthAt(i + 1, y);
    float pB = parallaxAt(i + 1, y);
    precise float landA = float(i) - direction * pA;
    precise float landB = float(i + 1) - direction * pB;
    coverage = hybridConsiderColumns(coverage, eyeX, landA, pA, dA, landB, pB, dB);
    dA = dB;
    pA = pB;
  }
  float gatherError = 0.0f;
  if (c.baseTapCount > 0) {  // the gather's own choice: the nearest depth over its taps (stereo_gather.glsl)
    float minDepth = S3D_INFINITY;
    for (int t = 0; t < S3D_STEREO_MAX_TAPS; ++t)
      if (t < c.baseTapCount)
        minDepth = min(minDepth, sanitizedDepthAt(x + int(direction) * c.baseTapOffsetPx[t], y));
    precise float u = float(x) + direction * (parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, minDepth) * float(c.width));
    float base = floor(u);
    float fraction = u - base;
    float pLow = parallaxAt(int(base), y), pHigh = parallaxAt(int(base) + 1, y);
    float pNearest = fraction < 0.5f ? pLow : pHigh;
    precise float landing = u - direction * pNearest;
    gatherError = hybridGatherErrorPx(coverage, pNearest, abs(landing - eyeX), pLow, pHigh, fraction);
  }
  return hybridPixelScore(coverage, gatherError, c.windowPx);
}

void main() {
  uint local = gl_LocalInvocationIndex;
  for (uint i = local; i < 2u * S3D_HYBRID_BINS; i += S3D_HYBRID_ROW_RUN) groupHistogram[i] = 0u;
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  rowBegin = int(gl_WorkGroupID.x) * S3D_HYBRID_ROW_RUN - S3D_HYBRID_ROW_MARGIN;
  for (int i = int(local); i < S3D_HYBRID_ROW_SPAN; i += S3D_HYBRID_ROW_RUN) {
    float depth = imageDepthAt(rowBegin + i, pixel.y);
    rowDepth[i] = depth;
    rowParallax[i] = hybridParallaxPx(depth, c.maxSeparation, c.zeroParallaxDistance, c.width);
  }
  barrier();

  bool inside = pixel.x < c.width && pixel.y < c.height;
  if (inside) {
    bool classified = pixel.x >= c.cropBegin && pixel.x < c.cropEnd;
    uint leftBin = classified ? hybridScoreBin(pixelScore(pixel.x, pixel.y, 1.0f)) : 0u;
    uint rightBin = classified ? hybridScoreBin(pixelScore(pixel.x, pixel.y, -1.0f)) : 0u;
    imageStore(leftBins, pixel, uvec4(leftBin));
    imageStore(rightBins, pixel, uvec4(rightBin));
    if (classified) {
      atomicAdd(groupHistogram[leftBin], 1u);
      atomicAdd(groupHistogram[S3D_HYBRID_BINS + rightBin], 1u);
    }
  }
  barrier();
  for (uint i = local; i < 2u * S3D_HYBRID_BINS; i += S3D_HYBRID_ROW_RUN)
    if (groupHistogram[i] != 0u)
      imageAtomicAdd(histogram, ivec2(int(i % S3D_HYBRID_BINS), int(i / S3D_HYBRID_BINS)), groupHistogram[i]);
}
