// `s3d render`: renders a built-in scene or a glTF file, synthesizes both eyes with the stereo pass, renders the two-pass
// reference eyes and writes images plus report.json (s3d/app/render_job.h); `--sequence` runs the scene's camera
// path with the comfort controls (s3d/app/sequence_job.h).
#include <cstdio>
#include <exception>
#include <iostream>
#include <set>

#include "cli_support.h"
#include "profile_options.h"
#include "s3d/app/render_job.h"
#include "s3d/app/sequence_job.h"
#include "s3d/app/views_job.h"
#include "s3d/io/output_transaction.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::cli {
namespace {

class RenderCommand final : public Command {
 public:
  // The option table, one declaration per option in --help's order: longer than 80 lines because it is a list.
  explicit RenderCommand(CLI::App& app) {
    subcommand = app.add_subcommand(
        "render",
        "Render a built-in scene, synthesize both eyes with the stereo pass, render the two-pass reference eyes, "
        "compare them and write the selected outputs (default: all) plus report.json");
    CLI::App& render = *subcommand;
    render.add_option("--width", options_.width, "Image width in pixels")
        ->check(CLI::Range(std::uint32_t(1), app::kMaxImageSize))
        ->capture_default_str();
    render.add_option("--height", options_.height, "Image height in pixels")
        ->check(CLI::Range(std::uint32_t(1), app::kMaxImageSize))
        ->capture_default_str();
    render.add_option("--resolution", resolution_, "Image size as WxH, e.g. 1920x1080 (instead of --width/--height)")
        ->check(resolutionValidator(app::kMaxImageSize))
        ->excludes("--width")
        ->excludes("--height");
    render
        .add_option("--scene", options_.scene,
                    "Built-in scene (" + joined(renderer::builtInSceneNames(), ", ") +
                        ") or a glTF 2.0 file (.gltf/.glb, with an optional NAME.scene.json beside it)")
        ->capture_default_str();
    render.add_option("--output", options_.outputFolder, "Output folder (created if missing)")->capture_default_str();
    render
        .add_option("--outputs", outputs_,
                    "Comma-separated subset of the outputs to write (default: all): " + joined(app::kAllOutputs, ","))
        ->delimiter(',')
        ->check(CLI::IsMember(app::kAllOutputs))
        ->type_name("LIST");
    render.add_option("--sbs", sideBySide_, "Side-by-side packing: half (each eye squeezed to half width) or full")
        ->check(CLI::IsMember({"half", "full"}))
        ->capture_default_str();
    render.add_option("--tab", topBottom_, "Top-and-bottom packing: half (each eye squeezed to half height) or full")
        ->check(CLI::IsMember({"half", "full"}))
        ->capture_default_str();
    stereo_.add(render, "world units, metres");
    render
        .add_option("--weapon-depth-offset", stereo_.parameters.weaponDepthOffset,
                    "First-person weapon: depth offset in world units added before stereo (pushes it into the screen)")
        ->check(floatRange(0.0, 1.0e4, false, "a distance in world units"))
        ->capture_default_str();
    render
        .add_option("--weapon-depth-scale", stereo_.parameters.weaponDepthScale,
                    "First-person weapon: depth scale applied before the offset (pushed = offset + scale * depth)")
        ->check(floatRange(0.0, 1.0e4, true, "a positive factor"))
        ->capture_default_str();
    render.add_option("--supersample", options_.supersample,
                      "Anti-aliasing: render at N x N samples per pixel and average them (center view and reference "
                      "eyes alike; the stereo pass sees the nearest sample's depth)")
        ->check(CLI::Range(1, 4))
        ->capture_default_str();
    profile_.add(render);
    addDisparityBudgetOption(render, profile_.disparityBudget);
    render.add_option("--frame", options_.frame, "Frame of the scene's camera path and animation to render (0: its first)")
        ->check(frameNumberValidator())
        ->capture_default_str();
    render
        .add_option("--frames-per-second", options_.framesPerSecond,
                    "Frame rate: frame N (--frame, and every frame of --sequence) is at N / rate seconds of an animated "
                    "glTF scene's first animation (looped over its duration), and --sequence's comfort controls step "
                    "by 1 / rate seconds")
        ->check(floatRange(0.0, 1000.0, true, "frames per second"))
        ->capture_default_str();
    render
        .add_option("--hud", hud_,
                    "HUD drawn into every view at its depth: game (the built-in health and ammo panels and the "
                    "crosshair), none, or auto (game on the built-in scenes, none on a glTF file: your scene, not ours)")
        ->check(CLI::IsMember({"auto", "game", "none"}))
        ->capture_default_str();
    addMemoryLimitOption(render, options_.memoryLimitBytes);
    render.add_flag("--reversed-z", options_.reversedZ,
                    "Reversed-Z depth buffer (cleared to 0, test GREATER, near/far swapped): more depth precision far "
                    "away; the linear depth handed to the stereo pass is the same");
    render.add_flag("--sequence", sequence_,
                    "Render the scene's whole camera path with the comfort controls running (zero-parallax "
                    "control, weapon push, crosshair): anaglyph_NNNN.png per frame and a per-frame report.json");
    render.add_flag("--previous-frame-fill", previousFrameFill_,
                    "With --sequence and --method forward: each frame's disocclusions take the previous frame's eyes, "
                    "reprojected with their depth and the camera's motion, where that frame saw them");
    render.add_option("--views", viewsFile_,
                      "Per-eye views as OpenXR reports them (JSON: eye x offsets in metres, angleLeft/Right/Up/Down, "
                      "size per eye, worldScale; samples/views/): render the center view covering both eyes, "
                      "synthesize each eye in its own projection and compare with the eyes rendered directly; each "
                      "eye's comfort is reported on the display of --display or --profile (else " +
                          app::ViewsJobOptions{}.display.name +
                          "). A display profile with eyeViews (samples/views/headset-display.json) does the same "
                          "for its own views in a single frame");
    addDeviceOptions(render, contextOptions_);
    render.add_flag("--list-devices", listDevicesOnly_,
                    "List the Vulkan devices and whether s3d can use them, then exit without rendering");
  }

