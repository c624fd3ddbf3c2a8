#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "row_sampling.h"
#include "s3d/number_text.h"
#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {
namespace {

using detail::clampInt;
using detail::sampleRow;

void requireFinite(float value, const char* name) {
  if (!std::isfinite(value)) throw std::invalid_argument(std::string(name) + " must be finite (got " + numberText(value) + ")");
}

float linearDepthAt(const DepthImage& depth, int x, int y, float zeroParallaxDistance) {
  return gpu::sanitizedDepth(*depth.at(std::uint32_t(clampInt(x, 0, int(depth.width) - 1)), std::uint32_t(y)),
                             zeroParallaxDistance);
}

// Listing 4.5: minimum depth over the separation range, on one side of the pixel (direction +1 or -1).
float minDepthOverTaps(const DepthImage& depth, int x, int y, int direction, const gpu::StereoConstants& c) {
  float minDepth = S3D_INFINITY;  // the seed starts at 1.0, its normalized far plane
  for (int i = 0; i < c.tapCount; ++i) minDepth = std::min(minDepth, linearDepthAt(depth, x + direction * c.tapOffsetPx[i], y, c.zeroParallaxDistance));
  return minDepth;
}

}  // namespace

void validate(const StereoParameters& p) {
  requireFinite(p.maxSeparation, "maxSeparation");
  requireFinite(p.zeroParallaxDistance, "zeroParallaxDistance");
  requireFinite(p.edgeCrop, "edgeCrop");
  requireFinite(p.weaponDepthOffset, "weaponDepthOffset");
  requireFinite(p.weaponDepthScale, "weaponDepthScale");
  if (p.weaponDepthOffset < 0.0f) throw std::invalid_argument("weaponDepthOffset must be >= 0 (got " + numberText(p.weaponDepthOffset) + ")");
  if (p.weaponDepthScale <= 0.0f) throw std::invalid_argument("weaponDepthScale must be > 0 (got " + numberText(p.weaponDepthScale) + ")");
  if (p.maxSeparation < 0.0f || p.maxSeparation > kMaxSeparationLimit)
    throw std::invalid_argument("maxSeparation " + numberText(p.maxSeparation) + " is outside [0, " +
                                numberText(kMaxSeparationLimit) + "] (a fraction of the screen width)");
  if (p.zeroParallaxDistance <= 0.0f)
    throw std::invalid_argument("zeroParallaxDistance must be positive (got " + numberText(p.zeroParallaxDistance) + ")");
  if (p.method == StereoMethod::Search && (p.searchTaps < 1 || p.searchTaps > S3D_STEREO_MAX_TAPS))
    throw std::invalid_argument("searchTaps " + std::to_string(p.searchTaps) + " is outside [1, " +
                                std::to_string(S3D_STEREO_MAX_TAPS) + "]");
  if (p.method == StereoMethod::Iterative && (p.iterations < 1 || p.iterations > 16))
    throw std::invalid_argument("iterations " + std::to_string(p.iterations) + " is outside [1, 16]");
  if (p.method == StereoMethod::Hybrid) {
    if (p.hybridBase == StereoMethod::Hybrid) throw std::invalid_argument("the hybrid method's base must be another method");
    requireFinite(p.hybridBudget, "hybridBudget");
    if (p.hybridBudget < 0.0f || p.hybridBudget > 1.0f)
      throw std::invalid_argument("hybridBudget " + numberText(p.hybridBudget) + " is outside [0, 1]");
    if (p.hybridCell < 0 || p.hybridCell > kHybridCellLimit)
      throw std::invalid_argument("hybridCell " + std::to_string(p.hybridCell) + " is not 0 (by the width), 1 or 2");
    requireFinite(p.hybridScoreFloor, "hybridScoreFloor");
    if (p.hybridScoreFloor < 0.0f || p.hybridScoreFloor > kHybridScoreFloorLimit)
      throw std::invalid_argument("hybridScoreFloor " + numberText(p.hybridScoreFloor) + " is outside [0, " +
                                  numberText(kHybridScoreFloorLimit) + "] (pixels)");
    StereoParameters base = p;
    base.method = p.hybridBase;
    validate(base);
  }
  if (p.edgeCrop > kMaxSeparationLimit)
    throw std::invalid_argument("edgeCrop " + numberText(p.edgeCrop) + " is above " + numberText(kMaxSeparationLimit));
  if (p.previousFrameFill && p.method != StereoMethod::Forward)
    throw std::invalid_argument(std::string("previousFrameFill needs the forward method (got ") + methodName(p.method) + ")");
  // A nonlinear map's eyes are no pair of camera views (one pair per segment of its curve): the hybrid method
  // renders its masked pixels, and the previous-frame fill reprojects the previous eyes, with a single pair.
  if (p.disparityMapping == DisparityMapping::Nonlinear && p.method == StereoMethod::Hybrid)
    throw std::invalid_argument("disparityMapping nonlinear does not work with the hybrid method (it renders the "
                                "masked pixels from one pair of eye cameras; a nonlinear map has none): use "
                                "disparityMapping linear or another method");
  if (p.disparityMapping == DisparityMapping::Nonlinear && p.previousFrameFill)
    throw std::invalid_argument("disparityMapping nonlinear does not work with previousFrameFill (it reprojects the "
                                "previous eyes as views of one pair of eye cameras; a nonlinear map has none)");
}

