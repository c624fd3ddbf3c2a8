#pragma once
// `s3d convert`: stereo pairs from frames another program rendered or captured (color + depth, or color +
// disparity files), one frame or a folder of frames.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/comfort/budget_frame.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::app {

enum class DepthKind {
  Linear,    // planar view depth in world units, along the view axis (+inf or any value >= 1e30: sky)
  Distance,  // distance from the camera centre along each pixel's ray (a ray tracer's "range"): needs intrinsics
  Hardware,  // zero-to-one device depth of a perspective projection with --near/--far (1.0: sky)
};

// Disparity mode: d = xLeft - xRight in pixels, per pixel of the input view (the usual stereo-matching sign:
// >= 0 for parallel cameras). Right: the input is the left view and the output (right view) shows each pixel at
// x - d. Left: the input is the right view and the output (left view) shows each pixel at x + d.
enum class DisparityOutput { Right, Left };

struct ConvertJobOptions {
  std::filesystem::path color;  // PNG (display-encoded) or EXR (linear HDR: clamped, sRGB-encoded)
  // Depth (or, with `disparity`, the disparity map): .exr (channel depthChannel; may be the color file),
  // .png (16-bit grey), .pfm (1 channel).
  std::filesystem::path depth;
  std::string depthChannel = "Z";  // EXR only
  // 16-bit PNG only: world units (or disparity pixels) per step for Linear / Distance / disparity; Hardware
  // depth reads value / 65535 instead. For Linear and Distance, 65535 is sky; 0 is unknown (also for disparity).
  float depthScale = 1.0f;
  DepthKind depthKind = DepthKind::Linear;
  float nearPlane = 0.0f;  // Hardware only
  float farPlane = 0.0f;   // Hardware only
  // Distance only, exactly one of them: the principal point is the image centre.
  std::optional<float> verticalFovDegrees;
  std::optional<float> focalLengthPx;
  // When set, `depth` holds disparity in pixels (scaled by depthScale for PNG) and the output is the other view.
  std::optional<DisparityOutput> disparity;
  std::filesystem::path outputFolder = "out";
  std::optional<std::filesystem::path> referenceLeft;  // a real second view to measure against
  std::optional<std::filesystem::path> referenceRight;
  stereo::PackingMode sideBySide = stereo::PackingMode::Half;
  stereo::PackingMode topBottom = stereo::PackingMode::Half;
  stereo::StereoParameters stereo;  // disparity mode: maxSeparation and zeroParallaxDistance are derived
  // --method auto (the tool's default): stereo.method is replaced by stereo::automaticMethod(External).
  bool automaticMethod = false;
  std::string fileSuffix;           // folder mode: "_0001" makes left_0001.png, ...
  bool writeReport = true;          // report<suffix>.json
  // OneDegree (depth input only; disparity input is reproduced as given): maxSeparation and the zero-parallax
  // distance chosen from the frame's depth range on `display` (s3d/comfort/budget_frame.h); folder mode runs one
  // controller over the frames in order. Off: the library default; `s3d convert` turns it on.
  comfort::DisparityBudgetRule disparityBudget = comfort::DisparityBudgetRule::Off;
  comfort::DisplayProfile display = comfort::builtInDisplayProfile("tv55");
  comfort::DisparityBudgetController* budgetController = nullptr;  // none: a fresh one (the frame's target)
  std::optional<std::uint64_t> memoryLimitBytes;  // --memory-limit; the machine's available memory in any case
};

struct ConvertReport {
  std::string deviceName;
  std::string color, depth;  // the input files
  std::uint32_t width = 0, height = 0;
  std::uint32_t cropColumns = 0;
  stereo::StereoParameters stereo;  // as used (disparity mode: the derived separation)
  bool automaticMethod = false;     // stereo.method was chosen by --method auto
  std::optional<double> stereoPassGpuMs;
  std::optional<stereo::ErrorStats> left, right;  // only with --reference-left / --reference-right
  std::uint64_t sanitizedColorValues = 0;  // NaN / inf channel values of an EXR color input, made 0
  // Depth or disparity pixels without a value (NaN; zero or negative depth; +-inf or PNG 0 disparity), given the
  // depth of the background beside them on their row (stereo::fillUnknownDepthFromBackground).
  std::uint64_t unknownDepthPixels = 0;
  comfort::BudgetFrame budget;           // the disparity budget's reduction and choice (off: empty)
  comfort::FrameComfort comfort;         // on options.display, with the budget on
  std::vector<std::string> filesWritten;
  frame::MemoryEstimate memory;  // estimated from the color file's header before anything was decoded
};

// Reads and checks every input first (missing, unreadable or truncated file, missing channel, mismatched
// sizes, no known depth at all, bad near/far or intrinsics, disparity beyond the separation limit) and
// throws std::invalid_argument or std::runtime_error naming the file and the problem before anything is written
// (NaN or inf in an EXR color input is sanitized and counted instead). Then runs the stereo pass on the GPU and
// writes left, right, anaglyph, sbs, tab (.png) and report.json, each with options.fileSuffix and each
// atomically. Disparity mode: left/right are the input view and the other view.
ConvertReport runConvertJob(vk::Context& context, const ConvertJobOptions& options);

nlohmann::json toJson(const ConvertReport& report);

// Folder mode: one frame of a sequence, named by what the patterns' '*' matched.
struct ConvertFrame {
  std::string key;
  std::filesystem::path color, depth;
};

// Pairs the files of `folder` matching colorPattern and depthPattern (file names, each with exactly one '*')
// by what the '*' matched, sorted by that key. Throws std::invalid_argument for a missing folder, a pattern
// without exactly one '*', no matching color file, or a color frame without its depth file (and vice versa).
std::vector<ConvertFrame> pairFrames(const std::filesystem::path& folder, const std::string& colorPattern,
                                     const std::string& depthPattern);

// How a folder run treats an earlier run's outputs in the same output folder.
enum class FolderResume {
  No,   // every frame converted; a caller's io::OutputTransaction makes the run all-or-nothing
  Yes,  // frames report.json lists with unchanged inputs and settings and all files present are kept; every other
        // frame is committed as soon as it is converted, with report.json rewritten to list exactly the frames
        // present ("complete": false until the last), so a failure leaves what report.json says and a rerun goes on
};

struct ConvertFolderResult {
  std::vector<ConvertReport> converted;  // frames converted by this run, in order
  std::vector<std::string> kept;         // keys of frames an earlier run converted (FolderResume::Yes)
};

// Converts every frame with `options` (its color/depth replaced, fileSuffix "_<key>", no per-frame report) and
// writes one report.json, the folder's manifest: {"settings": the options that shape the outputs, "complete",
// "frames": [{"frame": key, "inputs": {"color"|"depth": {"path", "bytes", "modifiedNs"}}, "files", ...}]}.
// progress(done, total, key) is called after each frame. A bad frame stops the run with an error naming it
// (with FolderResume::Yes also how many frames report.json lists). Throws std::invalid_argument when resuming
// from a report.json made with other settings, or one that is not such a manifest.
// The names a conversion writes into its output folder: one frame's (no `frames`) or a folder run's.
std::vector<std::string> convertOutputNames(const ConvertJobOptions& options, const std::vector<ConvertFrame>& frames);

ConvertFolderResult runConvertFolder(vk::Context& context, const ConvertJobOptions& options,
                                     const std::vector<ConvertFrame>& frames,
                                     const std::function<void(std::size_t, std::size_t, const std::string&)>& progress = {},
                                     FolderResume resume = FolderResume::No);

}  // namespace s3d::app
