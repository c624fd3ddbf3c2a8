// `s3d convert`: synthesizes the eyes of an external color + depth (or disparity) frame, or of a folder of
// frames (s3d/app/convert_job.h).
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "cli_support.h"
#include "profile_options.h"
#include "s3d/io/output_transaction.h"
#include "s3d/app/convert_job.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::cli {
namespace {

// One line redrawn in place on a terminal ("[#####.....] 12/40 frame 0012"); nothing when stderr is a file.
void drawProgress(std::size_t done, std::size_t total, const std::string& key) {
  if (!::isatty(STDERR_FILENO)) return;
  constexpr std::size_t kBarWidth = 30;
  const std::size_t filled = total ? done * kBarWidth / total : kBarWidth;
  std::cerr << "\r[" << std::string(filled, '#') << std::string(kBarWidth - filled, '.') << "] " << done << '/' << total
            << " frame " << key << (done == total ? "\n" : "") << std::flush;
}

class ConvertCommand final : public Command {
 public:
  // The option table, one declaration per option in --help's order: longer than 80 lines because it is a list.
  explicit ConvertCommand(CLI::App& app) {
    subcommand = app.add_subcommand(
        "convert",
        "Synthesize a stereo pair from an existing frame: a color image and its depth (from any renderer or "
        "capture), or a color image and its disparity map. Writes left.png, right.png, anaglyph.png, sbs.png, "
        "tab.png and report.json. Depth sign convention: the left eye shows a point of parallax p (maxSeparation * "
        "(1 - zeroParallaxDistance / depth), a fraction of the width) p * width pixels left of where the input shows "
        "it, the right eye as far right. Disparity sign convention: d = xLeft - xRight in pixels (>= 0 for parallel "
        "cameras); with --disparity-output right the input is the left view and the right view shows each pixel at "
        "x - d; with left the input is the right view and the left view shows each pixel at x + d; a larger "
        "disparity is nearer and wins where two pixels land on one. Unknown depth or disparity (NaN, zero or "
        "negative depth, +-inf disparity, 0 in a 16-bit PNG) takes the background's value beside it on its row and "
        "is counted in report.json (sanitized.unknownDepthPixels)");
    CLI::App& convert = *subcommand;
    convert.add_option("--color", options_.color,
                       "Color image: .png (display-encoded) or .exr (linear; clamped and sRGB-encoded)");
    auto* depth = convert.add_option(
        "--depth", options_.depth,
        "Depth: .exr (channel --depth-channel; may be the color file), 16-bit grey .png (see --depth-scale) or "
        "1-channel .pfm");
    auto* disparity = convert.add_option(
        "--disparity", disparityFile_,
        "Disparity map in pixels instead of depth (.exr channel, 16-bit .png times --depth-scale, or .pfm); the "
        "output is the other view of the stereo pair (see the sign convention above)");
    disparity->excludes(depth);
    convert.add_option("--disparity-output", disparityOutput_,
                       "With a disparity map: right (the input is the left view) or left (the input is the right view)")
        ->check(CLI::IsMember({"right", "left"}))
        ->capture_default_str();
    convert.add_option("--depth-channel", options_.depthChannel, "EXR channel holding depth or disparity")
        ->capture_default_str();
    convert
        .add_option("--depth-scale", options_.depthScale,
                    "16-bit PNG: world units (or disparity pixels) per step; 65535 is sky, 0 is unknown. Hardware "
                    "depth PNGs are read as value / 65535 instead")
        ->check(floatRange(0.0, 1.0e9, true, "units per step"))
        ->capture_default_str();
    convert
        .add_option("--depth-kind", depthKind_,
                    "linear (planar view depth in world units; >= 1e30 or inf is sky), distance (distance from the "
                    "camera centre along each ray; needs --fov-y or --focal-px) or hardware (zero-to-one perspective "
                    "depth; needs --near and --far; 1 is sky)")
        ->check(CLI::IsMember({"linear", "distance", "hardware"}))
        ->capture_default_str();
    convert.add_option("--near", options_.nearPlane, "Near plane of the projection, for --depth-kind hardware");
    convert.add_option("--far", options_.farPlane, "Far plane of the projection, for --depth-kind hardware");
    auto* fov = convert.add_option("--fov-y", fovY_, "Vertical field of view in degrees, for --depth-kind distance")
                    ->check(floatRange(0.0, 180.0, true, "degrees", true));
    convert.add_option("--focal-px", focalPx_, "Focal length in pixels, for --depth-kind distance")
        ->check(floatRange(0.0, 1.0e7, true, "pixels"))
        ->excludes(fov);
    convert.add_option("--input-folder", inputFolder_,
                       "Folder mode: convert every frame of a sequence (pairs files by --color-pattern and "
                       "--depth-pattern / --disparity-pattern); outputs are left_KEY.png, ... and one report.json")
        ->excludes("--color")
        ->excludes(depth)
        ->excludes(disparity);
    convert.add_option("--color-pattern", colorPattern_, "Folder mode: color file names, '*' is the frame key")
        ->capture_default_str();
    auto* depthPattern =
        convert.add_option("--depth-pattern", depthPattern_, "Folder mode: depth file names, '*' is the frame key")
            ->capture_default_str();
    convert.add_option("--disparity-pattern", disparityPattern_, "Folder mode: disparity file names instead of depth")
        ->excludes(depthPattern);
    convert.add_option("--output", options_.outputFolder, "Output folder (created if missing)")->capture_default_str();
    convert.add_flag("--resume", resume_,
                     "Folder mode: keep the frames the output folder's report.json lists with unchanged inputs and "
                     "settings, convert the rest, and commit each frame as it is done (report.json lists exactly the "
                     "frames present), so a run that fails or is stopped can go on; without it a folder run is "
                     "all-or-nothing");
    convert.add_option("--reference-left", referenceLeft_, "A real left view to measure the synthesized left eye against");
    convert.add_option("--reference-right", referenceRight_,
                       "A real right view to measure the synthesized right eye against");
    stereo_.method = "auto";
    stereo_.add(convert, "in the depth file's units", true);
    for (const char* derived : {"--max-separation", "--zero-parallax-distance"})
      convert.get_option(derived)->excludes(disparity);
    addDisparityBudgetOption(convert, disparityBudget_);
    convert
        .add_option("--display", display_,
                    "Display the disparity budget is computed for: tv55, monitor27, hmd or a JSON display profile FILE.json")
        ->capture_default_str();
    convert.add_option("--sbs", sideBySide_, "Side-by-side packing: half or full")->check(CLI::IsMember({"half", "full"}));
    convert.add_option("--tab", topBottom_, "Top-and-bottom packing: half or full")->check(CLI::IsMember({"half", "full"}));
    addMemoryLimitOption(convert, options_.memoryLimitBytes);
    addDeviceOptions(convert, contextOptions_);
  }

