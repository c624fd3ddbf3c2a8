#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_base_depth.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

std::array<DepthImage, 2> hybridBaseDepthReference(const DepthImage& linearDepth, const DepthImage& deviceDepth,
                                                   const gpu::HybridConstants& c) {
  if (c.baseTapCount <= 0) throw std::invalid_argument("hybrid base depth: the base is no gather (seed or search)");
  for (const DepthImage* image : {&linearDepth, &deviceDepth})
    if (int(image->width) != c.width || int(image->height) != c.height)
      throw std::invalid_argument("hybrid base depth: an image's size does not match the constants");
  const gpu::StereoConstants gather = hybridBaseGatherConstants(c);
  std::array<DepthImage, 2> eyes{DepthImage(linearDepth.width, linearDepth.height),
                                 DepthImage(linearDepth.width, linearDepth.height)};
  for (const Eye eye : {Eye::Left, Eye::Right}) {
    DepthImage& out = eyes[eye == Eye::Left ? 0 : 1];
    for (std::uint32_t y = 0; y < out.height; ++y)
      for (std::uint32_t x = 0; x < out.width; ++x) {
        const float column = gatherSourceColumn(linearDepth, int(x), int(y), eye, gather);
        const float base = std::floor(column);
        const int texel = std::clamp(int(base) + (column - base < 0.5f ? 0 : 1), 0, c.width - 1);
        out.at(x, y)[0] = deviceDepth.at(std::uint32_t(texel), y)[0];
      }
  }
  return eyes;
}

}  // namespace s3d::stereo
