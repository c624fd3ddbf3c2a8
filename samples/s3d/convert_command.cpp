// `s3d convert`: synthesizes the eyes of an external color + depth frame (s3d/app/convert_job.h).
#include <iostream>

#include "cli_support.h"
#include "s3d/app/convert_job.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::cli {
namespace {

class ConvertCommand final : public Command {
 public:
  explicit ConvertCommand(CLI::App& app) {
    subcommand = app.add_subcommand(
        "convert",
        "Synthesize a stereo pair from an existing frame: a color image and its depth (from any renderer or "
        "capture). Writes left.png, right.png, anaglyph.png, sbs.png, tab.png and report.json. Sign convention: "
        "the left eye shows a point of parallax p (maxSeparation * (1 - zeroParallaxDistance / depth), a "
        "fraction of the width) p * width pixels left of where the input shows it, the right eye as far right");
    CLI::App& convert = *subcommand;
    convert
        .add_option("--color", options_.color,
                    "Color image: .png (display-encoded) or .exr (linear; clamped and sRGB-encoded)")
        ->required();
    convert.add_option("--depth", options_.depth, "Depth: an .exr with a Z channel (may be the color file)")
        ->required();
    convert
        .add_option("--depth-kind", depthKind_,
                    "linear (view depth in world units; >= 1e30 or inf is sky) or hardware "
                    "(zero-to-one perspective depth; needs --near and --far; 1 is sky)")
        ->check(CLI::IsMember({"linear", "hardware"}))
        ->capture_default_str();
    convert.add_option("--near", options_.nearPlane, "Near plane of the projection, for --depth-kind hardware");
    convert.add_option("--far", options_.farPlane, "Far plane of the projection, for --depth-kind hardware");
    convert.add_option("--output", options_.outputFolder, "Output folder (created if missing)")->capture_default_str();
    convert.add_option("--reference-left", referenceLeft_, "A real left view to measure the synthesized left eye against");
    convert.add_option("--reference-right", referenceRight_,
                       "A real right view to measure the synthesized right eye against");
    stereo_.add(convert, "in the depth file's units");
    convert.add_option("--sbs", sideBySide_, "Side-by-side packing: half or full")->check(CLI::IsMember({"half", "full"}));
    convert.add_option("--tab", topBottom_, "Top-and-bottom packing: half or full")->check(CLI::IsMember({"half", "full"}));
    addDeviceOptions(convert, contextOptions_);
  }

  int run() override {
    options_.depthKind = depthKind_ == "hardware" ? app::DepthKind::Hardware : app::DepthKind::Linear;
    options_.sideBySide = stereo::parsePackingMode(sideBySide_);
    options_.topBottom = stereo::parsePackingMode(topBottom_);
    stereo_.finish();
    options_.stereo = stereo_.parameters;
    if (!referenceLeft_.empty()) options_.referenceLeft = referenceLeft_;
    if (!referenceRight_.empty()) options_.referenceRight = referenceRight_;
    vk::Context context(contextOptions_);
    const app::ConvertReport report = app::runConvertJob(context, options_);
    const std::vector<std::string> messages = context.validationMessages();
    for (const std::string& message : messages) std::cerr << "s3d: validation: " << oneLine(message) << '\n';
    if (!messages.empty())
      return fail("the Vulkan validation layer reported " + std::to_string(messages.size()) + " message(s)");
    std::cout << "s3d convert: " << report.width << "x" << report.height << " on " << report.deviceName
              << ", stereo pass " << formatMs(report.stereoPassGpuMs) << ", wrote " << report.filesWritten.size()
              << " files to " << options_.outputFolder.string() << '\n';
    return 0;
  }

 private:
  app::ConvertJobOptions options_;
  StereoOptions stereo_;
  vk::ContextOptions contextOptions_;
  std::string depthKind_ = "linear";
  std::string sideBySide_ = "half";
  std::string topBottom_ = "half";
  std::string referenceLeft_, referenceRight_;
};

}  // namespace

std::unique_ptr<Command> addConvertCommand(CLI::App& app) { return std::make_unique<ConvertCommand>(app); }

}  // namespace s3d::cli