  int run() override {
    const bool folderMode = !inputFolder_.empty();
    if (!folderMode && options_.color.empty()) return fail("convert needs --color (or --input-folder)");
    if (!folderMode && options_.depth.empty() && disparityFile_.empty())
      return fail("convert needs --depth or --disparity (or --input-folder)");
    rejectInapplicableOptions(folderMode);
    if (!disparityFile_.empty()) options_.depth = disparityFile_;
    if (!disparityFile_.empty() || !disparityPattern_.empty())
      options_.disparity = disparityOutput_ == "left" ? app::DisparityOutput::Left : app::DisparityOutput::Right;
    options_.depthKind = depthKind_ == "hardware"   ? app::DepthKind::Hardware
                         : depthKind_ == "distance" ? app::DepthKind::Distance
                                                    : app::DepthKind::Linear;
    if (fovY_ > 0.0f) options_.verticalFovDegrees = fovY_;
    if (focalPx_ > 0.0f) options_.focalLengthPx = focalPx_;
    options_.sideBySide = stereo::parsePackingMode(sideBySide_);
    options_.topBottom = stereo::parsePackingMode(topBottom_);
    stereo_.finish();
    stereo::StereoParameters used = stereo_.parameters;
    if (stereo_.automatic) used.method = stereo::automaticMethod(stereo::DepthSource::External);
    StereoOptions::requireMethodOptionsApply(*subcommand, used);
    options_.stereo = stereo_.parameters;
    options_.automaticMethod = stereo_.automatic;
    options_.disparityBudget = comfort::parseDisparityBudgetRule(disparityBudget_);
    options_.display = comfort::resolveDisplayProfile(display_);  // throws naming the file or the choices
    if (!referenceLeft_.empty()) options_.referenceLeft = referenceLeft_;
    if (!referenceRight_.empty()) options_.referenceRight = referenceRight_;
    // Pairing problems surface before a Vulkan start-up and before any output.
    const std::vector<app::ConvertFrame> frames =
        folderMode ? app::pairFrames(inputFolder_, colorPattern_, disparityPattern_.empty() ? depthPattern_ : disparityPattern_)
                   : std::vector<app::ConvertFrame>();
    RunFiles files;
    files.writeInFolder(options_.outputFolder, app::convertOutputNames(options_, frames));
    files.read(options_.color, "--color");
    files.read(options_.depth, disparityFile_.empty() ? "--depth" : "--disparity");
    files.read(referenceLeft_, "--reference-left");
    files.read(referenceRight_, "--reference-right");
    for (const app::ConvertFrame& frame : frames) {
      files.read(frame.color, "--input-folder");
      files.read(frame.depth, "--input-folder");
    }
    if (subcommand->count("--display") > 0) files.readDisplay(display_);
    files.check();
    vk::Context context(contextOptions_);
    // All files or none; resuming a folder commits frame by frame instead (runConvertFolder).
    std::optional<io::OutputTransaction> outputs;
    if (!resume_) outputs.emplace(options_.outputFolder);
    std::size_t filesWritten = 0;
    std::uint32_t width = 0, height = 0;
    std::optional<double> gpuMs;
    std::string kept;
    if (folderMode) {
      const app::ConvertFolderResult result = app::runConvertFolder(
          context, options_, frames, drawProgress, resume_ ? app::FolderResume::Yes : app::FolderResume::No);
      for (const app::ConvertReport& report : result.converted) filesWritten += report.filesWritten.size();
      filesWritten += 1;  // report.json
      if (!result.converted.empty()) {
        width = result.converted.front().width;
        height = result.converted.front().height;
        gpuMs = result.converted.front().stereoPassGpuMs;
      }
      if (resume_) kept = ", kept " + std::to_string(result.kept.size()) + " converted earlier";
    } else {
      const app::ConvertReport report = app::runConvertJob(context, options_);
      filesWritten = report.filesWritten.size();
      width = report.width;
      height = report.height;
      gpuMs = report.stereoPassGpuMs;
    }
    const std::vector<std::string> messages = context.validationMessages();
    for (const std::string& message : messages) std::cerr << "s3d: validation: " << oneLine(message) << '\n';
    if (!messages.empty())
      return failValidation(messages.size());
    if (outputs) outputs->commit();
    std::cout << "s3d convert: " << (folderMode ? std::to_string(frames.size()) + " frames" + kept + "; " : std::string());
    if (width > 0)
      std::cout << width << "x" << height << " on " << context.deviceName() << ", stereo pass " << formatMs(gpuMs) << ", ";
    std::cout << "wrote " << filesWritten << " files to " << options_.outputFolder.string() << '\n';
    return 0;
  }

