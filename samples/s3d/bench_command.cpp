// `s3d bench`: GPU time and error of every stereo method setting on every built-in scene and separation, against
// the center frame and one two-pass reference eye (s3d/app/bench_job.h); `--renderer` times the deferred
// renderer's passes per scene instead. Progress goes to stderr: one redrawn bar on a terminal, a line per step
// otherwise (CI logs).
#include <unistd.h>  // isatty

#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <string>

#include "cli_support.h"
#include "s3d/app/bench_job.h"
#include "s3d/app/render_job.h"
#include "s3d/app/sequence_bench.h"
#include "s3d/io/output_transaction.h"
#include "s3d/renderer/scene.h"

namespace s3d::cli {
namespace {

class BenchCommand final : public Command {
 public:
  // The option table, one declaration per option in --help's order: longer than 80 lines because it is a list.
  explicit BenchCommand(CLI::App& app) {
    subcommand = app.add_subcommand(
        "bench",
        "Time every stereo method setting (GPU timestamps, median of --repeat) on every built-in scene and "
        "separation, measure its error against the two-pass reference, and write bench.json, bench.md and "
        "bench_speed_vs_error.svg; --renderer times the renderer's passes instead");
    CLI::App& bench = *subcommand;
    bench
        .add_option("--resolution", resolution_,
                    "Image size as WxH (default: 1920x1080, with --renderer 1280x720)")
        ->check(resolutionValidator(app::kMaxImageSize));
    bench.add_option("--scenes", options_.scenes,
                     "Comma-separated scenes (default: all built-in ones): built-in names (" + joined(renderer::builtInSceneNames(), ", ") + ") or .gltf/.glb files")
        ->delimiter(',')
        ->type_name("LIST");
    bench
        .add_option("--methods", options_.methods,
                    "Comma-separated method settings: seed, forward, search-N (N taps), iterative-K (K iterations), hybrid-B "
                    "(hybrid budget B in [0, 1], search-4 base); search, iterative and hybrid alone sweep taps 4,8,16, "
                    "iterations 2,4,6,8 and budgets 0,0.02,0.05,0.1,0.2,0.5,0.6,1; a /pixel or /tiles suffix (search-4/pixel) "
                    "forces the per-pixel or the row-tiled kernel (default: the library's choice, " +
                        std::string(stereo::kernelName(stereo::StereoParameters{}.kernel)) +
                        ": per pixel, as row tiles measured slower)")
        ->delimiter(',')
        ->type_name("LIST")
        ->capture_default_str();
    bench
        .add_option("--separations", options_.separationsPercent,
                    "Comma-separated maxSeparation values in percent of the screen width, each in (0, 25]")
        ->delimiter(',')
        ->type_name("LIST")
        ->capture_default_str();
    bench.add_option("--repeat", options_.repeat, "GPU timings per number; the median is reported")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    bench.add_option("--supersample", options_.supersample,
                     "Anti-aliasing of the center view and the reference eyes: N x N samples per pixel")
        ->check(CLI::Range(1, 4))
        ->capture_default_str();
    const app::SequenceBenchOptions sequenceDefaults;
    bench.add_flag("--sequence", sequence_,
                   "Run each scene's camera path (default --scenes: " + joined(sequenceDefaults.scenes, ",") +
                       "; --resolution " + std::to_string(sequenceDefaults.width) + "x" +
                       std::to_string(sequenceDefaults.height) + ") with every method setting (default --methods: " +
                       joined(sequenceDefaults.methods, ",") +
                       "; a +previous suffix on forward: the previous-frame fill) and the comfort controls of `s3d "
                       "render --sequence`, and report per setting the temporal flicker, the mean PSNR and the stereo "
                       "pass's GPU time (sequence_bench.md, sequence_bench.json)");
    bench.add_flag("--renderer", options_.rendererOnly,
                   "Time the center frame and each renderer pass per scene instead of the stereo sweep");
    bench
        .add_option_function<std::string>(
            "--gbuffer-shading",
            [this](const std::string& name) {
              const auto shading = renderer::gbufferShadingFromName(name);
              if (!shading) throw CLI::ValidationError("--gbuffer-shading", "must be auto, raster or visibility (got '" + name + "')");
              options_.gbufferShading = *shading;
            },
            "With --renderer: how the G-buffer pass shades: auto (visibility on a GPU, raster on a CPU device), raster "
            "(the fragment shader writes normal and material) or visibility (triangle ids, then a compute resolve)")
        ->type_name("auto|raster|visibility");
    bench
        .add_option_function<std::string>(
            "--hybrid-surfaces",
            [this](const std::string& name) {
              const auto surfaces = frame::hybridSurfacesFromName(name);
              if (!surfaces)
                throw CLI::ValidationError("--hybrid-surfaces",
                                           "must be auto, raster, raycast, raycast-region or mixed (got '" + name + "')");
              options_.hybridSurfaces = *surfaces;
            },
            "How the hybrid settings find their eye pixels' surfaces: auto (ray casting where the eye renderer can "
            "shade what rays find: a GPU's visibility shading, timing rays, raster and mixed on each scene's first "
            "frame and keeping the fastest; else rasterized), "
            "raster, raycast (the eye renderer made to shade rays: visibility shading and the compute transparent "
            "pass, also on a CPU device; with ambient occlusion only the masked pixels are cast, the occlusion's "
            "region around them takes the center's depth where the base samples) or raycast-region (as raycast, "
            "but the occlusion's whole region is cast) or mixed (the left eye rasterized, the right eye's pixels cast: "
            "on a GPU the two render at once, the rays on the compute queue)")
        ->type_name("auto|raster|raycast|raycast-region|mixed");
    bench.add_flag("--hybrid-eyes-in-turn", options_.hybridEyesInTurn,
                   "Render the hybrid settings' eyes one after the other with one eye renderer, also on a GPU with a "
                   "compute queue, where ray-cast eyes otherwise render at once (two eye renderers)");
    addHybridClassificationOptions(bench, options_.stereo, "The hybrid settings' classification");
    bench
        .add_option("--bandwidth-gbs", bandwidth_,
                    "Memory bandwidth of the device in GB/s for the memory-traffic target (H100 SXM: 3350, "
                    "H100 PCIe: 2000); without it that target is skipped")
        ->check(floatRange(0.0, 1.0e6, true, "a bandwidth in GB/s"));
    bench.add_option("--target-setting", options_.targetSetting,
                     "The setting the speed and error targets judge (default: the library's default method, " +
                         app::defaultMethodSetting().name() + ")");
    bench.add_option("--output", options_.outputFolder, "Output folder (created if missing)")->capture_default_str();
    bench.add_option("--results-md", resultsMarkdown_,
                     "Markdown file (.md) whose section between '<!-- s3d bench: KIND begin -->' and '... end -->' "
                     "(KIND: cpu or gpu; 's3d bench renderer: KIND' with --renderer) is replaced by the tables "
                     "(appended when the file has no such section). It must be empty (it then gets the line '" +
                         std::string(app::kResultsFileMarker) +
                         "') or an s3d results file: that line or a bench section in it");
    addMemoryLimitOption(bench, options_.memoryLimitBytes);
    addDeviceOptions(bench, contextOptions_);
  }