  int run() override {
    if (listDevicesOnly_) {
      listDevices();
      return 0;
    }
    // Per-eye views: a --views file, or in a single frame a display that reports its own (a display profile's
    // eyeViews, from --display or the --profile's display).
    const bool displayViews =
        viewsFile_.empty() && !sequence_ && displayGiven() && profile_.resolveDisplay(*subcommand).eyeViews;
    // Options that do nothing in the chosen mode are errors naming the mode.
    if (!viewsFile_.empty() || displayViews)
      rejectGiven(*subcommand,
                  {"--sequence", "--previous-frame-fill", "--width", "--height", "--resolution", "--outputs", "--sbs",
                   "--tab", "--max-separation", "--zero-parallax-distance", "--edge-crop", "--method", "--taps",
                   "--iterations", "--hybrid-budget", "--hybrid-base", "--hybrid-cell", "--hybrid-score-floor",
                   "--weapon-depth-offset", "--weapon-depth-scale",
                   "--supersample", "--save-profile", "--allow-negative-parallax", "--disparity-budget",
                   "--disparity-mapping", "--reversed-z", "--hud"},
                  std::string("does not apply to ") +
                      (displayViews ? "a display with eye views (each eye's size, projection and offset come from "
                                      "the display profile's eyeViews"
                                    : "--views (each eye's size, projection and offset come from the views file") +
                      "; the eyes are synthesized by the views' own depth search and compared with the eyes rendered "
                      "directly; only the display, --display or a --profile's, applies: its focal distance for the "
                      "comfort report)");
    if (sequence_)
      rejectGiven(*subcommand, {"--outputs", "--sbs", "--tab", "--frame", "--hud"},
                  "does not apply to --sequence (it renders every frame of the camera path and writes "
                  "anaglyph_NNNN.png per frame and report.json, without the HUD)");
    else
      rejectGiven(*subcommand, {"--previous-frame-fill"}, "applies to --sequence (a single frame has no previous one)");
    if (!resolution_.empty()) parseResolution(resolution_, app::kMaxImageSize, options_.width, options_.height);
    options_.outputs = std::set<std::string>(outputs_.begin(), outputs_.end());
    if (!options_.outputs.count("sbs.png")) rejectGiven(*subcommand, {"--sbs"}, "packs sbs.png, which --outputs leaves out");
    if (!options_.outputs.count("tab.png")) rejectGiven(*subcommand, {"--tab"}, "packs tab.png, which --outputs leaves out");
    options_.sideBySide = stereo::parsePackingMode(sideBySide_);
    options_.topBottom = stereo::parsePackingMode(topBottom_);
    options_.hud = app::parseHudMode(hud_);
    requireOutputsAreNotInputs(!viewsFile_.empty() || displayViews);
    if (!viewsFile_.empty() || displayViews) return runViews();
    stereo_.finish();
    StereoOptions::rejectSeparationUnderBudget(*subcommand, profile_.disparityBudget);
    const comfort::ComfortProfile profile = profile_.resolve(*subcommand, stereo_);
    StereoOptions::requireMethodOptionsApply(*subcommand, profile.stereo);
    profile_.resolved = profile;  // --save-profile writes it once the run succeeded
    options_.stereo = profile.stereo;
    options_.display = profile.display;
    options_.crosshair = profile.crosshair;
    options_.allowNegativeParallax = profile.allowNegativeParallax;
    options_.disparityBudget = profile_.budgetRule();
    zeroParallax_ = profile.zeroParallaxSettings();
    if (previousFrameFill_) {
      if (options_.stereo.method != stereo::StereoMethod::Forward)
        rejectGiven(*subcommand, {"--previous-frame-fill"},
                    std::string("applies to --method forward (the method is ") +
                        stereo::methodName(options_.stereo.method) + ")");
      if (options_.stereo.disparityMapping == stereo::DisparityMapping::Nonlinear)
        rejectGiven(*subcommand, {"--previous-frame-fill"},
                    "does not work with " + profile_.mappingSource(*subcommand) +
                        " (the fill reprojects the previous eyes as views of one pair of eye cameras; a nonlinear "
                        "map has one per segment of its curve)");
      options_.stereo.previousFrameFill = true;
    }
    return sequence_ ? runSequence() : runSingleFrame();
  }

