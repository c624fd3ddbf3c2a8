#include "s3d/stereo/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace s3d::stereo {
namespace {

constexpr int kShareThresholdLevels = 8;  // differences up to 8 levels are hard to see in a side-by-side flip
constexpr double kPeakLevel = 255.0;

void requireConsistentBuffer(const ImageRGBA8& image, const char* which) {
  if (image.pixels.size() != image.pixelCount() * ImageRGBA8::channels)
    throw std::invalid_argument(std::string("compareDisplayImages: ") + which + " pixel buffer holds " +
                                std::to_string(image.pixels.size()) + " values, expected " +
                                std::to_string(image.pixelCount() * ImageRGBA8::channels));
}

}  // namespace

namespace {

// Statistics over the cropped columns, restricted to the pixels whose mask value equals `wanted` (no mask:
// every pixel). An empty selection reports 0 pixels, no error and kMaxPsnrDb.
ErrorStats compareSelected(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                           const std::vector<std::uint8_t>* mask, std::uint8_t wanted) {
  requireSameSize(synthesized, reference, "compareDisplayImages");
  requireConsistentBuffer(synthesized, "synthesized");
  requireConsistentBuffer(reference, "reference");
  if (mask && mask->size() != synthesized.pixelCount())
    throw std::invalid_argument("compareDisplayImages: region mask size does not match the images");
  const std::uint32_t width = synthesized.width;
  // 64-bit so a huge crop cannot wrap around.
  if (std::uint64_t(cropColumns) * 2 >= width || synthesized.height == 0)
    throw std::invalid_argument("compareDisplayImages: cropping " + std::to_string(cropColumns) +
                                " columns from each side of a " + std::to_string(width) + "x" +
                                std::to_string(synthesized.height) + " image leaves no pixels to compare");

  const std::uint32_t firstColumn = cropColumns;
  const std::uint32_t endColumn = width - cropColumns;
  std::uint64_t sumSquared = 0;  // exact integer sums: no drift on large images
  std::uint64_t sumAbsolute = 0;
  std::uint64_t pixelsAboveThreshold = 0;
  std::uint64_t pixelCount = 0;
  for (std::uint32_t y = 0; y < synthesized.height; ++y) {
    for (std::uint32_t x = firstColumn; x < endColumn; ++x) {
      if (mask && (*mask)[std::size_t(y) * width + x] != wanted) continue;
      const std::uint8_t* a = synthesized.at(x, y);
      const std::uint8_t* b = reference.at(x, y);
      int largest = 0;
      for (int c = 0; c < 3; ++c) {
        const int difference = std::abs(int(a[c]) - int(b[c]));
        sumAbsolute += std::uint64_t(difference);
        sumSquared += std::uint64_t(difference * difference);
        largest = std::max(largest, difference);
      }
      if (largest > kShareThresholdLevels) ++pixelsAboveThreshold;
      ++pixelCount;
    }
  }
  if (pixelCount == 0) return ErrorStats{kMaxPsnrDb, 0.0, 0.0, 0};

  const double samples = 3.0 * double(pixelCount);
  const double meanSquaredError = double(sumSquared) / samples;
  const double psnr = meanSquaredError == 0.0
                          ? kMaxPsnrDb
                          : std::min(kMaxPsnrDb, 10.0 * std::log10(kPeakLevel * kPeakLevel / meanSquaredError));
  return ErrorStats{psnr, double(sumAbsolute) / samples, double(pixelsAboveThreshold) / double(pixelCount),
                    pixelCount};
}

bool isDepthEdge(float a, float b) {
  if (std::isinf(a) != std::isinf(b)) return true;  // surface against sky
  if (std::isinf(a)) return false;
  return std::abs(a - b) > kDepthEdgeRelativeJump * std::min(a, b);
}

}  // namespace

ErrorStats compareDisplayImages(const ImageRGBA8& synthesized, const ImageRGBA8& reference,
                                std::uint32_t cropColumns) {
  return compareSelected(synthesized, reference, cropColumns, nullptr, 0);
}

