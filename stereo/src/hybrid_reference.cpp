#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "s3d/number_text.h"
#include "s3d/stereo/hybrid.h"

namespace s3d::stereo {

int hybridCellFor(const StereoParameters& parameters, std::uint32_t width) {
  if (parameters.hybridCell > 0) return parameters.hybridCell;
  return width >= kHybridCellWidth ? 2 : 1;
}

gpu::HybridConstants makeHybridConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height) {
  const gpu::StereoConstants stereo = makeSeedConstants(parameters, width, height);  // the crop rule of every method
  gpu::HybridConstants c{};
  c.maxSeparation = stereo.maxSeparation;
  c.zeroParallaxDistance = stereo.zeroParallaxDistance;
  c.cropBegin = stereo.cropBegin;
  c.cropEnd = stereo.cropEnd;
  c.width = int(width);
  c.height = int(height);
  // Parallax never exceeds maxSeparation (depth at or behind the zero-parallax plane; nearer surfaces are what
  // the comfort rules avoid): content farther than that plus a pixel cannot land on the pixel.
  c.windowPx = int(std::ceil(parameters.maxSeparation * float(width))) + 1;
  const std::uint64_t classified = std::uint64_t(std::max(c.cropEnd - c.cropBegin, 0)) * height;
  c.maskedPixelCap = hybridPixelCap(parameters.hybridBudget, classified);
  c.cell = hybridCellFor(parameters, width);
  c.minimumBin = int(gpu::hybridScoreBin(parameters.hybridScoreFloor));  // 0 without a floor
  // A gather base's taps (its choice of source is recomputed per pixel); the others land on the visible surface.
  const StereoParameters base = displacementParameters(parameters);
  if (base.method == StereoMethod::Seed || base.method == StereoMethod::Search) {
    const gpu::StereoConstants taps = makeStereoConstants(base, width, height);
    c.baseTapCount = taps.tapCount;
    for (int i = 0; i < taps.tapCount; ++i) c.baseTapOffsetPx[i] = taps.tapOffsetPx[i];
  }
  return c;
}

gpu::HybridConstants hybridGridConstants(const gpu::HybridConstants& image) {
  if (image.cell < 1) throw std::invalid_argument("hybrid classification: the cell must be at least one pixel");
  const int cell = image.cell;
  gpu::HybridConstants g = image;
  g.cell = 1;
  g.width = gpu::hybridGridSize(image.width, cell);
  g.height = gpu::hybridGridSize(image.height, cell);
  g.cropBegin = gpu::hybridGridCropBegin(image.cropBegin, cell);
  g.cropEnd = std::max(gpu::hybridGridCropEnd(image.cropEnd, cell), g.cropBegin);
  g.windowPx = int(std::ceil(image.maxSeparation * float(g.width))) + 1;
  for (int i = 0; i < image.baseTapCount; ++i)  // rounded half up: whole cells, as the taps are whole pixels
    g.baseTapOffsetPx[i] = (image.baseTapOffsetPx[i] + cell / 2) / cell;
  // The same share of the grid's classified cells as of the image's classified pixels (all of them at budget 1).
  const std::uint64_t pixels = std::uint64_t(std::max(image.cropEnd - image.cropBegin, 0)) * std::uint64_t(image.height);
  const std::uint64_t cells = std::uint64_t(g.cropEnd - g.cropBegin) * std::uint64_t(g.height);
  g.maskedPixelCap = pixels == 0 ? 0u
                     : image.maskedPixelCap >= pixels
                         ? std::uint32_t(cells)
                         : std::uint32_t(std::uint64_t(image.maskedPixelCap) * cells / pixels);
  return g;
}

