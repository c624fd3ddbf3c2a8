#include "s3d/stereo/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace s3d::stereo {
namespace {

constexpr int kShareThresholdLevels = 8;  // differences up to 8 levels are hard to see in a side-by-side flip
constexpr double kPeakLevel = 255.0;

template <typename Image>
void requireConsistentBuffer(const Image& image, const char* which) {
  if (image.pixels.size() != image.pixelCount() * Image::channels)
    throw std::invalid_argument(std::string("compareDisplayImages: ") + which + " pixel buffer holds " +
                                std::to_string(image.pixels.size()) + " values, expected " +
                                std::to_string(image.pixelCount() * Image::channels));
}

}  // namespace

namespace {

// Checks shared by every comparison: same size, consistent buffers, mask size, and a crop that leaves pixels.
template <typename Image>
void requireComparable(const Image& synthesized, const Image& reference, std::uint32_t cropColumns,
                       const std::vector<std::uint8_t>* mask) {
  requireSameSize(synthesized, reference, "compareDisplayImages");
  requireConsistentBuffer(synthesized, "synthesized");
  requireConsistentBuffer(reference, "reference");
  if (mask && mask->size() != synthesized.pixelCount())
    throw std::invalid_argument("compareDisplayImages: region mask size does not match the images");
  // 64-bit so a huge crop cannot wrap around.
  if (std::uint64_t(cropColumns) * 2 >= synthesized.width || synthesized.height == 0)
    throw std::invalid_argument("compareDisplayImages: cropping " + std::to_string(cropColumns) +
                                " columns from each side of a " + std::to_string(synthesized.width) + "x" +
                                std::to_string(synthesized.height) + " image leaves no pixels to compare");
}

double displayLuma(const std::uint8_t* p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }  // BT.601
double hdrLuminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }     // BT.709

// SSIM map over the compared area from the luma of both images (see ssimMap in metrics.h). The Gaussian window
// is separable, and so is its cut at the area's borders: each 1-D pass divides by the weights it used.
template <typename Image, typename Luma>
std::vector<float> ssimMapOf(const Image& synthesized, const Image& reference, std::uint32_t cropColumns,
                             double dynamicRange, Luma luma) {
  requireComparable(synthesized, reference, cropColumns, nullptr);
  constexpr int radius = kSsimWindowRadius;
  std::array<double, 2 * radius + 1> weight{};
  for (int k = -radius; k <= radius; ++k)
    weight[std::size_t(k + radius)] = std::exp(-double(k * k) / (2.0 * kSsimGaussianSigma * kSsimGaussianSigma));
  const int width = int(synthesized.width) - 2 * int(cropColumns);  // the compared area's columns
  const int height = int(synthesized.height);
  const std::size_t areaPixels = std::size_t(width) * std::size_t(height);
  // Moments x, y, x^2, y^2, xy, filtered along rows.
  std::array<std::vector<double>, 5> rows;
  for (std::vector<double>& plane : rows) plane.assign(areaPixels, 0.0);
  std::vector<double> x(static_cast<std::size_t>(width)), y(static_cast<std::size_t>(width));
  for (int r = 0; r < height; ++r) {
    for (int i = 0; i < width; ++i) {
      x[std::size_t(i)] = luma(synthesized.at(std::uint32_t(i) + cropColumns, std::uint32_t(r)));
      y[std::size_t(i)] = luma(reference.at(std::uint32_t(i) + cropColumns, std::uint32_t(r)));
    }
    for (int i = 0; i < width; ++i) {
      std::array<double, 5> sum{};
      double weightSum = 0.0;
      for (int k = std::max(-radius, -i); k <= std::min(radius, width - 1 - i); ++k) {
        const double w = weight[std::size_t(k + radius)];
        const double a = x[std::size_t(i + k)], b = y[std::size_t(i + k)];
        sum[0] += w * a, sum[1] += w * b, sum[2] += w * a * a, sum[3] += w * b * b, sum[4] += w * a * b;
        weightSum += w;
      }
      for (std::size_t m = 0; m < 5; ++m) rows[m][std::size_t(r) * std::size_t(width) + std::size_t(i)] = sum[m] / weightSum;
    }
  }
  const double c1 = (kSsimK1 * dynamicRange) * (kSsimK1 * dynamicRange);
  const double c2 = (kSsimK2 * dynamicRange) * (kSsimK2 * dynamicRange);
  std::vector<float> map(synthesized.pixelCount(), 0.0f);
  for (int r = 0; r < height; ++r)
    for (int i = 0; i < width; ++i) {
      std::array<double, 5> mean{};
      double weightSum = 0.0;
      for (int k = std::max(-radius, -r); k <= std::min(radius, height - 1 - r); ++k) {
        const double w = weight[std::size_t(k + radius)];
        const std::size_t at = std::size_t(r + k) * std::size_t(width) + std::size_t(i);
        for (std::size_t m = 0; m < 5; ++m) mean[m] += w * rows[m][at];
        weightSum += w;
      }
      for (double& value : mean) value /= weightSum;
      const double muX = mean[0], muY = mean[1];
      const double varianceX = mean[2] - muX * muX, varianceY = mean[3] - muY * muY, covariance = mean[4] - muX * muY;
      const double ssim = ((2.0 * muX * muY + c1) * (2.0 * covariance + c2)) /
                          ((muX * muX + muY * muY + c1) * (varianceX + varianceY + c2));
      map[std::size_t(r) * synthesized.width + std::size_t(i) + cropColumns] = float(ssim);
    }
  return map;
}

