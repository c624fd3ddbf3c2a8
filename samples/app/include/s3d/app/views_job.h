#pragma once
// `s3d render --views FILE.json`: per-eye views as OpenXR reports them (comfort/view_configuration.h). The
// center view is rendered with the frustum that covers both eyes plus the guard band; each eye is
// synthesized from it through the view mapping (stereo::synthesizeEyeForView) and resampled into its own
// projection and size; the two-pass reference renders exactly those eye views; the error is the whole frame's.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/view_configuration.h"
#include "s3d/image.h"
#include "s3d/stereo/metrics.h"
#include "s3d/vk/context.h"

namespace s3d::app {

struct ViewsJobOptions {
  std::string scene = "courtyard";
  std::size_t frame = 0;
  float framesPerSecond = 12.0f;  // the frame's time in an animated scene: frame / framesPerSecond (RenderJobOptions)
  comfort::ViewConfiguration views;
  std::string viewsFile;  // as given, for the report
  std::filesystem::path outputFolder = "out";
  bool writeImages = true;  // center.png, left.png, right.png, left_reference.png, right_reference.png
  std::optional<std::uint64_t> memoryLimitBytes;  // --memory-limit; the machine's available memory in any case
  // The display the views are shown on: its focal distance is where the eyes accommodate (the comfort report).
  comfort::DisplayProfile display = comfort::builtInDisplayProfile("hmd");
};

struct ViewsReport {
  std::string deviceName;
  std::string scene;
  comfort::CenterView center;
  std::array<stereo::ErrorStats, 2> error{};  // left, right: synthesized vs reference over the whole eye
  comfort::DisplayProfile display;
  double interocularMeters = 0.0;  // the views' eye separation
  // Left, right: vergence-accommodation conflict and the share beyond the 1-degree rule (against the focal
  // plane) of what each synthesized eye shows.
  std::array<comfort::EyeViewComfort, 2> comfort{};
  // Left, right: the range of disparity between the eyes over the depths the eye shows, in its pixels at the
  // image centre (eye separation in world units times (1 / nearest - 1 / farthest), over the eye's tangent pitch)
  // and in arcminutes at the eyes (the views are the viewer's: separation in metres over distance in metres).
  std::array<double, 2> disparityRangePx{}, disparityRangeArcmin{};
  std::vector<std::string> filesWritten;
};

ViewsReport runViewsJob(vk::Context& context, const ViewsJobOptions& options);
nlohmann::json toJson(const ViewsReport& report);

}  // namespace s3d::app
