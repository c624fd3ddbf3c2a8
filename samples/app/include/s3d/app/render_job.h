#pragma once
// `s3d render` as a library: render a built-in scene's center view with the deferred renderer, synthesize
// both eyes on the GPU with the stereo pass (Listing 4.5), render the two-pass reference eyes with
// off-axis cameras, compare them, and write the selected outputs plus a JSON report.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/frame_rules.h"
#include "s3d/app/report_json.h"
#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/comfort_profile.h"
#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/frame/hybrid_stereo.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::app {

// Every output runRenderJob can write, by file name inside the output folder, in the order they are written:
//   center.png            tone-mapped center view (RGBA8, sRGB-encoded)
//   center.exr            exposed linear HDR center view (RGBA half) + linear depth as "Z" (float, +inf: sky)
//   left.png, right.png   eyes synthesized by the stereo pass from the center view and its depth
//   left_reference.png,   eyes rendered by the two-pass reference (off-axis eye cameras)
//   right_reference.png
//   anaglyph.png          red-cyan Dubois anaglyph of the synthesized eyes
//   sbs.png, tab.png      side-by-side / top-and-bottom frames of the synthesized eyes
//   report.json           toJson(report), always written last
inline const std::vector<std::string> kAllOutputs = {
    "center.png",         "center.exr",          "left.png",     "right.png", "left_reference.png",
    "right_reference.png", "anaglyph.png",        "sbs.png",      "tab.png",   "error_left.png",
    "error_right.png",    "report.json"};

// Largest accepted width or height.
inline constexpr std::uint32_t kMaxImageSize = 16384;

struct RenderJobOptions {
  std::uint32_t width = 1280;
  std::uint32_t height = 720;
  std::string scene = "courtyard";  // one of renderer::builtInSceneNames(), or a .gltf/.glb file
  std::size_t frame = 0;            // frame of the scene's camera path
  // Frame `frame` is at frame / framesPerSecond seconds of the scene's animation (an animated glTF; looped over
  // its duration); the same rate as `s3d render --sequence`'s (SequenceJobOptions::framesPerSecond).
  float framesPerSecond = 12.0f;
  std::filesystem::path outputFolder = "out";
  // Which of kAllOutputs to write. The selection is honoured exactly: report.json is written only when
  // selected (it is by default). An empty set renders and measures without writing any file.
  std::set<std::string> outputs{kAllOutputs.begin(), kAllOutputs.end()};
  stereo::PackingMode sideBySide = stereo::PackingMode::Half;
  stereo::PackingMode topBottom = stereo::PackingMode::Half;
  // edgeCrop < 0 (the default): a guard band, full-frame eyes; >= 0: the output-size center view, that crop.
  stereo::StereoParameters stereo;
  comfort::DisplayProfile display = comfort::builtInDisplayProfile("tv55");  // of the comfort report
  comfort::CrosshairSettings crosshair;  // distance (nullopt: the scene's) and margin in front of a hit
  bool allowNegativeParallax = false;    // off: nothing in the frame is given negative parallax
  std::uint32_t supersample = 1;  // renderer anti-aliasing, 1..4 (center view and reference eyes alike)
  bool reversedZ = false;         // renderer::RendererOptions::reversedZ for every view
  // OneDegree: maxSeparation and the zero-parallax distance are chosen from the frame's depth range so every
  // pixel fits the display's 1-degree budget (s3d/comfort/budget_frame.h); the library default is off (`s3d`
  // turns it on).
  comfort::DisparityBudgetRule disparityBudget = comfort::DisparityBudgetRule::Off;
  // The game HUD (panels and crosshair) of the built-in scenes; Auto: drawn on them, left out of glTF files.
  HudMode hud = HudMode::Auto;
  // The most memory the run may use (--memory-limit); the machine's available memory in any case.
  std::optional<std::uint64_t> memoryLimitBytes;
};

// stereo::EyeError (per-region error of one eye) lives in s3d/stereo/eye_comparison.h, shared with `s3d bench`.

struct CrosshairReport {
  float depth = 0.0f;       // linear depth the crosshair is placed at (world units)
  bool hitWorld = false;    // the aim ray hit a surface closer than the scene's crosshair distance
  float parallaxPx = 0.0f;  // per-eye displacement in pixels (left eye: -parallaxPx, right eye: +parallaxPx)
};

// HudElementReport (one HUD element as drawn) is the library's (s3d/frame/frame_hud.h), shared with `s3d tune`.

// What the hybrid method did in one frame (method hybrid only).
struct HybridReport {
  float budget = 0.0f;
  stereo::StereoMethod base = stereo::StereoMethod::Search;
  std::uint64_t classifiedPixels = 0;               // per eye: the compared area
  int cell = 1;                                      // the classification's cell, pixels per side
  std::array<stereo::HybridThreshold, 2> thresholds;  // left, right: the threshold and split bins (in cells)
  std::array<std::uint64_t, 2> maskedPixels{};        // left, right
  frame::HybridTimings timings;
};