// HDR statistics over the cropped columns where the mask equals `wanted` (no mask: every pixel).
HdrErrorStats compareHdrSelected(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference,
                                 std::uint32_t cropColumns, const std::vector<std::uint8_t>* mask, std::uint8_t wanted,
                                 const std::vector<float>& ssim) {
  requireComparable(synthesized, reference, cropColumns, mask);
  const std::uint32_t width = synthesized.width;
  double sumSquared = 0.0, sumAbsolute = 0.0, sumSsim = 0.0;
  std::uint64_t pixelCount = 0;
  for (std::uint32_t y = 0; y < synthesized.height; ++y)
    for (std::uint32_t x = cropColumns; x < width - cropColumns; ++x) {
      if (mask && (*mask)[std::size_t(y) * width + x] != wanted) continue;
      const float* a = synthesized.at(x, y);
      const float* b = reference.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double difference = double(a[c]) - double(b[c]);
        sumSquared += difference * difference;
        sumAbsolute += std::abs(difference);
      }
      sumSsim += double(ssim[std::size_t(y) * width + x]);
      ++pixelCount;
    }
  HdrErrorStats stats;
  stats.pixelCount = pixelCount;
  if (pixelCount == 0) return stats;
  const double samples = 3.0 * double(pixelCount);
  const double meanSquaredError = sumSquared / samples;
  stats.psnrDb = meanSquaredError == 0.0 ? kMaxPsnrDb
                                         : std::min(kMaxPsnrDb, 10.0 * std::log10(kHdrPeak * kHdrPeak / meanSquaredError));
  stats.meanAbsoluteError = sumAbsolute / samples;
  stats.ssim = sumSsim / double(pixelCount);
  return stats;
}

// 1 where no region mask is set (an empty mask sets nothing).
std::vector<std::uint8_t> restMask(std::size_t pixelCount, const RegionMasks& masks) {
  std::vector<std::uint8_t> rest(pixelCount, 1);
  for (const std::vector<std::uint8_t>* mask : {&masks.halo, &masks.disocclusion, &masks.transparent, &masks.foliage}) {
    if (mask->empty()) continue;
    if (mask->size() != pixelCount)
      throw std::invalid_argument("compareByRegion: region mask size does not match the images");
    for (std::size_t i = 0; i < pixelCount; ++i)
      if ((*mask)[i] != 0) rest[i] = 0;
  }
  return rest;
}

