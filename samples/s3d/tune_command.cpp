// `s3d tune`: the comfort-parameter tuning tool: a window with the live stereo view and a panel of every stereo
// and comfort parameter (s3d/tune/tune_window.h); scriptable for tests and screenshots (s3d/tune/tune_script.h).
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli_support.h"
#include "profile_options.h"
#include "s3d/app/render_job.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/renderer/scene.h"
#include "s3d/tune/tune_window.h"

namespace s3d::cli {
namespace {

// The exit status when no window can be opened: the automake/ctest "skipped" code, so a test run without a
// display reports a skip instead of a failure.
constexpr int kNoDisplayExitCode = 77;

class TuneCommand final : public Command {
 public:
  explicit TuneCommand(CLI::App& app) {
    subcommand = app.add_subcommand(
        "tune",
        "Open the comfort-tuning window: live stereo view (anaglyph, side-by-side, eyes, two-pass reference, error, "
        "parallax and comfort heat maps), sliders for every stereo and comfort parameter, camera control, GPU "
        "times, error and comfort numbers, comfort profiles. Exits with status 77 when no window can be opened");
    CLI::App& tune = *subcommand;
    resolution_ = std::to_string(options_.width) + "x" + std::to_string(options_.height);
    hud_ = app::hudModeName(options_.state.hud);
    tune.add_option("--resolution", resolution_, "View size as WxH (the window adds the panel)")
        ->check(resolutionValidator(app::kMaxImageSize))
        ->capture_default_str();
    tune.add_option("--scene", options_.state.scene, "Built-in scene: " + joined(renderer::builtInSceneNames(), ", "))
        ->check(CLI::IsMember(renderer::builtInSceneNames()))
        ->capture_default_str();
    tune.add_option("--frame", frame_, "Start at this frame of the scene's camera path")
        ->check(frameNumberValidator())
        ->capture_default_str();
    tune.add_option("--hud", hud_, "HUD: game (the built-in panels and crosshair), none, or auto (game on the built-in scenes)")
        ->check(CLI::IsMember({"auto", "game", "none"}))
        ->capture_default_str();
    tune.add_option("--view", view_, "View mode: " + joined(tune::viewModeNames(), ", "))
        ->check(CLI::IsMember(tune::viewModeNames()))
        ->capture_default_str();
    stereo_.add(tune, "world units, metres");
    tune.add_option("--weapon-depth-offset", stereo_.parameters.weaponDepthOffset,
                    "First-person weapon: depth offset in world units added before stereo")
        ->check(floatRange(0.0, 1.0e4, false, "a distance in world units"))
        ->capture_default_str();
    tune.add_option("--weapon-depth-scale", stereo_.parameters.weaponDepthScale,
                    "First-person weapon: depth scale applied before the offset")
        ->check(floatRange(0.0, 1.0e4, true, "a positive factor"))
        ->capture_default_str();
    profile_.add(tune);  // --profile, --save-profile, --allow-negative-parallax, --display (as `s3d render`)
    addDisparityBudgetOption(tune, profile_.disparityBudget);
    tune.add_option("--set", sets_, "NAME=VALUE for any panel parameter (" + joined(tune::parameterNames(), ", ") +
                                        "); repeatable, applied last")
        ->type_name("NAME=VALUE");
    tune.add_option("--supersample", options_.state.supersample,
                    "Renderer anti-aliasing: every pass before the resolve at N x the view size (1 to 4)")
        ->check(CLI::Range(1, 4))
        ->capture_default_str();
    tune.add_flag("--no-reference", noReference_,
                  "Do not render the two-pass reference every frame (only for the reference and error views)");
    tune.add_option("--script", script_, "Scripted input, one command per line (see docs/DESIGN.md, s3d tune)")
        ->check(CLI::ExistingFile);
    tune.add_option("--frames", frames_, "Quit after this many frames")->check(CLI::Range(std::size_t(1), std::size_t(1000000)));
    tune.add_option("--screenshot", screenshot_, "PNG of the whole window at the last frame (--frames) or at quit");
    addMemoryLimitOption(tune, memoryLimit_);
    addDeviceOptions(tune, options_.context);
  }