  int run() override {
    if (sequence_) return runSequence();
    if (options_.rendererOnly)
      rejectGiven(*subcommand, {"--methods", "--separations", "--bandwidth-gbs", "--target-setting"},
                  "belongs to the stereo sweep: it does not apply to --renderer (the renderer's passes per scene)");
    if (resolution_.empty()) resolution_ = options_.rendererOnly ? "1280x720" : "1920x1080";
    parseResolution(resolution_, app::kMaxImageSize, options_.width, options_.height);
    if (bandwidth_) options_.bandwidthGBs = *bandwidth_;
    if (!resultsMarkdown_.empty()) options_.resultsMarkdown = resultsMarkdown_;
    // Options first: a typo must not cost a Vulkan start-up or a half-hour sweep, and must leave no files behind.
    app::validateBenchOptions(options_);
    RunFiles files;  // app::runBench's files
    files.writeInFolder(options_.outputFolder, {"bench.md", "bench.json"});
    if (!options_.rendererOnly)
      files.writeInFolder(options_.outputFolder, {"bench_speed_vs_error.svg", "bench_time_over_eye.svg"});
    files.write(resultsMarkdown_, "--results-md");
    files.check();
    frame::requireHostMemory(app::benchMemoryEstimate(options_), options_.memoryLimitBytes, contextOptions_.device == "cpu");
    vk::Context context(contextOptions_);
    std::cerr << "s3d bench: " << context.deviceName() << " (" << (context.isCpuDevice() ? "cpu" : "gpu") << "), "
              << options_.width << "x" << options_.height << '\n';
    const bool terminal = ::isatty(::fileno(stderr)) != 0;
    std::size_t previousLength = 0;
    options_.progress = progressPrinter(terminal, previousLength);

    const StagedRun run = runStaged(context, options_.outputFolder, [&] { return app::runBench(context, options_); });
    if (!run.report) return fail(run.error);
    const app::BenchReport* report = &*run.report;
    if (report->rendererOnly) std::cout << app::benchMarkdown(*report);
    char wall[32];
    std::snprintf(wall, sizeof(wall), "%.1f", report->wallSeconds);
    std::cout << "s3d bench: " << (report->rendererOnly ? report->rendererRows.size() : report->rows.size())
              << " rows on " << report->deviceName << " in " << wall << " s; wrote " << joined(report->filesWritten, ", ")
              << " (in " << options_.outputFolder.string() << ")\n";
    if (run.validationMessages > 0) return failValidation(run.validationMessages);
    return 0;
  }

