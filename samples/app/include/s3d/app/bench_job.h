#pragma once
// `s3d bench` as a library: for every scene x maxSeparation the center view and the two
// reference eyes are rendered once, then every stereo method setting runs on that center view; each number is
// the median of `repeat` GPU timestamp measurements. Writes bench.json, bench.md and bench_speed_vs_error.svg,
// and optionally regenerates a marked section of docs/RESULTS.md. `renderer` mode times the deferred
// renderer's center frame and each of its passes per scene instead.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/report_json.h"
#include "s3d/frame/hybrid_stereo.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/pass_traffic.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::app {

// One stereo method with its parameter: "seed", "search-N" (N taps), "iterative-K" (K iterations), "hybrid-B"
// (budget B; the base is the options' hybridBase with its default taps or iterations).
struct MethodSetting {
  stereo::StereoMethod method = stereo::StereoMethod::Seed;
  int parameter = 0;  // searchTaps (search), iterations (iterative), 0 (seed)
  stereo::StereoKernel kernel = stereo::StereoKernel::Auto;  // a "/pixel" or "/tiles" suffix
  float budget = 0.0f;  // hybrid only: hybridBudget
  std::string name() const;
  stereo::StereoParameters applyTo(stereo::StereoParameters parameters) const;
  bool operator==(const MethodSetting&) const = default;
};

// Parses --methods items: "seed", "search-N" (N in [1, S3D_STEREO_MAX_TAPS]), "iterative-K" (K in [1, 16]),
// "hybrid-B" (B in [0, 1]), and "search" / "iterative" / "hybrid" for their default sweeps (taps 4, 8, 16;
// iterations 2, 4, 6, 8; budgets 0, 0.02, 0.05, 0.1, 0.2, 0.5, 0.6, 1), each but hybrid optionally followed by
// "/pixel" or "/tiles" to force a kernel (stereo::StereoKernel; none: Auto). Repeats are dropped.
// Throws std::invalid_argument naming the bad item and the accepted forms.
std::vector<MethodSetting> parseMethodSettings(const std::vector<std::string>& items);
// The library's default stereo method (StereoParameters{}) as a setting: what the speed and error targets judge.
MethodSetting defaultMethodSetting();

inline const std::vector<std::string> kDefaultBenchMethods = {"seed", "search", "iterative"};
inline const std::vector<double> kDefaultSeparationsPercent = {1.0, 2.0, 4.0};

struct BenchProgress {
  std::size_t done = 0;   // steps finished
  std::size_t total = 0;  // all steps (sweep: scenes x separations x settings; renderer mode: scenes)
  std::string label;      // what runs next, e.g. "courtyard search-8 sep 2%"
};

struct BenchOptions {
  std::uint32_t width = 1920;
  std::uint32_t height = 1080;
  std::vector<std::string> scenes;  // empty: every built-in scene
  std::vector<std::string> methods = kDefaultBenchMethods;
  std::vector<double> separationsPercent = kDefaultSeparationsPercent;  // maxSeparation in % of the width, (0, 25]
  int repeat = 5;                 // GPU timings per number (median), [1, 1000]
  std::uint32_t supersample = 1;  // renderer anti-aliasing for the center view and the reference eyes, 1..4
  bool rendererOnly = false;      // center frame and pass timings per scene, no stereo sweep
  // --renderer: how the timed renderers' G-buffer pass shades (Automatic: the device's default).
  renderer::RendererOptions::GBufferShading gbufferShading = renderer::RendererOptions::GBufferShading::Automatic;
  frame::HybridSurfaces hybridSurfaces = frame::HybridSurfaces::Automatic;  // the hybrid settings' eye pixels
  // The hybrid's eyes one after the other by one eye renderer, also on a device that renders them at once
  // (frame::StereoSynthesisDescription::concurrentEyes): what rendering them at once buys.
  bool hybridEyesInTurn = false;
  std::optional<double> bandwidthGBs;  // memory bandwidth for the traffic target; no guess when absent
  std::string targetSetting;      // the setting the targets judge; empty: defaultMethodSetting()
  stereo::StereoParameters stereo;  // zeroParallaxDistance and the weapon push; method and maxSeparation are swept
  std::filesystem::path outputFolder = "bench";
  std::optional<std::filesystem::path> resultsMarkdown;  // file whose marked section is replaced
  std::function<void(const BenchProgress&)> progress;  // called before each step and once at the end
  std::optional<std::uint64_t> memoryLimitBytes;  // --memory-limit; the machine's available memory in any case
};

// A scene's frame at the largest separation swept (its guard band), as `s3d render` counts it (s3d/frame/memory_budget.h).
frame::MemoryEstimate benchMemoryEstimate(const BenchOptions& options);