const char* methodName(StereoMethod method) {
  switch (method) {
    case StereoMethod::Seed: return "seed";
    case StereoMethod::Search: return "search";
    case StereoMethod::Iterative: return "iterative";
    case StereoMethod::Forward: return "forward";
    case StereoMethod::Hybrid: return "hybrid";
  }
  return "unknown";
}

StereoMethod automaticMethod(DepthSource source) {
  return source == DepthSource::External ? StereoMethod::Forward : StereoParameters{}.method;
}

namespace {
constexpr StereoMethod kStereoMethods[] = {StereoMethod::Seed, StereoMethod::Search, StereoMethod::Iterative,
                                           StereoMethod::Forward, StereoMethod::Hybrid};
}

std::vector<std::string> stereoMethodNames(bool withHybrid) {
  std::vector<std::string> names;
  for (StereoMethod method : kStereoMethods)
    if (withHybrid || method != StereoMethod::Hybrid) names.push_back(methodName(method));
  return names;
}

StereoMethod parseStereoMethod(const std::string& name) {
  for (StereoMethod method : kStereoMethods)
    if (name == methodName(method)) return method;
  std::string choices;
  for (const std::string& known : stereoMethodNames()) choices += (choices.empty() ? "" : ", ") + known;
  throw std::invalid_argument("unknown stereo method '" + name + "' (expected one of " + choices + ")");
}

StereoParameters displacementParameters(StereoParameters parameters) {
  if (parameters.method == StereoMethod::Hybrid) parameters.method = parameters.hybridBase;
  return parameters;
}

const char* kernelName(StereoKernel kernel) {
  switch (kernel) {
    case StereoKernel::Auto: return "auto";
    case StereoKernel::PerPixel: return "pixel";
    case StereoKernel::RowTiles: return "tiles";
  }
  return "unknown";
}

StereoKernel parseStereoKernel(const std::string& name) {
  for (StereoKernel kernel : {StereoKernel::Auto, StereoKernel::PerPixel, StereoKernel::RowTiles})
    if (name == kernelName(kernel)) return kernel;
  throw std::invalid_argument("unknown stereo kernel '" + name + "' (expected auto, pixel or tiles)");
}

int rowTileMargin(const gpu::StereoConstants& c) {
  int largestTap = 0;
  for (int i = 0; i < c.tapCount; ++i) largestTap = std::max(largestTap, c.tapOffsetPx[i]);
  return gpu::rowTileMarginPx(c.maxSeparation * float(c.width), largestTap);
}

bool usesRowTiles(StereoKernel kernel, int rowTileMarginPx, bool cpuDevice) {
  if (rowTileMarginPx > S3D_STEREO_ROW_TILE_MARGIN) return false;
  (void)cpuDevice;  // Auto is PerPixel on every device measured so far (stereo.h)
  return kernel == StereoKernel::RowTiles;
}

