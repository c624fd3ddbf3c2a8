// s3d: the command-line tool. `s3d render` renders a built-in scene, synthesizes both eyes with the stereo
// pass, renders the two-pass reference eyes and writes images plus report.json (s3d/app/render_job.h);
// `--sequence` runs a scene's camera path with the comfort controls (s3d/app/sequence_job.h). `s3d convert`
// synthesizes the eyes of an external color + depth frame (s3d/app/convert_job.h).
//
// Exit status: 0 on success (and for --help / --list-devices); 1 on any error, which ends with one line
// "s3d: error: <message>" on stderr. `s3d` without a command prints the help and fails: there is nothing
// sensible to do by default, and a script calling a bare `s3d` is almost certainly a mistake.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "s3d/app/convert_job.h"
#include "s3d/app/render_job.h"
#include "s3d/app/sequence_job.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace {

using s3d::app::RenderJobOptions;

std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

int fail(const std::string& message) {
  std::cerr << "s3d: error: " << oneLine(message) << '\n';
  return 1;
}

std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) text += separator;
    text += name;
  }
  return text;
}

std::optional<double> parseNumber(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A finite float in [low, high] (or (low, high] when lowOpen); CLI11 puts the option's name before the message.
CLI::Validator floatRange(double low, double high, bool lowOpen, const std::string& what) {
  std::ostringstream description;
  description << "FLOAT in " << (lowOpen ? "(" : "[") << low << ", " << high << "]";
  return CLI::Validator(
      [low, high, lowOpen, what](std::string& input) -> std::string {
        std::optional<double> value = parseNumber(input);
        if (!value || *value > high || (lowOpen ? *value <= low : *value < low)) {
          std::ostringstream message;
          message << "expected " << what << ", a number in " << (lowOpen ? "(" : "[") << low << ", " << high
                  << "] (got '" << input << "')";
          return message.str();
        }
        return {};
      },
      description.str());
}

// "WxH" with both parts in [1, kMaxImageSize].
bool parseResolution(const std::string& text, std::uint32_t& width, std::uint32_t& height) {
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return false;
  auto parsePart = [](const char* begin, const char* end, std::uint32_t& value) {
    auto [ptr, ec] = std::from_chars(begin, end, value);
    return ec == std::errc() && ptr == end && begin != end && value >= 1 && value <= s3d::app::kMaxImageSize;
  };
  return parsePart(text.data(), text.data() + x, width) &&
         parsePart(text.data() + x + 1, text.data() + text.size(), height);
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

void listDevices() {
  const std::vector<s3d::vk::PhysicalDeviceInfo> devices = s3d::vk::listPhysicalDevices();
  if (devices.empty()) std::cout << "no Vulkan devices\n";
  for (const s3d::vk::PhysicalDeviceInfo& device : devices) {
    std::cout << device.index << ": " << device.name << " (" << deviceTypeName(device.type) << ", Vulkan "
              << VK_API_VERSION_MAJOR(device.apiVersion) << '.' << VK_API_VERSION_MINOR(device.apiVersion) << '.'
              << VK_API_VERSION_PATCH(device.apiVersion) << ") ";
    if (device.usable)
      std::cout << "usable\n";
    else
      std::cout << "not usable: " << oneLine(device.unusableReason) << '\n';
  }
}

std::string formatMs(const std::optional<double>& ms) {
  if (!ms) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f ms", *ms);
  return text;
}

void printSummary(const s3d::app::RenderReport& report, const RenderJobOptions& options) {
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
  std::snprintf(line, sizeof(line), "  synthesized vs reference (%u border columns excluded): left %.2f dB, right %.2f dB\n",
                report.cropColumns, report.left.display.psnrDb, report.right.display.psnrDb);
  std::cout << line;
  const std::size_t count = report.filesWritten.size();
  std::cout << "  wrote " << count << (count == 1 ? " file" : " files") << " to " << options.outputFolder.string() << '\n';
}

// Runs `s3d render`; returns the exit status.
int runRender(const RenderJobOptions& options, const s3d::vk::ContextOptions& contextOptions) {
  // Options first: a typo must not cost a Vulkan start-up, and must leave no files behind.
  s3d::app::validateRenderJobOptions(options);
  s3d::vk::Context context(contextOptions);
  std::optional<s3d::app::RenderReport> report;
  std::string jobError;
  try {
    report = s3d::app::runRenderJob(context, options);
  } catch (const std::exception& error) {
    jobError = error.what();
  }
  // With --validation, the layer's messages explain failures and are themselves failures.
  const std::vector<std::string> messages = context.validationMessages();
  for (const std::string& message : messages) std::cerr << "s3d: validation: " << oneLine(message) << '\n';
  if (!report) return fail(jobError);
  printSummary(*report, options);
  if (!messages.empty())
    return fail("the Vulkan validation layer reported " + std::to_string(messages.size()) + " message(s)");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"s3d: stereoscopic 3D from one rendered view and its depth (view synthesis), "
               "checked against a two-pass reference",
               "s3d"};
  bool listDevicesOnly = false;
  app.add_flag("--list-devices", listDevicesOnly, "List the Vulkan devices and whether s3d can use them, then exit");

  RenderJobOptions options;
  s3d::vk::ContextOptions contextOptions;
  std::string resolution;
  std::vector<std::string> outputs(s3d::app::kAllOutputs);
  std::string sideBySide = "half";
  std::string topBottom = "half";
  std::string stereoMethod = "seed";
  bool renderListDevices = false;

  CLI::App* render = app.add_subcommand(
      "render",
      "Render a built-in scene, synthesize both eyes with the stereo pass, render the two-pass reference eyes, "
      "compare them and write the selected outputs (default: all) plus report.json");
  render->add_option("--width", options.width, "Image width in pixels")
      ->check(CLI::Range(std::uint32_t(1), s3d::app::kMaxImageSize))
      ->capture_default_str();
  render->add_option("--height", options.height, "Image height in pixels")
      ->check(CLI::Range(std::uint32_t(1), s3d::app::kMaxImageSize))
      ->capture_default_str();
  render
      ->add_option("--resolution", resolution, "Image size as WxH, e.g. 1920x1080 (instead of --width/--height)")
      ->check(
          [](const std::string& text) -> std::string {
            std::uint32_t w = 0, h = 0;
            return parseResolution(text, w, h) ? std::string()
                                               : "expected WxH with both in [1, " +
                                                     std::to_string(s3d::app::kMaxImageSize) + "] (got '" + text + "')";
          },
          "WxH")
      ->excludes("--width")
      ->excludes("--height");
  render
      ->add_option("--scene", options.scene,
                   "Built-in scene: " + joined(s3d::renderer::builtInSceneNames(), ", "))
      ->capture_default_str();
  render->add_option("--output", options.outputFolder, "Output folder (created if missing)")->capture_default_str();
  render
      ->add_option("--outputs", outputs,
                   "Comma-separated subset of the outputs to write (default: all): " +
                       joined(s3d::app::kAllOutputs, ","))
      ->delimiter(',')
      ->check(CLI::IsMember(s3d::app::kAllOutputs))
      ->type_name("LIST");
  render->add_option("--sbs", sideBySide, "Side-by-side packing: half (each eye squeezed to half width) or full")
      ->check(CLI::IsMember({"half", "full"}))
      ->capture_default_str();
  render->add_option("--tab", topBottom, "Top-and-bottom packing: half (each eye squeezed to half height) or full")
      ->check(CLI::IsMember({"half", "full"}))
      ->capture_default_str();
  render
      ->add_option("--max-separation", options.stereo.maxSeparation,
                   "Eye separation at infinity, as a fraction of the screen width")
      ->check(floatRange(0.0, double(s3d::stereo::kMaxSeparationLimit), false, "a fraction of the screen width"))
      ->capture_default_str();
  render
      ->add_option("--zero-parallax-distance", options.stereo.zeroParallaxDistance,
                   "Depth in world units (metres) that stays on the screen plane")
      ->check(floatRange(0.0, 1.0e6, true, "a distance in world units"))
      ->capture_default_str();
  render
      ->add_option("--edge-crop", options.stereo.edgeCrop,
                   "Fraction of the width blacked out on each side of both eyes (and left out of the comparison); "
                   "default: = --max-separation")
      ->check(floatRange(0.0, double(s3d::stereo::kMaxSeparationLimit), false, "a fraction of the screen width"));
  render->add_option("--weapon-depth-offset", options.stereo.weaponDepthOffset,
                     "First-person weapon: depth offset in world units added before stereo (pushes it into the screen)")
      ->check(floatRange(0.0, 1.0e4, false, "a distance in world units"))
      ->capture_default_str();
  render->add_option("--weapon-depth-scale", options.stereo.weaponDepthScale,
                     "First-person weapon: depth scale applied before the offset (pushed = offset + scale * depth)")
      ->check(floatRange(0.0, 1.0e4, true, "a positive factor"))
      ->capture_default_str();
  render->add_option("--display", options.display,
                     "Display profile of the comfort report: tv55 (55-inch at 2.5 m), monitor27 (27-inch at 0.7 m) or "
                     "hmd (90-degree field of view focused at 1.3 m)")
      ->check(CLI::IsMember({"tv55", "monitor27", "hmd"}))
      ->capture_default_str();
  render->add_option("--frame", options.frame, "Frame of the scene's camera path to render (0: its first)")
      ->capture_default_str();
  bool sequence = false;
  render->add_flag("--sequence", sequence,
                   "Render the scene's whole camera path with the comfort controls running (zero-parallax "
                   "control, weapon push, crosshair): anaglyph_NNNN.png per frame and a per-frame report.json");
  render->add_option("--method", stereoMethod,
                     "Stereo method: seed (Listing 4.5, taps at 0.5/0.66/1.0 of the separation), search (--taps taps "
                     "spread over the separation) or iterative (fixed-point source search, --iterations)")
      ->check(CLI::IsMember({"seed", "search", "iterative"}))
      ->capture_default_str();
  render->add_option("--taps", options.stereo.searchTaps, "Depth-search taps of --method search")
      ->check(CLI::Range(1, S3D_STEREO_MAX_TAPS))
      ->capture_default_str();
  render->add_option("--iterations", options.stereo.iterations, "Fixed-point iterations of --method iterative")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  render
      ->add_option("--device", contextOptions.device,
                   "Vulkan device: auto (a GPU if present, else the CPU device), cpu, gpu, or an index from "
                   "--list-devices")
      ->check(
          [](const std::string& text) -> std::string {
            if (text == "auto" || text == "cpu" || text == "gpu") return {};
            if (!text.empty() && text.size() < 10 &&
                std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
              return {};
            return "expected auto, cpu, gpu or a device index (got '" + text + "')";
          },
          "auto|cpu|gpu|N")
      ->capture_default_str();
  render->add_flag("--validation", contextOptions.validation,
                   "Turn on the Khronos validation layer; any message it reports makes the run fail");
  render->add_flag("--list-devices", renderListDevices,
                   "List the Vulkan devices and whether s3d can use them, then exit without rendering");

  s3d::app::ConvertJobOptions convertOptions;
  s3d::vk::ContextOptions convertContext;
  std::string depthKind = "linear";
  std::string convertSideBySide = "half", convertTopBottom = "half", convertMethod = "seed";
  std::string referenceLeft, referenceRight;
  CLI::App* convert = app.add_subcommand(
      "convert",
      "Synthesize a stereo pair from an existing frame: a color image and its depth (from any renderer or "
      "capture). Writes left.png, right.png, anaglyph.png, sbs.png, tab.png and report.json. Sign convention: "
      "the left eye shows a point of parallax p (maxSeparation * (1 - zeroParallaxDistance / depth), a "
      "fraction of the width) p * width pixels left of where the input shows it, the right eye as far right");
  convert->add_option("--color", convertOptions.color, "Color image: .png (display-encoded) or .exr (linear; clamped and sRGB-encoded)")
      ->required();
  convert->add_option("--depth", convertOptions.depth, "Depth: an .exr with a Z channel (may be the color file)")->required();
  convert->add_option("--depth-kind", depthKind, "linear (view depth in world units; >= 1e30 or inf is sky) or hardware "
                                                 "(zero-to-one perspective depth; needs --near and --far; 1 is sky)")
      ->check(CLI::IsMember({"linear", "hardware"}))
      ->capture_default_str();
  convert->add_option("--near", convertOptions.nearPlane, "Near plane of the projection, for --depth-kind hardware");
  convert->add_option("--far", convertOptions.farPlane, "Far plane of the projection, for --depth-kind hardware");
  convert->add_option("--output", convertOptions.outputFolder, "Output folder (created if missing)")->capture_default_str();
  convert->add_option("--reference-left", referenceLeft, "A real left view to measure the synthesized left eye against");
  convert->add_option("--reference-right", referenceRight, "A real right view to measure the synthesized right eye against");
  convert->add_option("--max-separation", convertOptions.stereo.maxSeparation, "Eye separation at infinity, fraction of the width")
      ->check(floatRange(0.0, double(s3d::stereo::kMaxSeparationLimit), false, "a fraction of the screen width"))
      ->capture_default_str();
  convert->add_option("--zero-parallax-distance", convertOptions.stereo.zeroParallaxDistance,
                      "Depth (in the depth file's units) that stays on the screen plane")
      ->check(floatRange(0.0, 1.0e6, true, "a distance"))
      ->capture_default_str();
  convert->add_option("--edge-crop", convertOptions.stereo.edgeCrop, "Fraction of the width blacked out per side; default: = --max-separation")
      ->check(floatRange(0.0, double(s3d::stereo::kMaxSeparationLimit), false, "a fraction of the screen width"));
  convert->add_option("--method", convertMethod, "seed, search or iterative")
      ->check(CLI::IsMember({"seed", "search", "iterative"}))
      ->capture_default_str();
  convert->add_option("--iterations", convertOptions.stereo.iterations, "Fixed-point iterations of --method iterative")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  convert->add_option("--taps", convertOptions.stereo.searchTaps, "Depth-search taps of --method search")
      ->check(CLI::Range(1, S3D_STEREO_MAX_TAPS))
      ->capture_default_str();
  convert->add_option("--sbs", convertSideBySide, "Side-by-side packing: half or full")->check(CLI::IsMember({"half", "full"}));
  convert->add_option("--tab", convertTopBottom, "Top-and-bottom packing: half or full")->check(CLI::IsMember({"half", "full"}));
  convert->add_option("--device", convertContext.device, "Vulkan device: auto, cpu, gpu or an index")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {  // --help
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    const char* command = render->parsed() ? "render " : convert->parsed() ? "convert " : "";
    return fail(std::string(error.what()) + " (see `s3d " + command + "--help`)");
  }

  try {
    if (listDevicesOnly || renderListDevices) {
      listDevices();
      return 0;
    }
    if (convert->parsed()) {
      convertOptions.depthKind = depthKind == "hardware" ? s3d::app::DepthKind::Hardware : s3d::app::DepthKind::Linear;
      convertOptions.sideBySide = s3d::stereo::parsePackingMode(convertSideBySide);
      convertOptions.topBottom = s3d::stereo::parsePackingMode(convertTopBottom);
      convertOptions.stereo.method = s3d::stereo::parseStereoMethod(convertMethod);
      if (!referenceLeft.empty()) convertOptions.referenceLeft = referenceLeft;
      if (!referenceRight.empty()) convertOptions.referenceRight = referenceRight;
      s3d::stereo::validate(convertOptions.stereo);
      s3d::vk::Context context(convertContext);
      const s3d::app::ConvertReport report = s3d::app::runConvertJob(context, convertOptions);
      std::cout << "s3d convert: " << report.width << "x" << report.height << " on " << report.deviceName
                << ", stereo pass " << formatMs(report.stereoPassGpuMs) << ", wrote " << report.filesWritten.size()
                << " files to " << convertOptions.outputFolder.string() << '\n';
      return 0;
    }
    if (!render->parsed()) {
      std::cerr << app.help();
      return fail("no command given (try `s3d render` or `s3d convert`)");
    }
    if (!resolution.empty()) parseResolution(resolution, options.width, options.height);  // checked above
    options.outputs = std::set<std::string>(outputs.begin(), outputs.end());
    options.sideBySide = s3d::stereo::parsePackingMode(sideBySide);
    options.topBottom = s3d::stereo::parsePackingMode(topBottom);
    options.stereo.method = s3d::stereo::parseStereoMethod(stereoMethod);
    if (sequence) {
      s3d::app::SequenceJobOptions sequenceOptions;
      sequenceOptions.width = options.width;
      sequenceOptions.height = options.height;
      sequenceOptions.scene = options.scene;
      sequenceOptions.outputFolder = options.outputFolder;
      sequenceOptions.stereo = options.stereo;
      s3d::vk::Context context(contextOptions);
      const s3d::app::SequenceReport report = s3d::app::runSequenceJob(context, sequenceOptions);
      std::uint64_t conflicts = 0;
      for (const s3d::app::SequenceFrame& frame : report.frames) conflicts += frame.weaponConflictPixels;
      std::cout << "s3d render --sequence: scene " << report.scene << ", " << report.frames.size() << " frames on "
                << report.deviceName << ", weapon/world conflict pixels " << conflicts << ", wrote "
                << report.filesWritten.size() << " files to " << options.outputFolder.string() << '\n';
      return 0;
    }
    return runRender(options, contextOptions);
  } catch (const std::exception& error) {
    return fail(error.what());
  } catch (...) {
    return fail("unknown exception");
  }
}