struct BenchRow {
  std::string scene;
  MethodSetting setting;
  float maxSeparation = 0.0f;
  std::uint32_t cropColumns = 0;
  std::optional<double> stereoGpuMs;     // median over the repeats; empty without timestamps
  std::vector<double> stereoGpuMsRuns;
  std::optional<double> centerFrameGpuMs;  // the scene's center frame (median, timed with the eye before this setting)
  std::optional<double> depthReductionGpuMs;  // the disparity budget's depth reduction of that frame (median)
  std::optional<double> disparityMapGpuMs;    // the nonlinear mapping of that frame's depth in place (median)
  std::optional<double> referenceEyeGpuMs;  // the left reference eye at this separation (median, likewise)
  // The untimed eye and center frames run right before those two and this setting were timed
  // (s3d/stereo/interleaved_timing.h): host milliseconds, and whether they had reached a steady speed (false: the warm-up's
  // maximum ended it; always on a CPU device, whose warm-up is its minimum).
  double frameWarmUpMs = 0.0;
  bool frameWarmUpSettled = false;
  stereo::EyeError left{};
  stereo::EyeError right{};
  std::uint64_t filledLeft = 0;  // iterative: disoccluded pixels filled from the background side
  std::uint64_t filledRight = 0;
  stereo::StereoTraffic traffic;
  // Hybrid settings: the masked share of each eye and the GPU time per part (stereoGpuMs is their total).
  std::optional<double> maskedShareLeft, maskedShareRight;
  std::optional<frame::HybridTimings> hybridTimings;
};

struct RendererRow {
  std::string scene;
  std::uint64_t triangles = 0;                // drawn per center frame: every object's mesh, both layers
  std::optional<double> frameGpuMs;           // median whole center frame
  std::vector<renderer::PassTiming> passes;   // median per pass, in the order they ran
  std::uint32_t guardBandColumns = 0;         // per side, `s3d render`'s default band at the options' separation
  std::optional<double> guardBandFrameGpuMs;  // median center frame rendered that much wider
  std::optional<double> guardBandRatio;       // median over `repeat` back-to-back pairs of wide / plain frame time
  // CPU devices: the process's user + system time per center frame (the device's work summed over its threads),
  // which other load on the machine disturbs less than the wall-clock timestamps.
  std::optional<double> cpuTimePerFrameMs;
};

// A masked render of the center view (renderer timings, the first scene only).
struct MaskedRenderRow {
  std::string scene;
  double requestedShare = 0.0;  // of the output pixels
  double shadedShare = 0.0;     // what the mask holds
  std::optional<double> frameGpuMs;
  std::vector<renderer::PassTiming> passes;
};

struct BenchReport {
  std::string deviceName;
  std::string deviceKind;  // "cpu" (e.g. lavapipe) or "gpu": picks the marked section of --results-md
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int repeat = 0;
  bool rendererOnly = false;
  std::string gbufferShading;  // --renderer: the G-buffer shading the timed renderers ran ("raster", "visibility")
  std::string commandLine;  // an `s3d bench` command that reproduces the run
  MethodSetting targetSetting;
  std::optional<double> bandwidthGBs;
  std::vector<BenchRow> rows;              // scene, then separation, then setting, in option order
  std::vector<RendererRow> rendererRows;
  std::vector<MaskedRenderRow> maskedRenderRows;
  double wallSeconds = 0.0;
  std::vector<std::string> filesWritten;   // in the output folder (and the results file, by its path)
};

// Every check runBench makes before creating a GPU resource or file: size, scenes, method settings,
// separations (0 < s <= 25 % and leaving columns to compare), repeat, bandwidth, target setting, output folder,
// and the results file (must exist, markers well formed). Throws std::invalid_argument naming the problem.
void validateBenchOptions(const BenchOptions& options);

// Validates, runs the sweep (or the renderer timings), writes the outputs atomically and returns the report.
BenchReport runBench(vk::Context& context, const BenchOptions& options);

nlohmann::json toJson(const BenchReport& report);
// The tables, targets and traffic estimate; headings start at level 3 so the text fits into RESULTS.md.
std::string benchMarkdown(const BenchReport& report);
// The hybrid rows' section of benchMarkdown (masked share, time per part, error, the hybrid targets); empty
// without hybrid rows.
std::string hybridBenchMarkdown(const BenchReport& report);
// Speed against error: x = stereo pass GPU ms (log scale), y = halo PSNR (mean of both eyes), one labelled
// circle per row with a time, one color per scene.
std::string benchSpeedErrorSvg(const BenchReport& report);
// Speed against whole-image error: x = both eyes' GPU time over one reference eye's (log scale), y = whole-image
// PSNR (mean of both eyes); every row a circle, the hybrid budgets of a scene and separation joined into a curve.
std::string benchTimeOverEyeSvg(const BenchReport& report);

// The line that marks a file as an s3d results file: --results-md writes it into an empty file and refuses a
// non-empty one without it (or a bench section), and any file that does not end in .md.
inline constexpr const char* kResultsFileMarker = "<!-- s3d results: tables between s3d bench markers are generated -->";

// The markers of the section --results-md replaces: "<!-- s3d bench: KIND begin -->" / "... end -->"; the
// renderer mode uses "s3d bench renderer: KIND".
std::string resultsBeginMarker(const std::string& deviceKind, bool rendererOnly);
std::string resultsEndMarker(const std::string& deviceKind, bool rendererOnly);
// Replaces the text between the two marker lines with `section` (everything else stays byte for byte); when
// neither marker is present, appends the marked section at the end. Throws std::invalid_argument when only
// one is present, either repeats, or end comes before begin.
std::string replaceMarkedSection(const std::string& document, const std::string& beginMarker,
                                 const std::string& endMarker, const std::string& section);

// "[#####.....] 12/48 courtyard search-8 sep 2%" (ten cells).
std::string formatProgressBar(const BenchProgress& progress);

}  // namespace s3d::app
