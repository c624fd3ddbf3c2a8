#include "s3d/app/report_json.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

namespace s3d::app {

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
          {"eyeGeometry", optionalMs(t.eyeGeometry)},   {"baseDepth", optionalMs(t.baseDepth)},
          {"frontSpan", optionalMs(t.frontSpan)},
          {"maskedShading", optionalMs(t.maskedShading)}, {"eyeRenders", optionalMs(t.eyeRenders)},
          {"concurrentEyes", t.concurrentEyes},
          {"composite", optionalMs(t.composite)},       {"total", optionalMs(t.total)},
          {"surfaces", t.mixedSurfaces ? "mixed" : t.raycastSurfaces ? "raycast" : "raster"}};
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

nlohmann::json errorJson(const stereo::EyeError& error) {
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
