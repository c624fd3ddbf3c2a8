#pragma once
// The stereo methods applied to the linear HDR center view, for measuring the error in linear HDR:
// the GPU pass filters display-encoded RGBA8, but where each eye pixel comes from depends on depth only, so
// the C++ reference's source columns (the math the GPU pass is held to) gather the HDR color the same way.
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// Per pixel of each eye, the fractional center-view column its color is filtered from, as
// parameters.method's C++ reference computes it; NaN in the cropped border columns. Not for the forward
// method (its holes take a mean of texels; std::invalid_argument), which synthesizeHdrReference handles itself.
struct SourceColumns {
  std::vector<float> left;
  std::vector<float> right;
};
SourceColumns referenceSourceColumns(const DepthImage& linearDepth, const StereoParameters& parameters);

// Each pixel filtered from the center's row at its source column with the shaders' horizontal linear filter
// (clamped to the edge); NaN columns (the crop) give black with alpha 1, as the pass writes them.
ImageRGBA32F gatherRows(const ImageRGBA32F& center, const std::vector<float>& sourceColumns);

struct HdrStereoPair {
  ImageRGBA32F left;
  ImageRGBA32F right;
};
// Both eyes of the linear HDR center view (same size as the depth) by parameters.method (a hybrid: its base).
HdrStereoPair synthesizeHdrReference(const ImageRGBA32F& centerHdr, const DepthImage& linearDepth,
                                     const StereoParameters& parameters);

}  // namespace s3d::stereo
