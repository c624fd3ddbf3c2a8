#pragma once
// A synthesized eye against its two-pass reference, over the cropped area and per region (halo, disocclusion,
// transparent, foliage), in display space and linear HDR: one comparison for every tool and host that measures.
#include <cstdint>
#include <optional>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

struct EyeError {
  ErrorStats display{};  // synthesized eye vs two-pass reference, border strips of cropColumns excluded
  ErrorStats halo{};     // the same within maxSeparation of a center-view depth edge (haloMask)
  ErrorStats rest{};     // and in none of the regions (halo, disocclusion, transparent, foliage)
  ErrorStats disocclusion{};  // reference pixels the center camera never saw (disocclusionMask)
  ErrorStats transparent{};   // reference pixels covered by transparent surfaces (0 pixels without any)
  // The same in linear HDR (HdrErrorStats); only where the HDR images were compared (s3d render).
  std::optional<ErrorsByRegion<HdrErrorStats>> hdr;
  // Reference pixels whose visible surface is an alpha cut-out (alphaMode MASK) material (0 pixels without any).
  ErrorStats foliage{};
};

// The halo region of a center view for these parameters: within maxSeparation * width (rounded up) of a depth edge.
std::vector<std::uint8_t> haloMaskFor(const DepthImage& centerDepth, const StereoParameters& parameters);

// The reference pixels of one eye that the center camera did not see (disocclusionMask).
std::vector<std::uint8_t> disocclusionMaskFor(const DepthImage& referenceDepth, const DepthImage& centerDepth,
                                              const StereoParameters& parameters, Eye eye);

// One eye's error over the cropped area and its regions (masks from haloMaskFor / disocclusionMaskFor and the
// renderer's readTransparentMask and readCutoutMask), in display space and, when both HDR images are given, in linear HDR.
EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const RegionMasks& masks, const ImageRGBA32F* synthesizedHdr = nullptr,
                    const ImageRGBA32F* referenceHdr = nullptr);
// Display space only, without transparent and foliage regions.
EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion);

}  // namespace s3d::stereo
