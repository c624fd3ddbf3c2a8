#include "s3d/app/eye_comparison.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

namespace s3d::app {

std::vector<std::uint8_t> haloMaskFor(const DepthImage& centerDepth, const stereo::StereoParameters& parameters) {
  return stereo::haloMask(centerDepth, std::uint32_t(std::ceil(parameters.maxSeparation * float(centerDepth.width))));
}

std::vector<std::uint8_t> disocclusionMaskFor(const DepthImage& referenceDepth, const DepthImage& centerDepth,
                                              const stereo::StereoParameters& parameters, stereo::Eye eye) {
  return stereo::disocclusionMask(referenceDepth, centerDepth, parameters.maxSeparation,
                                  parameters.zeroParallaxDistance, eye);
}

EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const stereo::RegionMasks& masks, const ImageRGBA32F* synthesizedHdr,
                    const ImageRGBA32F* referenceHdr) {
  const stereo::ErrorsByRegion<stereo::ErrorStats> display =
      stereo::compareDisplayByRegion(synthesized, reference, cropColumns, masks);
  EyeError error{display.all, display.halo, display.rest, display.disocclusion, display.transparent, std::nullopt,
                 display.foliage};
  if (synthesizedHdr && referenceHdr)
    error.hdr = stereo::compareHdrByRegion(*synthesizedHdr, *referenceHdr, cropColumns, masks);
  return error;
}

EyeError compareEye(const ImageRGBA8& synthesized, const ImageRGBA8& reference, std::uint32_t cropColumns,
                    const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion) {
  return compareEye(synthesized, reference, cropColumns, stereo::RegionMasks{halo, disocclusion, {}});
}

double tidy(float value) {
  if (!std::isfinite(value)) return double(value);
  char text[32];
  const std::to_chars_result result = std::to_chars(text, text + sizeof(text), value);
  if (result.ec != std::errc()) return double(value);
  *result.ptr = '\0';
  return std::strtod(text, nullptr);
}

nlohmann::json finiteOrNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json optionalMs(const std::optional<double>& value) {
  return value ? finiteOrNull(*value) : nlohmann::json();
}

nlohmann::json toJson(const frame::HybridTimings& t) {
  return {{"displacement", optionalMs(t.displacement)}, {"classification", optionalMs(t.classification)},
          {"classify", optionalMs(t.classify)},         {"threshold", optionalMs(t.threshold)},
          {"mask", optionalMs(t.mask)},
          {"eyeGeometry", optionalMs(t.eyeGeometry)},   {"maskedShading", optionalMs(t.maskedShading)},
          {"composite", optionalMs(t.composite)},       {"total", optionalMs(t.total)},
          {"surfaces", t.raycastSurfaces ? "raycast" : "raster"}};
}

nlohmann::json statsJson(const stereo::ErrorStats& stats) {
  return {{"psnrDb", finiteOrNull(stats.psnrDb)},
          {"ssim", finiteOrNull(stats.ssim)},
          {"meanAbsoluteError", finiteOrNull(stats.meanAbsoluteError)},
          {"shareAbove8", finiteOrNull(stats.shareAbove8)},
          {"pixelCount", stats.pixelCount}};
}

nlohmann::json statsJson(const stereo::HdrErrorStats& stats) {
  return {{"psnrDb", finiteOrNull(stats.psnrDb)},
          {"ssim", finiteOrNull(stats.ssim)},
          {"meanAbsoluteError", finiteOrNull(stats.meanAbsoluteError)},
          {"pixelCount", stats.pixelCount}};
}

nlohmann::json errorJson(const EyeError& error) {
  nlohmann::json json = statsJson(error.display);
  json["halo"] = statsJson(error.halo);
  json["rest"] = statsJson(error.rest);
  json["disocclusion"] = statsJson(error.disocclusion);
  json["transparent"] = statsJson(error.transparent);
  json["foliage"] = statsJson(error.foliage);
  if (error.hdr) {
    nlohmann::json hdr = statsJson(error.hdr->all);
    hdr["halo"] = statsJson(error.hdr->halo);
    hdr["rest"] = statsJson(error.hdr->rest);
    hdr["disocclusion"] = statsJson(error.hdr->disocclusion);
    hdr["transparent"] = statsJson(error.hdr->transparent);
    hdr["foliage"] = statsJson(error.hdr->foliage);
    json["hdr"] = std::move(hdr);
  }
  return json;
}

}  // namespace s3d::app