DepthImage hybridGridDepthReference(const DepthImage& linearDepth, const gpu::HybridConstants& c) {
  if (int(linearDepth.width) != c.width || int(linearDepth.height) != c.height || c.cell < 1)
    throw std::invalid_argument("hybrid grid depth: depth size does not match the constants");
  const auto cell = std::uint32_t(c.cell);
  DepthImage grid(std::uint32_t(gpu::hybridGridSize(c.width, c.cell)), std::uint32_t(gpu::hybridGridSize(c.height, c.cell)));
  for (std::uint32_t gy = 0; gy < grid.height; ++gy)
    for (std::uint32_t gx = 0; gx < grid.width; ++gx) {
      float nearest = S3D_INFINITY;
      for (std::uint32_t y = gy * cell; y < std::min((gy + 1) * cell, linearDepth.height); ++y)
        for (std::uint32_t x = gx * cell; x < std::min((gx + 1) * cell, linearDepth.width); ++x)
          nearest = std::min(nearest, gpu::sanitizedDepth(*linearDepth.at(x, y), c.zeroParallaxDistance));
      *grid.at(gx, gy) = nearest;
    }
  return grid;
}

gpu::StereoConstants hybridBaseGatherConstants(const gpu::HybridConstants& c) {
  gpu::StereoConstants gather{};
  gather.tapCount = c.baseTapCount;
  gather.maxSeparation = c.maxSeparation;
  gather.zeroParallaxDistance = c.zeroParallaxDistance;
  gather.width = c.width;
  gather.height = c.height;
  std::copy_n(c.baseTapOffsetPx, c.baseTapCount, gather.tapOffsetPx);
  return gather;
}

std::uint32_t hybridPixelCap(float budget, std::uint64_t classifiedPixels) {
  if (!(budget >= 0.0f && budget <= 1.0f))
    throw std::invalid_argument("hybrid budget must be in [0, 1] (got " + numberText(budget) + ")");
  if (classifiedPixels > 0xffffffffu) throw std::invalid_argument("hybrid classification: too many pixels");
  // Integer cap, so budget 1 takes every pixel whatever the rounding of budget * total; the factor undoes the float
  // budget's representation error (at most 2^-24 relative: 0.02f * 550 is 10.9999997, meant as 11).
  return budget >= 1.0f ? std::uint32_t(classifiedPixels)
                        : std::uint32_t(std::floor(double(budget) * double(classifiedPixels) * (1.0 + 1e-7)));
}