 private:
  // Progress on stderr: one bar redrawn in place on a terminal, a line per step otherwise (CI logs).
  static std::function<void(const app::BenchProgress&)> progressPrinter(bool terminal, std::size_t& previousLength) {
    return [terminal, &previousLength](const app::BenchProgress& progress) {
      const std::string line = app::formatProgressBar(progress);
      if (terminal) {  // spaces wipe the rest of a longer previous line
        std::cerr << '\r' << line << std::string(previousLength > line.size() ? previousLength - line.size() : 0, ' ');
        if (progress.done == progress.total) std::cerr << '\n';
        std::cerr.flush();
        previousLength = line.size();
      } else {
        std::cerr << line << '\n';
      }
    };
  }

  int runSequence() {
    rejectGiven(*subcommand,
                {"--renderer", "--separations", "--repeat", "--bandwidth-gbs", "--target-setting", "--results-md"},
                "does not apply to --sequence (each setting runs the camera path once, the disparity budget choosing "
                "the separation every frame; the tables go to sequence_bench.md)");
    app::SequenceBenchOptions sequence;
    if (!resolution_.empty()) parseResolution(resolution_, app::kMaxImageSize, sequence.width, sequence.height);
    if (!options_.scenes.empty()) sequence.scenes = options_.scenes;
    if (subcommand->count("--methods") > 0) sequence.methods = options_.methods;
    sequence.supersample = options_.supersample;
    sequence.outputFolder = options_.outputFolder;
    // As `s3d render --sequence` runs by default: the disparity budget on the default display.
    sequence.sequence.disparityBudget = comfort::DisparityBudgetRule::OneDegree;
    sequence.sequence.memoryLimitBytes = options_.memoryLimitBytes;
    // Options first: a typo must not cost a Vulkan start-up, and must leave no files behind.
    app::validateSequenceBenchOptions(sequence);
    RunFiles files;  // app::runSequenceBench's files
    files.writeInFolder(options_.outputFolder, {"sequence_bench.json", "sequence_bench.md"});
    files.check();
    frame::requireHostMemory(app::sequenceBenchMemoryEstimate(sequence), options_.memoryLimitBytes,
                           contextOptions_.device == "cpu");
    vk::Context context(contextOptions_);
    std::cerr << "s3d bench --sequence: " << context.deviceName() << ", " << sequence.width << "x" << sequence.height << '\n';
    std::size_t previousLength = 0;
    sequence.progress = progressPrinter(::isatty(::fileno(stderr)) != 0, previousLength);
    const StagedRun run =
        runStaged(context, options_.outputFolder, [&] { return app::runSequenceBench(context, sequence); });
    if (!run.report) return fail(run.error);
    const app::SequenceBenchReport* report = &*run.report;
    std::cout << app::sequenceBenchMarkdown(*report);
    char wall[32];
    std::snprintf(wall, sizeof(wall), "%.1f", report->wallSeconds);
    std::cout << "s3d bench --sequence: " << report->rows.size() << " rows on " << report->deviceName << " in " << wall
              << " s; wrote " << joined(report->filesWritten, ", ") << " (in " << options_.outputFolder.string() << ")\n";
    if (run.validationMessages > 0) return failValidation(run.validationMessages);
    return 0;
  }

  bool sequence_ = false;
  app::BenchOptions options_;
  vk::ContextOptions contextOptions_;
  std::string resolution_;
  std::optional<double> bandwidth_;
  std::string resultsMarkdown_;
};

}  // namespace

std::unique_ptr<Command> addBenchCommand(CLI::App& app) { return std::make_unique<BenchCommand>(app); }

}  // namespace s3d::cli
