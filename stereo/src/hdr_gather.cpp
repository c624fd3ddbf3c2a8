#include "s3d/stereo/hdr_gather.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "row_sampling.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/iterative.h"

namespace s3d::stereo {

SourceColumns referenceSourceColumns(const DepthImage& linearDepth, const StereoParameters& parameters) {
  const std::uint32_t width = linearDepth.width, height = linearDepth.height;
  SourceColumns columns{std::vector<float>(linearDepth.pixelCount(), std::numeric_limits<float>::quiet_NaN()),
                        std::vector<float>(linearDepth.pixelCount(), std::numeric_limits<float>::quiet_NaN())};
  if (parameters.method == StereoMethod::Forward)  // holes take a mean: synthesizeHdrReference has its own path
    throw std::invalid_argument("referenceSourceColumns: the forward method has no single source column per pixel");
  if (parameters.method == StereoMethod::Iterative) {
    const gpu::IterativeConstants c = makeIterativeConstants(parameters, parameters.iterations, width, height);
    for (int y = 0; y < c.height; ++y)
      for (int x = c.cropBegin; x < c.cropEnd; ++x) {
        const std::size_t at = std::size_t(y) * width + std::size_t(x);
        columns.left[at] = solveIterativePixel(linearDepth, x, y, Eye::Left, c).sourcePosition;
        columns.right[at] = solveIterativePixel(linearDepth, x, y, Eye::Right, c).sourcePosition;
      }
    return columns;
  }
  const gpu::StereoConstants c = makeStereoConstants(parameters, width, height);
  for (int y = 0; y < c.height; ++y)
    for (int x = c.cropBegin; x < c.cropEnd; ++x) {
      const std::size_t at = std::size_t(y) * width + std::size_t(x);
      columns.left[at] = gatherSourceColumn(linearDepth, x, y, Eye::Left, c);
      columns.right[at] = gatherSourceColumn(linearDepth, x, y, Eye::Right, c);
    }
  return columns;
}

ImageRGBA32F gatherRows(const ImageRGBA32F& center, const std::vector<float>& sourceColumns) {
  if (sourceColumns.size() != center.pixelCount())
    throw std::invalid_argument("gatherRows: " + std::to_string(sourceColumns.size()) + " source columns for a " +
                                std::to_string(center.width) + "x" + std::to_string(center.height) + " image");
  ImageRGBA32F eye(center.width, center.height);
  for (std::uint32_t y = 0; y < center.height; ++y)
    for (std::uint32_t x = 0; x < center.width; ++x) {
      const float u = sourceColumns[std::size_t(y) * center.width + x];
      float* out = eye.at(x, y);
      if (std::isnan(u)) {
        out[0] = out[1] = out[2] = 0.0f;
        out[3] = 1.0f;
        continue;
      }
      // detail::sampleRow's arithmetic, on floats instead of unorm bytes.
      const float base = std::floor(u);
      const float fraction = u - base;
      const int last = int(center.width) - 1;
      const float* a = center.at(std::uint32_t(detail::clampInt(int(base), 0, last)), y);
      const float* b = center.at(std::uint32_t(detail::clampInt(int(base) + 1, 0, last)), y);
      for (int channel = 0; channel < 4; ++channel) out[channel] = a[channel] * (1.0f - fraction) + b[channel] * fraction;
    }
  return eye;
}

namespace {

// The forward method's samples (forward.h) applied to the HDR center: the same filter, or the same mean.
HdrStereoPair forwardHdr(const ImageRGBA32F& center, const DepthImage& linearDepth, const StereoParameters& parameters) {
  const gpu::ForwardConstants c = makeForwardConstants(parameters, linearDepth.width, linearDepth.height);
  std::vector<float> crop(center.pixelCount(), std::numeric_limits<float>::quiet_NaN());
  HdrStereoPair pair{gatherRows(center, crop), gatherRows(center, crop)};  // black, alpha 1
  for (int y = 0; y < c.height; ++y)
    for (auto [eye, direction] : {std::pair{&pair.left, 1.0f}, std::pair{&pair.right, -1.0f}}) {
      const std::vector<ForwardSample> samples = forwardRowSamples(linearDepth, y, direction, c);
      for (int x = c.cropBegin; x < c.cropEnd; ++x) {
        const ForwardSample& sample = samples[std::size_t(x)];
        float* out = eye->at(std::uint32_t(x), std::uint32_t(y));
        if (sample.fillCount == 0) {
          const float base = std::floor(sample.position), fraction = sample.position - base;
          const int last = c.width - 1;
          const float* a = center.at(std::uint32_t(detail::clampInt(int(base), 0, last)), std::uint32_t(y));
          const float* b = center.at(std::uint32_t(detail::clampInt(int(base) + 1, 0, last)), std::uint32_t(y));
          for (int channel = 0; channel < 4; ++channel) out[channel] = a[channel] * (1.0f - fraction) + b[channel] * fraction;
          continue;
        }
        for (int channel = 0; channel < 4; ++channel) out[channel] = 0.0f;
        for (int k = 0; k < sample.fillCount; ++k) {
          const float* texel = center.at(std::uint32_t(sample.fillFirst + k * sample.fillStep), std::uint32_t(y));
          for (int channel = 0; channel < 4; ++channel) out[channel] += texel[channel] / float(sample.fillCount);
        }
      }
    }
  return pair;
}

}  // namespace

HdrStereoPair synthesizeHdrReference(const ImageRGBA32F& centerHdr, const DepthImage& linearDepth,
                                     const StereoParameters& methodParameters) {
  const StereoParameters parameters = displacementParameters(methodParameters);  // a hybrid's displaced pixels
  requireSameSize(centerHdr, linearDepth, "HDR stereo (color vs depth)");
  if (parameters.method == StereoMethod::Forward) return forwardHdr(centerHdr, linearDepth, parameters);
  const SourceColumns columns = referenceSourceColumns(linearDepth, parameters);
  return {gatherRows(centerHdr, columns.left), gatherRows(centerHdr, columns.right)};
}

}  // namespace s3d::stereo