std::vector<gpu::HybridCoverage> hybridRowCoverageReference(const DepthImage& linearDepth, int y, Eye eye,
                                                             const gpu::HybridConstants& c) {
  if (int(linearDepth.width) != c.width || int(linearDepth.height) != c.height || y < 0 || y >= c.height)
    throw std::invalid_argument("hybrid coverage: depth size or row does not match the constants");
  if (c.cell != 1) throw std::invalid_argument("hybrid coverage: the constants' cell is not one pixel (use hybridGridConstants)");
  auto sanitizedDepthAt = [&](int column) {
    return gpu::sanitizedDepth(*linearDepth.at(std::uint32_t(std::clamp(column, 0, c.width - 1)), std::uint32_t(y)),
                               c.zeroParallaxDistance);
  };
  const float direction = eye == Eye::Left ? 1.0f : -1.0f;
  const int width = c.width;
  const std::size_t n = std::size_t(width);
  std::vector<float> cover(n, S3D_INFINITY), hole(n, 0.0f), edge(n, 0.0f);
  std::vector<float> farthestEnd(n, -S3D_INFINITY), nearestStart(n, S3D_INFINITY);
  for (int i = -c.windowPx; i <= width + c.windowPx - 2; ++i) {
    const float dA = sanitizedDepthAt(i), dB = sanitizedDepthAt(i + 1);
    const float pA = gpu::hybridParallaxPx(dA, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const float pB = gpu::hybridParallaxPx(dB, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const gpu::HybridPair pair =
        gpu::hybridPair(float(i) - direction * pA, pA, dA, float(i + 1) - direction * pB, pB, dB);
    const glm::vec2 reach = gpu::hybridPairReach(pair);
    const int from = int(std::clamp(reach.x, 0.0f, float(width)));
    const int to = int(std::clamp(reach.y, -1.0f, float(width - 1)));
    for (int x = from; x <= to; ++x) {
      const gpu::HybridPairTerms terms = gpu::hybridPairTerms(pair, float(x));
      const std::size_t at = std::size_t(x);
      cover[at] = std::min(cover[at], terms.coverParallaxPx);
      hole[at] = std::max(hole[at], terms.holeJumpPx);
      edge[at] = std::max(edge[at], terms.edgeScore);
    }
    if (pair.edgeBase > 0.0f) {  // a pair between two surfaces: its landings for the nearest boundary
      const float start = std::ceil(pair.lo);  // the first pixel at or after lo: the pixels from here on have lo <= x
      if (start <= float(width - 1)) {
        const std::size_t at = std::size_t(std::max(start, 0.0f));
        farthestEnd[at] = std::max(farthestEnd[at], pair.hi);
      }
      if (start - 1.0f >= 0.0f) {  // the pixels up to start - 1 have lo > x
        const std::size_t at = std::size_t(std::min(start - 1.0f, float(width - 1)));
        nearestStart[at] = std::min(nearestStart[at], pair.lo);
      }
    }
  }
  for (std::size_t x = 1; x < n; ++x) farthestEnd[x] = std::max(farthestEnd[x], farthestEnd[x - 1]);
  for (std::size_t x = n - 1; x-- > 0;) nearestStart[x] = std::min(nearestStart[x], nearestStart[x + 1]);

  std::vector<gpu::HybridCoverage> coverage(n);
  for (std::size_t x = 0; x < n; ++x) {
    coverage[x].covered = cover[x] < S3D_INFINITY;
    coverage[x].visibleParallaxPx = cover[x];
    coverage[x].holeJumpPx = hole[x];
    coverage[x].edgeScore = edge[x];
    coverage[x].nearestChangePx = gpu::hybridChangeDistancePx(float(x), farthestEnd[x], nearestStart[x]);
  }
  return coverage;
}

namespace {

// Every eye pixel's score in row y: its coverage, and a gather base's own choice of source checked against it.
std::vector<float> rowScores(const DepthImage& linearDepth, int y, Eye eye, const gpu::HybridConstants& c) {
  auto depthAt = [&](int column) {
    return *linearDepth.at(std::uint32_t(std::clamp(column, 0, c.width - 1)), std::uint32_t(y));
  };
  auto parallaxAt = [&](int column) {
    return gpu::hybridParallaxPx(depthAt(column), c.maxSeparation, c.zeroParallaxDistance, c.width);
  };
  const float direction = eye == Eye::Left ? 1.0f : -1.0f;
  const gpu::StereoConstants gather = hybridBaseGatherConstants(c);
  const std::vector<gpu::HybridCoverage> coverage = hybridRowCoverageReference(linearDepth, y, eye, c);
  std::vector<float> scores(coverage.size(), 0.0f);
  for (int x = 0; x < c.width; ++x) {
    const std::size_t at = std::size_t(x);
    const float eyeX = float(x);
    float gatherError = 0.0f;
    if (c.baseTapCount > 0) {  // the gather's own choice of source
      const float u = gatherSourceColumn(linearDepth, x, y, eye, gather);
      const float base = std::floor(u);
      const float fraction = u - base;
      const float pLow = parallaxAt(int(base)), pHigh = parallaxAt(int(base) + 1);
      const float pNearest = fraction < 0.5f ? pLow : pHigh;
      const float landing = u - direction * pNearest;
      gatherError = gpu::hybridGatherErrorPx(coverage[at], pNearest, std::abs(landing - eyeX), pLow, pHigh, fraction);
    }
    scores[at] = gpu::hybridPixelScore(coverage[at], gatherError, c.windowPx);
  }
  return scores;
}

}  // namespace

float hybridPixelScoreReference(const DepthImage& linearDepth, int x, int y, Eye eye, const gpu::HybridConstants& c) {
  if (x < 0 || x >= c.width || y < 0 || y >= c.height) throw std::invalid_argument("hybrid score: pixel outside the image");
  return rowScores(linearDepth, y, eye, c)[std::size_t(x)];
}

HybridClassification classifyHybridReference(const DepthImage& linearDepth, const gpu::HybridConstants& image) {
  if (int(linearDepth.width) != image.width || int(linearDepth.height) != image.height)
    throw std::invalid_argument("hybrid classification: depth size does not match the constants");
  if (image.cell > 1) return classifyHybridReference(hybridGridDepthReference(linearDepth, image), hybridGridConstants(image));
  const gpu::HybridConstants& c = image;
  const std::size_t count = std::size_t(c.width) * std::size_t(c.height);
  HybridClassification result{std::vector<std::uint32_t>(count, 0u), std::vector<std::uint32_t>(count, 0u), {}, {}};
  for (int y = 0; y < c.height; ++y) {
    const std::vector<float> left = rowScores(linearDepth, y, Eye::Left, c);
    const std::vector<float> right = rowScores(linearDepth, y, Eye::Right, c);
    for (int x = c.cropBegin; x < c.cropEnd; ++x) {
      const std::size_t index = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      result.leftBins[index] = gpu::hybridScoreBin(left[std::size_t(x)]);
      result.rightBins[index] = gpu::hybridScoreBin(right[std::size_t(x)]);
      ++result.leftHistogram[result.leftBins[index]];
      ++result.rightHistogram[result.rightBins[index]];
    }
  }
  return result;
}

HybridThreshold hybridThreshold(const HybridHistogram& histogram, std::uint32_t maskedPixelCap, int minimumBin) {
  HybridThreshold threshold;
  const std::uint64_t classified = std::accumulate(histogram.begin(), histogram.end(), std::uint64_t(0));
  if (maskedPixelCap >= classified) return {0, classified, S3D_HYBRID_NO_PIXEL, 0};  // every pixel, whatever its score
  // Bin 0 (nothing expected wrong) and the bins below the floor are never masked below budget 1.
  const int lowest = std::max(minimumBin, 1);
  for (int bin = S3D_HYBRID_BINS - 1; bin >= lowest; --bin) {
    const std::uint64_t masked = threshold.maskedPixels + histogram[std::size_t(bin)];
    if (masked > maskedPixelCap) {  // the cap falls inside this bin: split its ties
      threshold.splitBin = bin;
      threshold.splitPixels = maskedPixelCap - threshold.maskedPixels;
      threshold.maskedPixels = maskedPixelCap;
      break;
    }
    threshold.bin = bin;
    threshold.maskedPixels = masked;
  }
  if (threshold.splitPixels == 0) threshold.splitBin = S3D_HYBRID_NO_PIXEL;
  return threshold;
}

std::vector<std::uint8_t> hybridMaskReference(const std::vector<std::uint32_t>& bins, const HybridThreshold& threshold,
                                              const gpu::HybridConstants& image) {
  const gpu::HybridConstants g = hybridGridConstants(image);
  if (bins.size() != std::size_t(g.width) * std::size_t(g.height))
    throw std::invalid_argument("hybrid mask: bins size does not match the constants");
  std::vector<std::uint8_t> mask(std::size_t(image.width) * std::size_t(image.height), 0);
  std::uint64_t split = 0;
  for (int gy = 0; gy < g.height; ++gy)
    for (int gx = g.cropBegin; gx < g.cropEnd; ++gx) {
      const int bin = int(bins[std::size_t(gy) * std::size_t(g.width) + std::size_t(gx)]);
      if (!(bin >= threshold.bin || (bin == threshold.splitBin && split++ < threshold.splitPixels))) continue;
      for (int y = gy * image.cell; y < std::min((gy + 1) * image.cell, image.height); ++y)  // the cell's pixels in the crop
        for (int x = std::max(gx * image.cell, image.cropBegin); x < std::min((gx + 1) * image.cell, image.cropEnd); ++x)
          mask[std::size_t(y) * std::size_t(image.width) + std::size_t(x)] = 1;
    }
  return mask;
}

}  // namespace s3d::stereo
