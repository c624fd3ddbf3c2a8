#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "row_sampling.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/row_tile_shared.h"

namespace s3d::stereo {
namespace {

using detail::sampleRow;

float depthAtTexel(const DepthImage& depth, const gpu::IterativeConstants& c, float position, int y) {
  // NaN, zero and negative depth read as the zero-parallax plane, as in the seed (gpu::sanitizedDepth).
  return gpu::sanitizedDepth(*depth.at(std::uint32_t(gpu::iterativeDepthTexel(c, position)), std::uint32_t(y)),
                             c.zeroParallaxDistance);
}

}  // namespace

gpu::IterativeConstants makeIterativeConstants(const StereoParameters& parameters, int iterations, std::uint32_t width,
                                               std::uint32_t height) {
  if (iterations < 1 || iterations > S3D_ITERATIVE_MAX_ITERATIONS)
    throw std::invalid_argument("iterations " + std::to_string(iterations) + " is outside [1, " +
                                std::to_string(S3D_ITERATIVE_MAX_ITERATIONS) + "]");
  // Validation, size checks and the edge crop exactly as the seed's.
  const gpu::StereoConstants seed = makeSeedConstants(parameters, width, height);
  gpu::IterativeConstants c{};
  c.maxSeparation = seed.maxSeparation;
  c.zeroParallaxDistance = seed.zeroParallaxDistance;
  c.maxParallaxPx = gpu::parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, S3D_INFINITY) * float(width);
  c.cropBegin = seed.cropBegin;
  c.cropEnd = seed.cropEnd;
  c.width = seed.width;
  c.height = seed.height;
  c.iterations = iterations;
  c.markFilled = 0;  // the eyes carry the center's alpha (the weapon mask), as every method's do
  // Near-start taps from the target itself (offset 0: a surface the target lies on) to the sky's displacement,
  // evenly spread and rounded like the seed's; repeated offsets are dropped.
  for (int i = 0; i < S3D_ITERATIVE_START_TAPS; ++i) {
    float fraction = float(i) / float(S3D_ITERATIVE_START_TAPS - 1);
    int offset = int(std::floor(0.5f + fraction * parameters.maxSeparation * float(width)));
    if (c.startTapCount == 0 || offset != c.startTapOffsetPx[c.startTapCount - 1]) c.startTapOffsetPx[c.startTapCount++] = offset;
  }
  return c;
}

int rowTileMargin(const gpu::IterativeConstants& c) {
  int largestTap = 0;
  for (int i = 0; i < c.startTapCount; ++i) largestTap = std::max(largestTap, c.startTapOffsetPx[i]);
  return gpu::rowTileMarginPx(c.maxParallaxPx, largestTap);
}

IterativeSample solveIterativePixel(const DepthImage& linearDepth, int x, int y, Eye eye, const gpu::IterativeConstants& c) {
  const float direction = eye == Eye::Left ? 1.0f : -1.0f;
  const float target = float(x);
  gpu::IterativeSearch search = gpu::iterativeBegin(c, target, direction);
  // Near start: the nearest surface over the separation range (the seed's idea, taps from the target on).
  // Each tap is also a candidate solution, so a surface the iterations jump over is still found.
  float minDepth = S3D_INFINITY;
  for (int i = 0; i < c.startTapCount; ++i) {
    float tap = target + direction * float(c.startTapOffsetPx[i]);
    float depth = depthAtTexel(linearDepth, c, tap, y);
    search = gpu::iterativeConsiderSolution(search, c, target, direction, tap, depth);
    minDepth = gpu::iterativeNearerDepth(minDepth, depth);
  }
  const float starts[2] = {gpu::iterativeFarStart(c, target, direction),
                           gpu::iterativeNextPosition(c, target, direction, minDepth)};
  for (float start : starts) {
    float position = start;
    for (int k = 0; k < c.iterations; ++k) {
      float depth = depthAtTexel(linearDepth, c, position, y);
      search = gpu::iterativeConsider(search, c, target, direction, position, depth);
      position = gpu::iterativeNextPosition(c, target, direction, depth);
    }
  }
  return {gpu::iterativeSourcePosition(search), search.converged ? search.depth : search.fallbackDepth, !search.converged};
}

StereoPair synthesizeIterativeReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                        const gpu::IterativeConstants& c) {
  requireSameSize(center, linearDepth, "iterative stereo (color vs depth)");
  if (int(center.width) != c.width || int(center.height) != c.height)
    throw std::invalid_argument("iterative stereo: constants were made for another image size");
  StereoPair pair{ImageRGBA8(center.width, center.height), ImageRGBA8(center.width, center.height)};
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      for (auto [eye, image] : {std::pair{Eye::Left, &pair.left}, std::pair{Eye::Right, &pair.right}}) {
        std::uint8_t* out = image->at(std::uint32_t(x), std::uint32_t(y));
        if (x < c.cropBegin || x >= c.cropEnd) {  // cropped edges, as in the seed
          std::fill(out, out + 4, std::uint8_t(0));
          out[3] = 255;
          continue;
        }
        IterativeSample sample = solveIterativePixel(linearDepth, x, y, eye, c);
        sampleRow(center, y, sample.sourcePosition, out);
        if (c.markFilled != 0) out[3] = sample.filled ? 0 : 255;  // the fill flag instead of the alpha
      }
    }
  }
  return pair;
}

}  // namespace s3d::stereo
