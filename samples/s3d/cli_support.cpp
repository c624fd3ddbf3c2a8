#include "cli_support.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "s3d/comfort/display_profile.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/number_text.h"
#include "s3d/renderer/scene_file.h"

namespace s3d::cli {

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

int failValidation(std::size_t messages) {
  return fail("the Vulkan validation layer reported " + std::to_string(messages) + " message(s)");
}

void warn(const std::string& message) { std::cerr << "s3d: warning: " << oneLine(message) << '\n'; }

std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) text += separator;
    text += name;
  }
  return text;
}

void RunFiles::writeInFolder(const std::filesystem::path& folder, const std::vector<std::string>& names) {
  for (const std::string& name : names) write(folder / name, "--output");
}

void RunFiles::readScene(const std::string& scene, const std::string& option) {
  if (!renderer::isSceneFile(scene)) return;
  for (const std::filesystem::path& file : renderer::sceneFileInputs(scene)) read(file, option);
}

void RunFiles::readDisplay(const std::string& display) {
  const std::vector<std::string> names = comfort::builtInDisplayProfileNames();
  if (std::find(names.begin(), names.end(), display) == names.end()) read(display, "--display");
}

std::optional<double> parseNumber(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string formatMs(const std::optional<double>& ms) {
  if (!ms) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f ms", *ms);
  return text;
}

CLI::Validator floatRange(double low, double high, bool lowOpen, const std::string& what, bool highOpen) {
  std::ostringstream interval;
  interval << (lowOpen ? "(" : "[") << low << ", " << high << (highOpen ? ")" : "]");
  return CLI::Validator(
      [low, high, lowOpen, highOpen, what, range = interval.str()](std::string& input) -> std::string {
        const std::optional<double> parsed = parseNumber(input);
        // As the float it is stored in; past float's range it is out of any range here (and may not be converted).
        const bool representable = parsed && std::abs(*parsed) <= double(std::numeric_limits<float>::max());
        const double value = representable ? double(float(*parsed)) : parsed ? *parsed : 0.0;
        const bool inside = parsed && std::isfinite(value) && (highOpen ? value < high : value <= high) &&
                            (lowOpen ? value > low : value >= low);
        if (inside) return {};
        std::string message = "expected " + what + ", a number in " + range + " (got '" + input + "'";
        if (parsed && value != *parsed && std::isfinite(*parsed)) message += ", which is " + numberText(float(value)) + " as a float";
        return message + ")";
      },
      "FLOAT in " + interval.str());
}

bool parseResolution(const std::string& text, std::uint32_t maxSize, std::uint32_t& width, std::uint32_t& height) {
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return false;
  auto parsePart = [maxSize](const char* begin, const char* end, std::uint32_t& value) {
    auto [ptr, ec] = std::from_chars(begin, end, value);
    return ec == std::errc() && ptr == end && begin != end && value >= 1 && value <= maxSize;
  };
  return parsePart(text.data(), text.data() + x, width) &&
         parsePart(text.data() + x + 1, text.data() + text.size(), height);
}

CLI::Validator resolutionValidator(std::uint32_t maxSize) {
  return CLI::Validator(
      [maxSize](std::string& text) -> std::string {
        std::uint32_t width = 0, height = 0;
        return parseResolution(text, maxSize, width, height)
                   ? std::string()
                   : "expected WxH with both in [1, " + std::to_string(maxSize) + "] (got '" + text + "')";
      },
      "WxH");
}

CLI::Validator frameNumberValidator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() < 10 &&
                            std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
        return digits ? std::string() : "expected a frame number, 0 or more (got '" + text + "')";
      },
      "N");
}

void rejectGiven(const CLI::App& command, const std::vector<std::string>& options, const std::string& reason) {
  for (const std::string& option : options)
    if (command.count(option) > 0) throw std::invalid_argument(option + " " + reason);
}

void addMemoryLimitOption(CLI::App& command, std::optional<std::uint64_t>& limit) {
  command
      .add_option_function<std::string>(
          "--memory-limit", [&limit](const std::string& text) { limit = frame::parseByteSize(text); },
          "Most memory the run may plan for (e.g. 4GiB, 512MiB): its estimate (images x bytes per pixel) is checked "
          "against this and the machine's available memory before anything is allocated")
      ->check(
          [](const std::string& text) -> std::string {
            return frame::parseByteSize(text) ? std::string()
                                            : "expected a size such as 4GiB, 1.5G or 512MiB (got '" + text + "')";
          },
          "SIZE");
}

void StereoOptions::requireMethodOptionsApply(const CLI::App& command, const stereo::StereoParameters& parameters) {
  const stereo::StereoMethod method = parameters.method;
  const std::string used = std::string("(the method is ") + stereo::methodName(method) + ")";
  if (method != stereo::StereoMethod::Hybrid)
    rejectGiven(command, {"--hybrid-budget", "--hybrid-base", "--hybrid-cell", "--hybrid-score-floor"},
                "applies to --method hybrid " + used);
  // A hybrid's displacement is its base: --taps and --iterations apply to that.
  const stereo::StereoMethod displacement = stereo::displacementParameters(parameters).method;
  const std::string base = method == stereo::StereoMethod::Hybrid
                               ? std::string("(the hybrid's base is ") + stereo::methodName(displacement) + ")"
                               : used;
  if (displacement != stereo::StereoMethod::Search)
    rejectGiven(command, {"--taps"}, "applies to --method search " + base);
  if (displacement != stereo::StereoMethod::Iterative)
    rejectGiven(command, {"--iterations"}, "applies to --method iterative " + base);
}

