#version 450
// Hybrid, pass 1: every eye pixel's score bin (hybrid_shared.h) and a histogram of the bins per eye, summed
// in shared memory per workgroup so the global atomics stay few.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/hybrid_shared.h"

layout(local_size_x = S3D_HYBRID_GROUP_SIZE, local_size_y = S3D_HYBRID_GROUP_SIZE) in;

layout(binding = 0, r32f) uniform readonly image2D linearDepth;
layout(binding = 1, r32ui) uniform writeonly uimage2D leftBins;
layout(binding = 2, r32ui) uniform writeonly uimage2D rightBins;
layout(binding = 3, r32ui) uniform uimage2D histogram;  // S3D_HYBRID_BINS x 2: row 0 left eye, row 1 right

layout(push_constant) uniform Push { HybridConstants c; };

shared uint groupHistogram[2 * S3D_HYBRID_BINS];

float parallaxAt(int x, int y) {
  return hybridParallaxPx(imageLoad(linearDepth, ivec2(clamp(x, 0, c.width - 1), y)).r, c.maxSeparation,
                          c.zeroParallaxDistance, c.width);
}

void main() {
  uint local = gl_LocalInvocationIndex;
  for (uint i = local; i < 2u * S3D_HYBRID_BINS; i += S3D_HYBRID_GROUP_SIZE * S3D_HYBRID_GROUP_SIZE) groupHistogram[i] = 0u;
  barrier();

  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  bool inside = pixel.x < c.width && pixel.y < c.height;
  if (inside) {
    float leftScore = 0.0f, rightScore = 0.0f;
    float eyeX = float(pixel.x);
    // Column i lands at i - p (left eye) and i + p (right eye): every step within the window can reach x.
    float previous = parallaxAt(pixel.x - c.windowPx, pixel.y);
    for (int i = pixel.x - c.windowPx; i < pixel.x + c.windowPx; ++i) {
      float next = parallaxAt(i + 1, pixel.y);
      float jump = abs(next - previous);
      leftScore = max(leftScore, hybridStepScore(eyeX, float(i) - previous, float(i + 1) - next, jump));
      rightScore = max(rightScore, hybridStepScore(eyeX, float(i) + previous, float(i + 1) + next, jump));
      previous = next;
    }
    bool classified = pixel.x >= c.cropBegin && pixel.x < c.cropEnd;
    uint leftBin = classified ? hybridScoreBin(leftScore) : 0u;
    uint rightBin = classified ? hybridScoreBin(rightScore) : 0u;
    imageStore(leftBins, pixel, uvec4(leftBin));
    imageStore(rightBins, pixel, uvec4(rightBin));
    if (classified) {
      atomicAdd(groupHistogram[leftBin], 1u);
      atomicAdd(groupHistogram[S3D_HYBRID_BINS + rightBin], 1u);
    }
  }
  barrier();
  for (uint i = local; i < 2u * S3D_HYBRID_BINS; i += S3D_HYBRID_GROUP_SIZE * S3D_HYBRID_GROUP_SIZE)
    if (groupHistogram[i] != 0u)
      imageAtomicAdd(histogram, ivec2(int(i % S3D_HYBRID_BINS), int(i / S3D_HYBRID_BINS)), groupHistogram[i]);
}
