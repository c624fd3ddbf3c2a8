#include "s3d/stereo/guard_band.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace s3d::stereo {

double maxDisplacement(double maxSeparation, double zeroParallaxDistance, double nearestDepth) {
  if (!(maxSeparation >= 0.0) || !(zeroParallaxDistance > 0.0) || !(nearestDepth > 0.0))
    throw std::invalid_argument("guard band: separation, zero-parallax distance and nearest depth must be positive");
  return maxSeparation * std::max(1.0, zeroParallaxDistance / nearestDepth - 1.0);
}

GuardBand guardBandFor(double maxSeparation, double zeroParallaxDistance, double nearestDepth, std::uint32_t width,
                       std::uint32_t maxRenderedWidth) {
  const double displacementPx = maxDisplacement(maxSeparation, zeroParallaxDistance, nearestDepth) * double(width);
  GuardBand band;
  // Double precision and a cap before the cast: a huge ratio zpp / nearest must not overflow the count.
  const double needed = displacementPx > 0.0 ? std::ceil(displacementPx) + 1.0 : 0.0;
  band.neededColumns = std::uint32_t(std::min(needed, 1.0e9));
  const std::uint32_t byRenderedWidth = maxRenderedWidth > width ? (maxRenderedWidth - width) / 2 : 0;
  band.columns = std::min({band.neededColumns, width / 2, byRenderedWidth});
  band.capped = band.columns < band.neededColumns;
  return band;
}

StereoParameters guardBandParameters(const StereoParameters& parameters, std::uint32_t width, const GuardBand& band) {
  StereoParameters wide = parameters;
  const double rendered = double(band.renderedWidth(width));
  wide.maxSeparation = float(double(parameters.maxSeparation) * double(width) / rendered);
  wide.edgeCrop = band.columns == 0 ? 0.0f : float((double(band.columns) - 0.5) / rendered);
  return wide;
}

std::vector<std::uint8_t> cropColumns(const std::vector<std::uint8_t>& mask, std::uint32_t rowWidth,
                                      std::uint32_t begin, std::uint32_t width) {
  if (rowWidth == 0 || mask.size() % rowWidth != 0 || begin + width > rowWidth)
    throw std::invalid_argument("cropColumns: mask and columns do not match");
  const std::size_t rows = mask.size() / rowWidth;
  std::vector<std::uint8_t> out(rows * width);
  for (std::size_t y = 0; y < rows; ++y)
    std::copy_n(mask.begin() + std::ptrdiff_t(y * rowWidth + begin), width, out.begin() + std::ptrdiff_t(y * width));
  return out;
}

}  // namespace s3d::stereo