void StereoOptions::rejectSeparationUnderBudget(const CLI::App& command, const std::string& budgetRule) {
  if (budgetRule == "off") return;
  rejectGiven(command, {"--max-separation", "--zero-parallax-distance"},
              "is chosen every frame by --disparity-budget " + budgetRule +
                  (command.count("--disparity-budget") ? "" : " (the default)") +
                  " from the frame's depth range; add --disparity-budget off to set it");
}

namespace {
std::vector<std::string> methodChoices(bool offerAuto) {
  std::vector<std::string> names = stereo::stereoMethodNames();
  if (offerAuto) names.insert(names.begin(), "auto");
  return names;
}
}  // namespace

void StereoOptions::add(CLI::App& command, const std::string& depthUnits, bool offerAuto) {
  command
      .add_option("--max-separation", parameters.maxSeparation,
                  "Eye separation at infinity, as a fraction of the screen width")
      ->check(floatRange(0.0, double(stereo::kMaxSeparationLimit), false, "a fraction of the screen width"))
      ->capture_default_str();
  command
      .add_option("--zero-parallax-distance", parameters.zeroParallaxDistance,
                  "Depth (" + depthUnits + ") that stays on the screen plane")
      ->check(floatRange(0.0, 1.0e6, true, "a distance in " + depthUnits))
      ->capture_default_str();
  command
      .add_option("--edge-crop", parameters.edgeCrop,
                  "Fraction of the width blacked out on each side of both eyes (and left out of the comparison); "
                  "default: none in s3d render (the center view gets a guard band, the eyes are full frame), = "
                  "--max-separation elsewhere; giving it renders the output-size center view and crops")
      ->check(floatRange(0.0, double(stereo::kMaxSeparationLimit), false, "a fraction of the screen width"));
  command
      .add_option("--method", method,
                  std::string("Stereo method: seed (Listing 4.5, taps at 0.5/0.66/1.0 of the separation), search (--taps "
                              "taps spread over the separation), iterative (fixed-point source search, --iterations) "
                              "forward (z-buffered scatter of every pixel, holes filled from the background) or hybrid "
                              "(--hybrid-base's displacement, then up to --hybrid-budget of each eye's pixels, the ones it "
                              "gets wrong, rendered from the eye cameras; needs a renderer)") +
                      (offerAuto ? "; auto: forward for depth or disparity from files (measured on real photographs, "
                                   "docs/RESULTS.md)"
                                 : ""))
      ->check(CLI::IsMember(methodChoices(offerAuto)))
      ->capture_default_str();
  command
      .add_option("--hybrid-budget", parameters.hybridBudget,
                  "--method hybrid: largest share of each eye's pixels rendered from the eye camera, worst first (0: the "
                  "base displacement bit for bit, 1: every pixel, the two-pass reference)")
      ->check(floatRange(0.0, 1.0, false, "a share of the pixels"))
      ->capture_default_str();
  addHybridClassificationOptions(command, parameters, "--method hybrid: the classification's");
  command
      .add_option("--hybrid-base", hybridBase, "--method hybrid: the displacement it starts from")
      ->check(CLI::IsMember(stereo::stereoMethodNames(false)))
      ->capture_default_str();
  command.add_option("--taps", parameters.searchTaps, "Depth-search taps of --method search")
      ->check(CLI::Range(1, S3D_STEREO_MAX_TAPS))
      ->capture_default_str();
  command.add_option("--iterations", parameters.iterations, "Fixed-point iterations of --method iterative")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
}

void addHybridClassificationOptions(CLI::App& command, stereo::StereoParameters& parameters, const std::string& whose) {
  command
      .add_option("--hybrid-cell", parameters.hybridCell,
                  whose + " cell in pixels per side: 2 classifies each 2x2 block once, from its nearest depth; 1 "
                          "every pixel; 0 by the width (2 from 1280 columns up)")
      ->check(CLI::Range(0, stereo::kHybridCellLimit))
      ->capture_default_str();
  command
      .add_option("--hybrid-score-floor", parameters.hybridScoreFloor,
                  whose + " floor: below budget 1, pixels whose expected error (pixels of parallax on the "
                          "classification's cells) lies below it are not rendered")
      ->check(floatRange(0.0, double(stereo::kHybridScoreFloorLimit), false, "pixels of parallax"))
      ->capture_default_str();
}

void StereoOptions::finish() {
  automatic = method == "auto";
  if (!automatic) parameters.method = stereo::parseStereoMethod(method);
  parameters.hybridBase = stereo::parseStereoMethod(hybridBase);
  stereo::validate(parameters);
}

void addDeviceOptions(CLI::App& command, vk::ContextOptions& options) {
  command
      .add_option("--device", options.device,
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
  command.add_flag("--validation", options.validation,
                   "Turn on the Khronos validation layer; any message it reports makes the run fail");
}

namespace {
const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}
}  // namespace

void listDevices() {
  const std::vector<vk::PhysicalDeviceInfo> devices = vk::listPhysicalDevices();
  if (devices.empty()) std::cout << "no Vulkan devices\n";
  for (const vk::PhysicalDeviceInfo& device : devices) {
    std::cout << device.index << ": " << device.name << " (" << deviceTypeName(device.type) << ", Vulkan "
              << VK_API_VERSION_MAJOR(device.apiVersion) << '.' << VK_API_VERSION_MINOR(device.apiVersion) << '.'
              << VK_API_VERSION_PATCH(device.apiVersion) << ") ";
    if (device.usable)
      std::cout << "usable\n";
    else
      std::cout << "not usable: " << oneLine(device.unusableReason) << '\n';
  }
}

}  // namespace s3d::cli