std::vector<std::uint8_t> haloMask(const DepthImage& centerDepth, std::uint32_t radiusPx) {
  const std::uint32_t width = centerDepth.width;
  std::vector<std::uint8_t> mask(centerDepth.pixelCount(), 0);
  for (std::uint32_t y = 0; y < centerDepth.height; ++y) {
    for (std::uint32_t x = 0; x + 1 < width; ++x) {
      if (!isDepthEdge(*centerDepth.at(x, y), *centerDepth.at(x + 1, y))) continue;
      // Mark every column within radiusPx of the edge between x and x + 1.
      const std::uint32_t begin = x + 1 > radiusPx ? x + 1 - radiusPx : 0;
      const std::uint32_t end = std::min(width, x + 1 + radiusPx);
      std::fill(mask.begin() + std::ptrdiff_t(std::size_t(y) * width + begin),
                mask.begin() + std::ptrdiff_t(std::size_t(y) * width + end), std::uint8_t(1));
    }
  }
  return mask;
}

RegionErrors compareByRegion(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                             const std::vector<std::uint8_t>& halo) {
  return {compareSelected(synthesized, reference, cropColumns, nullptr, 0),
          compareSelected(synthesized, reference, cropColumns, &halo, 1),
          compareSelected(synthesized, reference, cropColumns, &halo, 0)};
}

ErrorStats compareWithinMask(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                             const std::vector<std::uint8_t>& mask) {
  return compareSelected(synthesized, reference, cropColumns, &mask, 1);
}

std::vector<std::uint8_t> disocclusionMask(const DepthImage& referenceDepth, const DepthImage& centerDepth,
                                           float maxSeparation, float zeroParallaxDistance, Eye eye) {
  requireSameSize(referenceDepth, centerDepth, "disocclusionMask");
  const float width = float(referenceDepth.width);
  const float sign = eye == Eye::Left ? 1.0f : -1.0f;  // the left eye shows center content from x + p W
  std::vector<std::uint8_t> mask(referenceDepth.pixelCount(), 0);
  for (std::uint32_t y = 0; y < referenceDepth.height; ++y)
    for (std::uint32_t x = 0; x < referenceDepth.width; ++x) {
      const float depth = *referenceDepth.at(x, y);
      const float parallax = gpu::parallaxFromDepth(maxSeparation, zeroParallaxDistance, gpu::sanitizedDepth(depth, zeroParallaxDistance));
      const long centerX = std::lround(float(x) + sign * parallax * width);
      bool seen = false;
      if (centerX >= 0 && centerX < long(referenceDepth.width)) {
        const float centerDepthHere = *centerDepth.at(std::uint32_t(centerX), y);
        seen = std::isinf(depth) ? std::isinf(centerDepthHere)
                                 : std::abs(centerDepthHere - depth) <= kSameSurfaceRelativeDepth * depth;
      }
      mask[std::size_t(y) * referenceDepth.width + x] = seen ? 0 : 1;
    }
  return mask;
}

ImageRGBA8 makeErrorHeatMap(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                            int fullScaleLevels) {
  requireSameSize(synthesized, reference, "makeErrorHeatMap");
  if (fullScaleLevels < 1) throw std::invalid_argument("makeErrorHeatMap: fullScaleLevels must be >= 1");
  // Piecewise-linear ramp through these colors at error fractions 0, 1/4, 1/2, 3/4 and 1.
  static constexpr float kRamp[5][3] = {{0, 0, 0}, {0, 0, 255}, {255, 0, 0}, {255, 255, 0}, {255, 255, 255}};
  ImageRGBA8 heat(synthesized.width, synthesized.height);
  for (std::uint32_t y = 0; y < heat.height; ++y)
    for (std::uint32_t x = 0; x < heat.width; ++x) {
      std::uint8_t* out = heat.at(x, y);
      out[3] = 255;
      if (x < cropColumns || x + cropColumns >= heat.width) continue;
      int largest = 0;
      for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(synthesized.at(x, y)[c]) - int(reference.at(x, y)[c])));
      const float position = std::min(1.0f, float(largest) / float(fullScaleLevels)) * 4.0f;
      const int segment = std::min(3, int(position));
      const float t = position - float(segment);
      for (int c = 0; c < 3; ++c)
        out[c] = std::uint8_t(std::lround(kRamp[segment][c] + (kRamp[segment + 1][c] - kRamp[segment][c]) * t));
    }
  return heat;
}

}  // namespace s3d::stereo
