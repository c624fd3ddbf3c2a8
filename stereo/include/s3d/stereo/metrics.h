#pragma once
// Image-difference statistics for judging a synthesized eye view against a rendered reference.
#include <cstdint>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// PSNR reported for identical images: the true value is +inf, which breaks JSON/CSV reports and averages.
constexpr double kMaxPsnrDb = 100.0;

// Differences below are over R, G, B in 8-bit sRGB code levels; alpha is ignored.
struct ErrorStats {
  double psnrDb;             // 10*log10(255^2 / MSE), capped at kMaxPsnrDb
  double meanAbsoluteError;  // mean |difference| in levels over R, G, B of the compared pixels
  double shareAbove8;        // fraction of compared pixels whose largest R/G/B |difference| exceeds 8 levels
  std::uint64_t pixelCount;  // number of pixels compared (after cropping)
  double ssim = 1.0;         // mean SSIM of luma over the compared pixels (ssimMap)
};

// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004) per pixel on luma: an 11x11 Gaussian window with sigma 1.5 and
// the paper's constants C1 = (0.01 L)^2, C2 = (0.03 L)^2. Display images use BT.601 luma of the 8-bit sRGB
// codes (L = 255, as the paper's reference code); HDR images the BT.709 luminance of the linear color with
// L = kHdrPeak. The window is cut at the borders of the compared area (columns [cropColumns, W - cropColumns),
// all rows) and renormalized, so every pixel has a value down to a 1x1 image. Values outside the area are 0.
constexpr int kSsimWindowRadius = 5;      // 11x11
constexpr double kSsimGaussianSigma = 1.5;
constexpr double kSsimK1 = 0.01;
constexpr double kSsimK2 = 0.03;
std::vector<float> ssimMap(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns);
std::vector<float> ssimMap(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference, std::uint32_t cropColumns);

// Linear-HDR differences over R, G, B of the exposed scene-referred color (the tone curve's input), against a
// fixed peak of 1.0: an exposed white; brighter highlights may give errors above the peak.
constexpr double kHdrPeak = 1.0;
struct HdrErrorStats {
  double psnrDb = kMaxPsnrDb;       // 10*log10(kHdrPeak^2 / MSE), capped at kMaxPsnrDb
  double ssim = 1.0;                // mean SSIM of luminance (ssimMap)
  double meanAbsoluteError = 0.0;   // mean |difference| over R, G, B, in linear units
  std::uint64_t pixelCount = 0;
};
HdrErrorStats compareHdrImages(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference,
                               std::uint32_t cropColumns);

// Compares columns [cropColumns, W - cropColumns) of all rows: view synthesis cannot know what lies
// beyond the image edge, so the disoccluded border strips are excluded by the caller's choice of crop.
// Throws std::invalid_argument if the sizes differ, a buffer is inconsistent, or the crop leaves no columns.
ErrorStats compareDisplayImages(const ImageRGBA8& synthesized, const ImageRGBA8& reference,
                                std::uint32_t cropColumns);

// Neighbouring depths differing by more than this fraction of the nearer one form a depth edge.
constexpr float kDepthEdgeRelativeJump = 0.1f;

// Halo region: 1 for pixels within radiusPx columns of a horizontal depth edge of the center view
// (surface against sky counts), where the seed clones background next to near objects. Use
// radiusPx = maxSeparation * width.
std::vector<std::uint8_t> haloMask(const DepthImage& centerDepth, std::uint32_t radiusPx);

struct RegionErrors {
  ErrorStats all;
  ErrorStats halo;  // pixels of the halo mask
  ErrorStats rest;  // the others (not halo; compareDisplayByRegion's rest also leaves out its other regions)
};
RegionErrors compareByRegion(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                             const std::vector<std::uint8_t>& halo);

// Statistics over the cropped area's pixels whose mask value is 1.
ErrorStats compareWithinMask(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                             const std::vector<std::uint8_t>& mask);

// Disocclusion region: 1 for the pixels of a reference eye that the center camera did not see.
// Each reference pixel at linear depth d is reprojected into the center view (left eye: x + p(d) W, right
// eye: x - p(d) W, nearest pixel); it was seen when the center's depth there matches d within
// kSameSurfaceRelativeDepth (or both are sky), and unseen when it lands outside the image or on another
// surface. Depths are the stereo pass's (weapon pushed), as both renders write them.
constexpr float kSameSurfaceRelativeDepth = 0.02f;
std::vector<std::uint8_t> disocclusionMask(const DepthImage& referenceDepth, const DepthImage& centerDepth,
                                           float maxSeparation, float zeroParallaxDistance, Eye eye);

// The error regions (whole, halo, disocclusion, transparent, foliage, rest) as masks over the image (1: in the region); an empty mask is a region without
// pixels. Regions may overlap; `rest` is every compared pixel in none of them.
struct RegionMasks {
  std::vector<std::uint8_t> halo;          // haloMask
  std::vector<std::uint8_t> disocclusion;  // disocclusionMask
  std::vector<std::uint8_t> transparent;   // reference pixels covered by transparent surfaces
  // Reference pixels whose visible surface is an alpha cut-out (alphaMode MASK) material: foliage, fences.
  std::vector<std::uint8_t> foliage;
};
template <typename Stats>
struct ErrorsByRegion {
  Stats all, halo, disocclusion, transparent, rest, foliage;
};
ErrorsByRegion<ErrorStats> compareDisplayByRegion(const ImageRGBA8& synthesized, const ImageRGBA8& reference,
                                                  std::uint32_t cropColumns, const RegionMasks& masks);
ErrorsByRegion<HdrErrorStats> compareHdrByRegion(const ImageRGBA32F& synthesized, const ImageRGBA32F& reference,
                                                 std::uint32_t cropColumns, const RegionMasks& masks);

// Error heat map: per pixel the largest R/G/B difference, black at 0 through blue, red and
// yellow to white at fullScaleLevels and above; the cropped border columns stay black.
ImageRGBA8 makeErrorHeatMap(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                            int fullScaleLevels = 32);

}  // namespace s3d::stereo
