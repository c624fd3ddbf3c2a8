#include "s3d/stereo/eye_comparison.h"

#include <cmath>

namespace s3d::stereo {

std::vector<std::uint8_t> haloMaskFor(const DepthImage& centerDepth, const StereoParameters& parameters) {
  return haloMask(centerDepth, std::uint32_t(std::ceil(parameters.maxSeparation * float(centerDepth.width))));
}

std::vector<std::uint8_t> disocclusionMaskFor(const DepthImage& referenceDepth, const DepthImage& centerDepth,
                                              const StereoParameters& parameters, Eye eye) {
  return disocclusionMask(referenceDepth, centerDepth, parameters.maxSeparation, parameters.zeroParallaxDistance, eye);
}

EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const RegionMasks& masks, const ImageRGBA32F* synthesizedHdr,
                    const ImageRGBA32F* referenceHdr) {
  const ErrorsByRegion<ErrorStats> display = compareDisplayByRegion(synthesized, reference, cropColumns, masks);
  EyeError error{display.all, display.halo, display.rest, display.disocclusion, display.transparent, std::nullopt,
                 display.foliage};
  if (synthesizedHdr && referenceHdr)
    error.hdr = compareHdrByRegion(*synthesizedHdr, *referenceHdr, cropColumns, masks);
  return error;
}

EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion) {
  return compareEye(synthesized, reference, cropColumns, RegionMasks{halo, disocclusion, {}});
}

}  // namespace s3d::stereo