namespace {

int nearestTexelOffset(float tapFraction, float maxSeparation, std::uint32_t width) {
  return int(std::floor(0.5f + tapFraction * maxSeparation * float(width)));
}

// Everything but the taps.
gpu::StereoConstants makeConstantsWithoutTaps(const StereoParameters& p, std::uint32_t width, std::uint32_t height) {
  validate(p);
  if (width == 0 || height == 0) throw std::invalid_argument("stereo pass: image has zero size");
  gpu::StereoConstants c{};
  c.maxSeparation = p.maxSeparation;
  c.zeroParallaxDistance = p.zeroParallaxDistance;
  float crop = p.edgeCrop < 0.0f ? p.maxSeparation : p.edgeCrop;
  int cropColumns = std::min(int(std::ceil(crop * float(width))), int(width) / 2);
  c.cropBegin = cropColumns;
  c.cropEnd = int(width) - cropColumns;
  c.width = int(width);
  c.height = int(height);
  return c;
}

}  // namespace

gpu::StereoConstants makeSeedConstants(const StereoParameters& p, std::uint32_t width, std::uint32_t height) {
  gpu::StereoConstants c = makeConstantsWithoutTaps(p, width, height);
  c.tapCount = 3;
  for (int i = 0; i < c.tapCount; ++i) c.tapOffsetPx[i] = nearestTexelOffset(kSeedTaps[i], p.maxSeparation, width);
  return c;
}

gpu::StereoConstants makeStereoConstants(const StereoParameters& p, std::uint32_t width, std::uint32_t height) {
  // The iterative pass has its own constants (makeIterativeConstants); crop and size are the seed's.
  if (displacementParameters(p).method != StereoMethod::Search) return makeSeedConstants(p, width, height);
  gpu::StereoConstants c = makeConstantsWithoutTaps(p, width, height);
  // Evenly spread over (0, maxSeparation], rounded to whole pixels; repeated offsets are dropped.
  for (int i = 1; i <= p.searchTaps; ++i) {
    int offset = nearestTexelOffset(float(i) / float(p.searchTaps), p.maxSeparation, width);
    if (c.tapCount == 0 || offset != c.tapOffsetPx[c.tapCount - 1]) c.tapOffsetPx[c.tapCount++] = offset;
  }
  return c;
}

float gatherSourceColumn(const DepthImage& linearDepth, int x, int y, Eye eye, const gpu::StereoConstants& c) {
  const int direction = eye == Eye::Left ? +1 : -1;
  const float minDepth = minDepthOverTaps(linearDepth, x, y, direction, c);
  const float parallax = gpu::parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, minDepth);
  // The left eye adds the parallax, the right eye subtracts it.
  return eye == Eye::Left ? float(x) + parallax * float(c.width) : float(x) - parallax * float(c.width);
}

StereoPair synthesizeStereoReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                     const gpu::StereoConstants& c) {
  requireSameSize(center, linearDepth, "stereo pass (color vs depth)");
  if (int(center.width) != c.width || int(center.height) != c.height)
    throw std::invalid_argument("stereo pass: constants were made for another image size");
  StereoPair pair{ImageRGBA8(center.width, center.height), ImageRGBA8(center.width, center.height)};
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      std::uint8_t* left = pair.left.at(std::uint32_t(x), std::uint32_t(y));
      std::uint8_t* right = pair.right.at(std::uint32_t(x), std::uint32_t(y));
      if (x < c.cropBegin || x >= c.cropEnd) {  // cropped edges: the search would read outside the image
        std::fill(left, left + 4, std::uint8_t(0));
        std::fill(right, right + 4, std::uint8_t(0));
        left[3] = right[3] = 255;
        continue;
      }
      sampleRow(center, y, gatherSourceColumn(linearDepth, x, y, Eye::Left, c), left);
      sampleRow(center, y, gatherSourceColumn(linearDepth, x, y, Eye::Right, c), right);
    }
  }
  return pair;
}

}  // namespace s3d::stereo
