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
  // the comfort rules avoid): a step farther than that plus a pixel cannot land on the pixel.
  c.windowPx = int(std::ceil(parameters.maxSeparation * float(width))) + 1;
  c.thresholdBin = S3D_HYBRID_NO_PIXEL;
  return c;
}

HybridClassification classifyHybridReference(const DepthImage& linearDepth, const gpu::HybridConstants& c) {
  if (int(linearDepth.width) != c.width || int(linearDepth.height) != c.height)
    throw std::invalid_argument("hybrid classification: depth size does not match the constants");
  const std::size_t count = std::size_t(c.width) * std::size_t(c.height);
  HybridClassification result{std::vector<std::uint32_t>(count, 0u), std::vector<std::uint32_t>(count, 0u), {}, {}};
  std::vector<float> parallax(std::size_t(c.width));
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x)
      parallax[std::size_t(x)] = gpu::hybridParallaxPx(*linearDepth.at(std::uint32_t(x), std::uint32_t(y)),
                                                       c.maxSeparation, c.zeroParallaxDistance, c.width);
    auto at = [&](int x) { return parallax[std::size_t(std::clamp(x, 0, c.width - 1))]; };
    for (int x = c.cropBegin; x < c.cropEnd; ++x) {
      float leftScore = 0.0f, rightScore = 0.0f;
      const float eyeX = float(x);
      for (int i = x - c.windowPx; i < x + c.windowPx; ++i) {
        const float previous = at(i), next = at(i + 1);
        const float jump = std::abs(next - previous);
        leftScore = std::max(leftScore, gpu::hybridStepScore(eyeX, float(i) - previous, float(i + 1) - next, jump));
        rightScore = std::max(rightScore, gpu::hybridStepScore(eyeX, float(i) + previous, float(i + 1) + next, jump));
      }
      const std::size_t index = std::size_t(y) * std::size_t(c.width) + std::size_t(x);
      result.leftBins[index] = gpu::hybridScoreBin(leftScore);
      result.rightBins[index] = gpu::hybridScoreBin(rightScore);
      ++result.leftHistogram[result.leftBins[index]];
      ++result.rightHistogram[result.rightBins[index]];
    }
  }
  return result;
}

HybridThreshold hybridThreshold(const HybridHistogram& histogram, float budget) {
  if (!(budget >= 0.0f && budget <= 1.0f))
    throw std::invalid_argument("hybrid budget must be in [0, 1] (got " + numberText(budget) + ")");
  const std::uint64_t total = std::accumulate(histogram.begin(), histogram.end(), std::uint64_t(0));
  // Integer cap, so budget 1 takes every pixel whatever the rounding of budget * total.
  const std::uint64_t cap = budget >= 1.0f ? total : std::uint64_t(std::floor(double(budget) * double(total)));
  HybridThreshold threshold;
  for (int bin = S3D_HYBRID_BINS - 1; bin >= 0; --bin) {
    const std::uint64_t masked = threshold.maskedPixels + histogram[std::size_t(bin)];
    if (masked > cap) break;
    threshold = {bin, masked};
  }
  return threshold;
}

void compositeHybridReference(ImageRGBA8& eye, const ImageRGBA8& rendered, const std::vector<std::uint32_t>& bins,
                              const gpu::HybridConstants& c) {
  requireSameSize(eye, rendered, "hybrid composite (eye vs rendered eye)");
  if (int(eye.width) != c.width || int(eye.height) != c.height || bins.size() != eye.pixels.size() / 4)
    throw std::invalid_argument("hybrid composite: image or bins size does not match the constants");
  for (int y = 0; y < c.height; ++y)
    for (int x = c.cropBegin; x < c.cropEnd; ++x)
      if (int(bins[std::size_t(y) * std::size_t(c.width) + std::size_t(x)]) >= c.thresholdBin)
        std::copy_n(rendered.at(std::uint32_t(x), std::uint32_t(y)), 4, eye.at(std::uint32_t(x), std::uint32_t(y)));
}

}  // namespace s3d::stereo