 private:
  // Every file the run writes against every file it reads, before anything is written.
  void requireOutputsAreNotInputs(bool views) const {
    RunFiles files;
    if (views)  // app::runViewsJob's files
      files.writeInFolder(options_.outputFolder, {"center.png", "left.png", "right.png", "left_reference.png",
                                                  "right_reference.png", "report.json"});
    else if (sequence_)  // app::runSequenceJob's files
      files.writeInFolder(options_.outputFolder, {"anaglyph_*.png", "report.json"});
    else
      files.writeInFolder(options_.outputFolder, {options_.outputs.begin(), options_.outputs.end()});
    profile_.addFiles(*subcommand, files);
    files.read(viewsFile_, "--views");
    files.readScene(options_.scene, "--scene");
    files.check();
  }

  bool displayGiven() const { return subcommand->count("--display") > 0 || !profile_.load.empty(); }

  // Before the Vulkan start-up: the host's share of the estimate (all of it on the CPU device).
  void requireHostMemory(const frame::MemoryEstimate& estimate) const {
    frame::requireHostMemory(estimate, options_.memoryLimitBytes, contextOptions_.device == "cpu");
  }

  int runViews() {
    app::ViewsJobOptions viewsOptions;
    viewsOptions.memoryLimitBytes = options_.memoryLimitBytes;
    // The comfort report's display: the one given (--display or a profile's), else the head-mounted display.
    if (displayGiven()) viewsOptions.display = profile_.resolveDisplay(*subcommand);
    if (!viewsFile_.empty()) {
      viewsOptions.views = comfort::loadViewConfiguration(viewsFile_);  // one error naming the file and field
      viewsOptions.viewsFile = viewsFile_;
    } else {  // the display reports its own per-eye views
      viewsOptions.views = *viewsOptions.display.eyeViews;
      viewsOptions.viewsFile = "display profile " + viewsOptions.display.name;
    }
    viewsOptions.scene = options_.scene;
    viewsOptions.frame = options_.frame;
    viewsOptions.framesPerSecond = options_.framesPerSecond;
    viewsOptions.outputFolder = options_.outputFolder;
    vk::Context context(contextOptions_);
    io::OutputTransaction outputs(options_.outputFolder);  // all files or none
    const app::ViewsReport report = app::runViewsJob(context, viewsOptions);
    outputs.commit();
    std::printf("s3d render --views: scene %s, center view %ux%u on %s; synthesized vs reference: left %.2f dB, "
                "right %.2f dB; beyond the 1-degree rule at %.2f m (%s): left %.1f %%, right %.1f %%; wrote %zu "
                "files to %s\n",
                report.scene.c_str(), report.center.width, report.center.height, report.deviceName.c_str(),
                report.error[0].psnrDb, report.error[1].psnrDb, double(report.display.viewingDistanceMeters),
                report.display.name.c_str(), 100.0 * report.comfort[0].shareBeyondOneDegree,
                100.0 * report.comfort[1].shareBeyondOneDegree, report.filesWritten.size(),
                options_.outputFolder.string().c_str());
    return 0;
  }