  int run() override {
    parseResolution(resolution_, app::kMaxImageSize, options_.width, options_.height);
    stereo_.finish();
    StereoOptions::rejectSeparationUnderBudget(*subcommand, profile_.disparityBudget);
    // The view's frame (the edges cropped, no guard band) before the window and the Vulkan start-up; the panel
    // can switch to the hybrid method at any time, so its eye renderer is counted.
    frame::requireHostMemory(frame::renderMemoryEstimate(options_.width, options_.height, options_.width,
                                                     options_.state.supersample, true),
                           memoryLimit_, options_.context.device == "cpu");
    options_.state.hud = app::parseHudMode(hud_);
    tune::TuneSettings& settings = options_.state.settings;
    settings.profile = profile_.resolve(*subcommand, stereo_);  // the profile, with the options given here over it
    for (const std::string& assignment : sets_) {
      const std::size_t equals = assignment.find('=');
      if (equals == std::string::npos) return fail("--set expects NAME=VALUE (got '" + assignment + "')");
      tune::setParameter(settings, assignment.substr(0, equals), assignment.substr(equals + 1));
    }
    profile_.resolved = settings.profile;  // --save-profile writes it once the window closed without errors
    RunFiles files;
    profile_.addFiles(*subcommand, files);
    files.write(screenshot_, "--screenshot");
    files.read(script_, "--script");
    files.check();
    if (!profile_.save.empty()) options_.profileFile = profile_.save;
    else if (!profile_.load.empty()) options_.profileFile = profile_.load;
    options_.state.view = tune::parseViewMode(view_);
    options_.state.disparityBudget = profile_.budgetRule();
    options_.state.reference = !noReference_;
    options_.state.pathFrame = frame_;
    if (!script_.empty()) options_.script = script_;
    if (frames_ > 0) options_.frames = frames_;
    if (!screenshot_.empty()) options_.screenshot = screenshot_;
    const FileState before = fileState(profile_.save);
    try {
      const tune::TuneWindowResult result = tune::runTuneWindow(options_);
      for (const std::string& message : result.validationMessages) std::cerr << "s3d: validation: " << oneLine(message) << '\n';
      std::cout << "s3d tune: " << result.frames << (result.frames == 1 ? " frame" : " frames") << " on "
                << result.deviceName << '\n';
      if (!result.validationMessages.empty())
        return failValidation(result.validationMessages.size());
      if (!sessionWrote(profile_.save, before)) profile_.saveAfterSuccess();
      return 0;
    } catch (const tune::NoDisplayError& error) {
      fail(error.what());
      return kNoDisplayExitCode;
    }
  }

 private:
  // The session's own Save (panel or script) to the --save-profile file is newer than the command line's profile:
  // a file changed during the run is kept.
  using FileState = std::optional<std::filesystem::file_time_type>;
  static FileState fileState(const std::filesystem::path& file) {
    std::error_code error;
    if (file.empty()) return std::nullopt;
    const auto time = std::filesystem::last_write_time(file, error);
    return error ? FileState() : FileState(time);
  }
  static bool sessionWrote(const std::filesystem::path& file, const FileState& before) {
    return fileState(file) != before;
  }

  tune::TuneWindowOptions options_;
  StereoOptions stereo_;
  std::string resolution_;  // the defaults of options_ (TuneWindowOptions), set first in the constructor
  std::size_t frame_ = 0;
  std::string view_ = "anaglyph";
  std::string hud_;
  std::optional<std::uint64_t> memoryLimit_;
  ProfileOptions profile_;
  std::vector<std::string> sets_;
  bool noReference_ = false;
  std::string script_;
  std::size_t frames_ = 0;
  std::string screenshot_;
};

}  // namespace

std::unique_ptr<Command> addTuneCommand(CLI::App& app) { return std::make_unique<TuneCommand>(app); }

}  // namespace s3d::cli
