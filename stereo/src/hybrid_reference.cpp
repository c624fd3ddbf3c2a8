#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "s3d/number_text.h"
#include "s3d/stereo/hybrid.h"

namespace s3d::stereo {

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
  // A gather base's taps (its choice of source is recomputed per pixel); the others land on the visible surface.
  const StereoParameters base = displacementParameters(parameters);
  if (base.method == StereoMethod::Seed || base.method == StereoMethod::Search) {
    const gpu::StereoConstants taps = makeStereoConstants(base, width, height);
    c.baseTapCount = taps.tapCount;
    for (int i = 0; i < taps.tapCount; ++i) c.baseTapOffsetPx[i] = taps.tapOffsetPx[i];
  }
  return c;
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

float hybridPixelScoreReference(const DepthImage& linearDepth, int x, int y, Eye eye, const gpu::HybridConstants& c) {
  auto depthAt = [&](int column) {
    return *linearDepth.at(std::uint32_t(std::clamp(column, 0, c.width - 1)), std::uint32_t(y));
  };
  auto parallaxAt = [&](int column) {
    return gpu::hybridParallaxPx(depthAt(column), c.maxSeparation, c.zeroParallaxDistance, c.width);
  };
  const float direction = eye == Eye::Left ? 1.0f : -1.0f;
  const float eyeX = float(x);
  gpu::HybridCoverage coverage = gpu::hybridCoverageBegin();
  auto sanitizedDepthAt = [&](int column) { return gpu::sanitizedDepth(depthAt(column), c.zeroParallaxDistance); };
  float dA = sanitizedDepthAt(x - c.windowPx);
  float pA = gpu::hybridParallaxPx(dA, c.maxSeparation, c.zeroParallaxDistance, c.width);
  for (int i = x - c.windowPx; i < x + c.windowPx; ++i) {
    const float dB = sanitizedDepthAt(i + 1);
    const float pB = gpu::hybridParallaxPx(dB, c.maxSeparation, c.zeroParallaxDistance, c.width);
    const float landA = float(i) - direction * pA;
    const float landB = float(i + 1) - direction * pB;
    coverage = gpu::hybridConsiderColumns(coverage, eyeX, landA, pA, dA, landB, pB, dB);
    dA = dB;
    pA = pB;
  }
  float gatherError = 0.0f;
  if (c.baseTapCount > 0) {  // the gather's own choice: the nearest depth over its taps (stereo_reference.cpp)
    float minDepth = S3D_INFINITY;
    for (int t = 0; t < c.baseTapCount; ++t)
      minDepth = std::min(minDepth, gpu::sanitizedDepth(depthAt(x + int(direction) * c.baseTapOffsetPx[t]),
                                                        c.zeroParallaxDistance));
    const float u =
        float(x) + direction * (gpu::parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, minDepth) * float(c.width));
    const float base = std::floor(u);
    const float fraction = u - base;
    const float pLow = parallaxAt(int(base)), pHigh = parallaxAt(int(base) + 1);
    const float pNearest = fraction < 0.5f ? pLow : pHigh;
    const float landing = u - direction * pNearest;
    gatherError = gpu::hybridGatherErrorPx(coverage, pNearest, std::abs(landing - eyeX), pLow, pHigh, fraction);
  }
  return gpu::hybridPixelScore(coverage, gatherError, c.windowPx);
}

HybridClassification classifyHybridReference(const DepthImage& linearDepth, const gpu::HybridConstants& c) {
  if (int(linearDepth.width) != c.width || int(linearDepth.height) != c.height)
    throw std::invalid_argument("hybrid classification: depth size does not match the constants");
  const std::size_t count = std::size_t(c.width) * std::size_t(c.height);
  HybridClassification result{std::vector<std::uint32_t>(count, 0u), std::vector<std::uint32_t>(count, 0u), {}, {}};
  for (int y = 0; y < c.height; ++y)
    for (int x = c.cropBegin; x < c.cropEnd; ++x) {
      const std::size_t index = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      result.leftBins[index] = gpu::hybridScoreBin(hybridPixelScoreReference(linearDepth, x, y, Eye::Left, c));
      result.rightBins[index] = gpu::hybridScoreBin(hybridPixelScoreReference(linearDepth, x, y, Eye::Right, c));
      ++result.leftHistogram[result.leftBins[index]];
      ++result.rightHistogram[result.rightBins[index]];
    }
  return result;
}

HybridThreshold hybridThreshold(const HybridHistogram& histogram, std::uint32_t maskedPixelCap) {
  HybridThreshold threshold;
  for (int bin = S3D_HYBRID_BINS - 1; bin >= 0; --bin) {
    const std::uint64_t masked = threshold.maskedPixels + histogram[std::size_t(bin)];
    if (masked > maskedPixelCap) break;
    threshold = {bin, masked};
  }
  return threshold;
}

std::vector<std::uint8_t> hybridMaskReference(const std::vector<std::uint32_t>& bins, int thresholdBin,
                                              const gpu::HybridConstants& c) {
  if (bins.size() != std::size_t(c.width) * std::size_t(c.height))
    throw std::invalid_argument("hybrid mask: bins size does not match the constants");
  std::vector<std::uint8_t> mask(bins.size(), 0);
  for (int y = 0; y < c.height; ++y)
    for (int x = c.cropBegin; x < c.cropEnd; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      mask[i] = int(bins[i]) >= thresholdBin ? 1 : 0;
    }
  return mask;
}

}  // namespace s3d::stereo