  int runSequence() {
    app::SequenceJobOptions sequenceOptions;
    sequenceOptions.width = options_.width;
    sequenceOptions.height = options_.height;
    sequenceOptions.scene = options_.scene;
    sequenceOptions.supersample = options_.supersample;
    sequenceOptions.framesPerSecond = options_.framesPerSecond;
    sequenceOptions.outputFolder = options_.outputFolder;
    sequenceOptions.stereo = options_.stereo;
    sequenceOptions.zeroParallax = zeroParallax_;
    sequenceOptions.crosshair = options_.crosshair;
    sequenceOptions.display = options_.display;
    sequenceOptions.allowNegativeParallax = options_.allowNegativeParallax;
    sequenceOptions.reversedZ = options_.reversedZ;
    sequenceOptions.disparityBudget = options_.disparityBudget;
    sequenceOptions.memoryLimitBytes = options_.memoryLimitBytes;
    requireHostMemory(app::sequenceMemoryEstimate(sequenceOptions));
    vk::Context context(contextOptions_);
    io::OutputTransaction outputs(options_.outputFolder);  // all files or none
    const app::SequenceReport report = app::runSequenceJob(context, sequenceOptions);
    outputs.commit();
    profile_.saveAfterSuccess();
    std::uint64_t conflicts = 0;
    for (const app::SequenceFrame& frame : report.frames) conflicts += frame.weaponConflictPixels;
    std::cout << "s3d render --sequence: scene " << report.scene << ", " << report.frames.size() << " frames on "
              << report.deviceName << ", weapon/world conflict pixels " << conflicts << ", wrote "
              << report.filesWritten.size() << " files to " << options_.outputFolder.string() << '\n';
    return 0;
  }

  int runSingleFrame() {
    // Options first: a typo must not cost a Vulkan start-up, and must leave no files behind.
    requireHostMemory(app::renderJobMemoryEstimate(options_));  // validates every option on the way
    vk::Context context(contextOptions_);
    // With --validation, the layer's messages explain failures and are themselves failures.
    const StagedRun run = runStaged(context, options_.outputFolder, [&] { return app::runRenderJob(context, options_); });
    if (!run.report) return fail(run.error);
    for (const std::string& warning : run.report->warnings) warn(warning);
    printSummary(*run.report);
    if (run.validationMessages > 0) return failValidation(run.validationMessages);
    profile_.saveAfterSuccess();
    return 0;
  }

  void printSummary(const app::RenderReport& report) const {
    std::cout << "s3d render: scene " << report.scene << ", " << report.width << "x" << report.height << " on "
              << report.deviceName << '\n';
    std::cout << "  GPU time: center frame " << formatMs(report.centerFrameGpuMs) << ", stereo pass "
              << formatMs(report.stereoPassGpuMs) << ", reference eye " << formatMs(report.referenceEyeGpuMs);
    if (report.stereoPassGpuMs && report.referenceEyeGpuMs && *report.referenceEyeGpuMs > 0.0) {
      char ratio[32];
      std::snprintf(ratio, sizeof(ratio), "%.3f", *report.stereoPassGpuMs / *report.referenceEyeGpuMs);
      std::cout << " (stereo pass / reference eye = " << ratio << ')';
    }
    std::cout << '\n';
    char line[160];
    std::snprintf(line, sizeof(line),
                  "  synthesized vs reference (%u border columns excluded): left %.2f dB, right %.2f dB\n",
                  report.cropColumns, report.left.display.psnrDb, report.right.display.psnrDb);
    std::cout << line;
    const std::size_t count = report.filesWritten.size();
    std::cout << "  wrote " << count << (count == 1 ? " file" : " files") << " to " << options_.outputFolder.string()
              << '\n';
  }

  app::RenderJobOptions options_;
  std::string viewsFile_;
  StereoOptions stereo_;
  ProfileOptions profile_;
  comfort::ZeroParallaxControlSettings zeroParallax_;
  vk::ContextOptions contextOptions_;
  std::string resolution_;
  std::vector<std::string> outputs_{app::kAllOutputs};
  std::string sideBySide_ = "half";
  std::string topBottom_ = "half";
  std::string hud_ = app::hudModeName(app::RenderJobOptions{}.hud);
  bool sequence_ = false;
  bool previousFrameFill_ = false;
  bool listDevicesOnly_ = false;
};

}  // namespace

std::unique_ptr<Command> addRenderCommand(CLI::App& app) { return std::make_unique<RenderCommand>(app); }

}  // namespace s3d::cli