struct RenderReport {
  std::string deviceName;
  std::string scene;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  stereo::StereoParameters stereo;  // as used: edgeCrop resolved (never < 0), zeroParallaxDistance clamped, the no-negative-parallax rules applied
  std::uint32_t cropColumns = 0;    // columns blacked out on each side (and excluded from the error); 0 with a guard band
  std::uint32_t guardBandColumns = 0;  // extra center-view columns rendered per side (0 with --edge-crop)
  std::uint32_t renderedWidth = 0;     // width of the rendered center view and reference eyes: width + 2 guard band
  std::optional<double> centerFrameGpuMs;   // whole deferred frame of the center view
  std::optional<double> stereoPassGpuMs;    // the stereo compute dispatch producing both eyes
  std::optional<double> referenceEyeGpuMs;  // whole deferred frame of the left reference eye
  comfort::BudgetFrame budget;               // the disparity budget's reduction and choice (rule off: empty)
  comfort::DisparityMapReport disparityMap;  // the depth-to-parallax curve (identity: linear)
  std::vector<renderer::PassTiming> centerPasses;
  stereo::EyeError left{};
  stereo::EyeError right{};
  CrosshairReport crosshair;
  comfort::DisplayProfile display;
  comfort::FrameComfort comfort;  // of the stereo pass's depth on that display
  bool zeroParallaxLimited = false;    // lowered to the frame's nearest depth (negative parallax disallowed)
  std::uint64_t weaponConflictPixels = 0;  // weapon pixels whose pushed depth lies behind the world surface there
  std::vector<HudElementReport> hud;       // panels, then the crosshair
  std::uint64_t hudConflictPixels = 0;     // sum over the HUD elements
  std::array<std::uint64_t, 2> filledPixels{};  // left, right: disoccluded pixels filled (iterative method)
  std::optional<HybridReport> hybrid;           // method hybrid: the masks and the GPU time per part
  struct {
    std::uint64_t colorValues = 0;  // non-finite HDR channel values of the center view, made 0
    std::uint64_t depthPixels = 0;  // NaN / -inf / non-positive center depths, read as the zero-parallax plane
  } sanitized;
  std::vector<std::string> warnings;  // e.g. a clamped zero-parallax distance; also printed on stderr by the CLI
  std::vector<std::string> filesWritten;  // file names relative to the output folder, in write order
  frame::MemoryEstimate memory;           // what the run was estimated to need before it started
};

// Throws std::invalid_argument naming the problem: zero or absurd size (> kMaxImageSize), unknown scene,
// unknown output name, invalid stereo parameters, a crop that leaves no columns to compare, a packing the size
// cannot take (half side-by-side of a 1-pixel-wide eye), a memory estimate beyond the host's memory, or an output
// folder path that exists but is not a folder. Needs no Vulkan: call it before creating a context.
void validateRenderJobOptions(const RenderJobOptions& options);

// The run's memory (s3d/frame/memory_budget.h), with the widest guard band the options allow: the separation's, the
// disparity budget's largest on the display, or half the width a side with negative parallax allowed.
frame::MemoryEstimate renderJobMemoryEstimate(const RenderJobOptions& options);

// Validates the options (before creating any GPU resource or file), renders, compares, writes the selected
// outputs into options.outputFolder (each write atomic) and returns the report.
// Throws std::invalid_argument for bad options, std::runtime_error for write failures, vk::VulkanError.
RenderReport runRenderJob(vk::Context& context, const RenderJobOptions& options);

// The report.json document:
// { "device", "scene", "width", "height",
//   "stereo": {"maxSeparation", "zeroParallaxDistance", "edgeCrop", "cropColumns", "guardBandColumns", "renderedWidth", "method": "seed"|"search", "searchTaps" (search only)},
//   "gpuTimeMs": {"centerFrame", "stereoPass", "referenceEye", "depthReduction" (disparity budget on)},
//   "disparityBudget": budgetJson (comfort_json.h),   (null when the device has no timestamps)
//   "centerPasses": [{"name", "gpuMs"}],
//   "ratios": {"stereoPassToReferenceEye"},                        (null when a time is missing)
//   "error": {"left": {"psnrDb", "ssim", "meanAbsoluteError", "shareAbove8", "pixelCount",
//                      "halo"|"disocclusion"|"transparent"|"foliage"|"rest": {same fields},
//                      "hdr": {"psnrDb", "ssim", "meanAbsoluteError", "pixelCount", and the same regions}},
//             "right": {...}},
//   "sanitized": {"colorValues", "depthPixels"},                  (non-finite input replaced, see RenderReport)
//   "warnings": [...],
//   "comfort": {comfortJson (comfort_json.h): parallax range in px / % / arcmin, shares beyond 1 degree and in
//               front of the screen, windowViolations; "display",
//               "zeroParallaxDistance", "zeroParallaxLimited", "crosshairDepth", "weaponConflictPixels", "hudConflictPixels"},
//   "crosshair": {"depth", "hitWorld", "parallaxPx"},              (the HUD crosshair, see CrosshairReport)
//   "hud": [{"name", "depth", "behindWeapon", "drawnPixels": {"left", "right"}, "fadedPixels": {...}, "conflictPixels"}],
//   "files": [...] }
// Every number is finite (a non-finite value would be written as null).
nlohmann::json toJson(const RenderReport& report);

}  // namespace s3d::app
