#pragma once
// Guard band: the center view rendered wider than the output, so every eye pixel's source column lies inside
// it and both eyes are full frame (docs/DESIGN.md "Guard band"). The stereo pass runs unchanged on the wide
// image with the separation rescaled to the wide width; the eyes are its middle columns.
#include <cstdint>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// Largest |parallax| (fraction of the output width) of any depth in [nearestDepth, +inf):
// m (1 - zpp / d) runs from m (1 - zpp / nearest) to m (sky), so the bound is m max(1, zpp / nearest - 1).
double maxDisplacement(double maxSeparation, double zeroParallaxDistance, double nearestDepth);

struct GuardBand {
  std::uint32_t columns = 0;        // per side
  std::uint32_t neededColumns = 0;  // per side, before the cap
  bool capped = false;              // columns < neededColumns: the outermost eye columns clamp to the band's edge
  std::uint32_t renderedWidth(std::uint32_t outputWidth) const { return outputWidth + 2 * columns; }
};

// Columns per side: ceil(maxDisplacement * width) plus one for the bilinear filter's right-hand texel (0 when
// nothing moves), capped at half the output width per side (the pass's largest crop, kMaxSeparationLimit of the
// rendered width) and at a rendered width of maxRenderedWidth.
GuardBand guardBandFor(double maxSeparation, double zeroParallaxDistance, double nearestDepth, std::uint32_t width,
                       std::uint32_t maxRenderedWidth);

// The parameters that give the wide image the same parallax in pixels (maxSeparation * width / renderedWidth)
// and crop exactly the band (edgeCrop (columns - 1/2) / renderedWidth, which ceil() maps to `columns`).
StereoParameters guardBandParameters(const StereoParameters& parameters, std::uint32_t width, const GuardBand& band);

// Columns [begin, begin + width) of an image or of a per-pixel mask of the given row width.
template <typename Channel, int N>
Image<Channel, N> cropColumns(const Image<Channel, N>& image, std::uint32_t begin, std::uint32_t width) {
  if (begin + width > image.width) throw std::invalid_argument("cropColumns: columns outside the image");
  Image<Channel, N> out(width, image.height);
  for (std::uint32_t y = 0; y < image.height; ++y)
    std::copy(image.at(begin, y), image.at(begin, y) + std::size_t(width) * N, out.at(0, y));
  return out;
}
std::vector<std::uint8_t> cropColumns(const std::vector<std::uint8_t>& mask, std::uint32_t rowWidth,
                                      std::uint32_t begin, std::uint32_t width);

}  // namespace s3d::stereo
