#pragma once
// Synthesized eye against its two-pass reference, per region, and the JSON form of the statistics: shared by
// `s3d render` (render_job.h) and `s3d bench` (bench_job.h) so both report the same numbers the same way.
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/frame/hybrid_stereo.h"
#include "s3d/image.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/stereo.h"

namespace s3d::app {

struct EyeError {
  stereo::ErrorStats display{};  // synthesized eye vs two-pass reference, border strips of cropColumns excluded
  stereo::ErrorStats halo{};     // the same within maxSeparation of a center-view depth edge (stereo::haloMask)
  stereo::ErrorStats rest{};     // and in none of the regions (halo, disocclusion, transparent, foliage)
  stereo::ErrorStats disocclusion{};  // reference pixels the center camera never saw (stereo::disocclusionMask)
  stereo::ErrorStats transparent{};   // reference pixels covered by transparent surfaces (0 pixels without any)
  // The same in linear HDR (stereo::HdrErrorStats); only where the HDR images were compared (s3d render).
  std::optional<stereo::ErrorsByRegion<stereo::HdrErrorStats>> hdr;
  // Reference pixels whose visible surface is an alpha cut-out (alphaMode MASK) material (0 pixels without any).
  stereo::ErrorStats foliage{};
};

// The halo region of a center view for these parameters: within maxSeparation * width (rounded up) of a depth edge.
std::vector<std::uint8_t> haloMaskFor(const DepthImage& centerDepth, const stereo::StereoParameters& parameters);

// The reference pixels of one eye that the center camera did not see (stereo::disocclusionMask).
std::vector<std::uint8_t> disocclusionMaskFor(const DepthImage& referenceDepth, const DepthImage& centerDepth,
                                              const stereo::StereoParameters& parameters, stereo::Eye eye);

// One eye's error over the cropped area and its regions (masks from haloMaskFor / disocclusionMaskFor and the
// renderer's readTransparentMask and readCutoutMask), in display space and, when both HDR images are given, in linear HDR.
EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const stereo::RegionMasks& masks, const ImageRGBA32F* synthesizedHdr = nullptr,
                    const ImageRGBA32F* referenceHdr = nullptr);
// Display space only, without transparent and foliage regions.
EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion);

// Shortest decimal that round-trips the float (0.02f is reported as 0.02, not 0.019999999552965164).
double tidy(float value);
nlohmann::json finiteOrNull(double value);
nlohmann::json optionalMs(const std::optional<double>& value);  // null when absent or not finite
// {"displacement", "classification", "eyeGeometry", "maskedShading", "composite", "total"}: ms or null;
// "surfaces": "raycast" or "raster".
nlohmann::json toJson(const frame::HybridTimings& timings);
// {"psnrDb", "ssim", "meanAbsoluteError", "shareAbove8", "pixelCount"}: every ErrorStats field, non-finite as null.
nlohmann::json statsJson(const stereo::ErrorStats& stats);
// {"psnrDb", "ssim", "meanAbsoluteError", "pixelCount"}.
nlohmann::json statsJson(const stereo::HdrErrorStats& stats);
// The whole cropped area at the top level, the regions ("halo", "disocclusion", "transparent", "foliage", "rest") below
// it, and "hdr" (the same layout in linear HDR) when measured.
nlohmann::json errorJson(const EyeError& error);

}  // namespace s3d::app
