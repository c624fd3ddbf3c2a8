#pragma once
// `s3d convert`: stereo pairs from frames another program rendered or captured (color + depth files).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::app {

enum class DepthKind {
  Linear,    // view depth in world units (+inf or any value >= 1e30: sky)
  Hardware,  // zero-to-one device depth of a perspective projection with --near/--far (1.0: sky)
};

struct ConvertJobOptions {
  std::filesystem::path color;       // PNG (display-encoded) or EXR (linear HDR: clamped, sRGB-encoded)
  std::filesystem::path depth;       // EXR with a Z (or R) channel; may be the same file as color
  DepthKind depthKind = DepthKind::Linear;
  float nearPlane = 0.0f;            // Hardware only
  float farPlane = 0.0f;             // Hardware only
  std::filesystem::path outputFolder = "out";
  std::optional<std::filesystem::path> referenceLeft;   // a real second view to measure against
  std::optional<std::filesystem::path> referenceRight;
  stereo::PackingMode sideBySide = stereo::PackingMode::Half;
  stereo::PackingMode topBottom = stereo::PackingMode::Half;
  stereo::StereoParameters stereo;
};

struct ConvertReport {
  std::string deviceName;
  std::uint32_t width = 0, height = 0;
  std::uint32_t cropColumns = 0;
  std::optional<double> stereoPassGpuMs;
  std::optional<stereo::ErrorStats> left, right;  // only with --reference-left / --reference-right
  std::uint64_t sanitizedColorValues = 0;  // NaN / inf channel values of an EXR color input, made 0
  std::uint64_t sanitizedDepthPixels = 0;  // NaN / -inf depths, read as the zero-parallax plane
  std::vector<std::string> filesWritten;
};

// Reads and checks every input first (missing, unreadable or truncated file, missing channel, mismatched
// sizes, negative / zero depth, bad near/far; NaN or inf color and NaN depth are sanitized and counted instead) and throws std::invalid_argument or std::runtime_error
// naming the file and the problem before anything is written. Then runs the stereo pass on the GPU and
// writes left.png, right.png, anaglyph.png, sbs.png, tab.png and report.json (each atomically).
ConvertReport runConvertJob(vk::Context& context, const ConvertJobOptions& options);

nlohmann::json toJson(const ConvertReport& report);

}  // namespace s3d::app