// Statistics over the cropped columns, restricted to the pixels whose mask value equals `wanted` (no mask:
// every pixel). An empty selection reports 0 pixels, no error, kMaxPsnrDb and SSIM 1.
// `ssim`: the ssimMap of the two images (computed here when null).
ErrorStats compareSelected(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                           const std::vector<std::uint8_t>* mask, std::uint8_t wanted,
                           const std::vector<float>* ssim = nullptr) {
  requireComparable(synthesized, reference, cropColumns, mask);
  const std::uint32_t width = synthesized.width;
  std::vector<float> ownSsim;
  if (!ssim) {
    ownSsim = ssimMap(synthesized, reference, cropColumns);
    ssim = &ownSsim;
  }
  const std::uint32_t firstColumn = cropColumns;
  const std::uint32_t endColumn = width - cropColumns;
  double sumSsim = 0.0;
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
      sumSsim += double((*ssim)[std::size_t(y) * width + x]);
      ++pixelCount;
    }
  }
  if (pixelCount == 0) return ErrorStats{kMaxPsnrDb, 0.0, 0.0, 0, 1.0};

  const double samples = 3.0 * double(pixelCount);
  const double meanSquaredError = double(sumSquared) / samples;
  const double psnr = meanSquaredError == 0.0
                          ? kMaxPsnrDb
                          : std::min(kMaxPsnrDb, 10.0 * std::log10(kPeakLevel * kPeakLevel / meanSquaredError));
  return ErrorStats{psnr, double(sumAbsolute) / samples, double(pixelsAboveThreshold) / double(pixelCount),
                    pixelCount, sumSsim / double(pixelCount)};
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

std::vector<float> ssimMap(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns) {
  return ssimMapOf(synthesized, reference, cropColumns, 255.0, displayLuma);
}

std::vector<float> ssimMap(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference, std::uint32_t cropColumns) {
  return ssimMapOf(synthesized, reference, cropColumns, kHdrPeak, hdrLuminance);
}

HdrErrorStats compareHdrImages(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference,
                               std::uint32_t cropColumns) {
  return compareHdrSelected(synthesized, reference, cropColumns, nullptr, 0, ssimMap(synthesized, reference, cropColumns));
}

ErrorsByRegion<ErrorStats> compareDisplayByRegion(const ImageRGBA8& synthesized, const ImageRGBA8& reference,
                                                  std::uint32_t cropColumns, const RegionMasks& masks) {
  const std::vector<float> ssim = ssimMap(synthesized, reference, cropColumns);  // once for every region
  const std::vector<std::uint8_t> rest = restMask(synthesized.pixelCount(), masks);
  auto region = [&](const std::vector<std::uint8_t>& mask) {
    if (mask.empty()) return ErrorStats{kMaxPsnrDb, 0.0, 0.0, 0, 1.0};
    return compareSelected(synthesized, reference, cropColumns, &mask, 1, &ssim);
  };
  return {compareSelected(synthesized, reference, cropColumns, nullptr, 0, &ssim), region(masks.halo),
          region(masks.disocclusion), region(masks.transparent), region(rest), region(masks.foliage)};
}

ErrorsByRegion<HdrErrorStats> compareHdrByRegion(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference,
                                                 std::uint32_t cropColumns, const RegionMasks& masks) {
  const std::vector<float> ssim = ssimMap(synthesized, reference, cropColumns);
  const std::vector<std::uint8_t> rest = restMask(synthesized.pixelCount(), masks);
  auto region = [&](const std::vector<std::uint8_t>& mask) {
    if (mask.empty()) return HdrErrorStats{};
    return compareHdrSelected(synthesized, reference, cropColumns, &mask, 1, ssim);
  };
  return {compareHdrSelected(synthesized, reference, cropColumns, nullptr, 0, ssim), region(masks.halo),
          region(masks.disocclusion), region(masks.transparent), region(rest), region(masks.foliage)};
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