 private:
  // Every option that does nothing with the inputs and modes chosen is an error naming the mode.
  void rejectInapplicableOptions(bool folderMode) const {
    const CLI::App& convert = *subcommand;
    if (folderMode)
      rejectGiven(convert, {"--reference-left", "--reference-right"},
                  "measures one frame: it does not apply to --input-folder");
    else
      rejectGiven(convert, {"--color-pattern", "--depth-pattern", "--disparity-pattern", "--resume"},
                  "applies to --input-folder (folder mode) only");
    const bool disparity = !disparityFile_.empty() || !disparityPattern_.empty();
    if (disparity) {
      rejectGiven(convert, {"--max-separation", "--zero-parallax-distance"},
                  "is derived from the disparity: it does not apply to disparity input (--disparity, "
                  "--disparity-pattern)");
      rejectGiven(convert, {"--depth-kind", "--near", "--far", "--fov-y", "--focal-px"},
                  "describes depth: it does not apply to disparity input (--disparity, --disparity-pattern)");
      rejectGiven(convert, {"--disparity-budget", "--display"},
                  "does not apply to disparity input: the disparity is reproduced as given");
    } else {
      rejectGiven(convert, {"--disparity-output"}, "applies to disparity input (--disparity, --disparity-pattern)");
      StereoOptions::rejectSeparationUnderBudget(convert, disparityBudget_);
      if (disparityBudget_ == "off")
        rejectGiven(convert, {"--display"}, "is the display of the disparity budget: it does not apply with "
                                            "--disparity-budget off");
      if (depthKind_ != "hardware")
        rejectGiven(convert, {"--near", "--far"}, "applies to --depth-kind hardware (the depth kind is " + depthKind_ + ")");
      else if (convert.count("--near") == 0 || convert.count("--far") == 0)
        throw std::invalid_argument("--depth-kind hardware needs --near and --far (the projection's planes)");
      if (depthKind_ != "distance")
        rejectGiven(convert, {"--fov-y", "--focal-px"},
                    "applies to --depth-kind distance (the depth kind is " + depthKind_ + ")");
    }
    // The depth or disparity file's format: --depth-channel is an EXR's, --depth-scale a 16-bit PNG's.
    const std::string scalarFile = folderMode ? (disparity ? disparityPattern_ : depthPattern_)
                                              : (disparity ? disparityFile_ : options_.depth.string());
    std::string extension = std::filesystem::path(scalarFile).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    const std::string what = std::string(disparity ? "disparity" : "depth") + " '" + scalarFile + "'";
    if (extension != ".exr") rejectGiven(convert, {"--depth-channel"}, "applies to EXR files (the " + what + " is not one)");
    if (extension != ".png")
      rejectGiven(convert, {"--depth-scale"}, "applies to 16-bit PNG files (the " + what + " is not one)");
  }

  app::ConvertJobOptions options_;
  StereoOptions stereo_;
  vk::ContextOptions contextOptions_;
  std::string depthKind_ = "linear";  // app::DepthKind::Linear, ConvertJobOptions' default
  std::string disparityBudget_ = comfort::disparityBudgetRuleName(comfort::DisparityBudgetRule::OneDegree);
  std::string display_ = app::ConvertJobOptions{}.display.name;
  std::string sideBySide_ = "half";
  std::string topBottom_ = "half";
  std::string referenceLeft_, referenceRight_;
  std::string disparityFile_;
  std::string disparityOutput_ = "right";
  float fovY_ = 0.0f, focalPx_ = 0.0f;
  std::string inputFolder_;
  std::string colorPattern_ = "color_*.png";
  std::string depthPattern_ = "depth_*.exr";
  std::string disparityPattern_;
  bool resume_ = false;
};

}  // namespace

std::unique_ptr<Command> addConvertCommand(CLI::App& app) { return std::make_unique<ConvertCommand>(app); }

}  // namespace s3d::cli
