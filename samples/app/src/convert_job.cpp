#include "s3d/app/convert_job.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "s3d/app/comfort_json.h"
#include "s3d/app/frame_rules.h"
#include "s3d/gpu/linear_depth.h"
#include "s3d/io/depth_io.h"
#include "s3d/io/image_io.h"
#include "s3d/io/output_transaction.h"
#include "s3d/json_document.h"
#include "s3d/number_text.h"
#include "s3d/stereo/sanitize.h"
#include "s3d/stereo/srgb.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const fs::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

void requireFile(const fs::path& file, const char* what) {
  if (file.empty()) throw std::invalid_argument(std::string(what) + ": no file given");
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (fs::is_directory(status))
    throw std::invalid_argument(std::string(what) + " file '" + file.string() + "' is a folder, not a file");
  if (!fs::exists(status)) throw std::invalid_argument(std::string(what) + " file '" + file.string() + "' does not exist");
  if (!fs::is_regular_file(status))
    throw std::invalid_argument(std::string(what) + " file '" + file.string() + "' is not a regular file");
}

std::string sizeText(std::uint32_t width, std::uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// Display-encoded RGBA8 from a PNG as is, or from an EXR's linear color clamped to [0, 1] and sRGB-encoded;
// NaN or inf channel values are made 0 (stereo::sanitizeColor) and added to *sanitizedValues.
ImageRGBA8 readColor(const fs::path& file, std::uint64_t* sanitizedValues = nullptr) {
  requireFile(file, "color");
  const std::string extension = lowerExtension(file);
  if (extension == ".png") return io::readPng(file);
  if (extension != ".exr") throw std::invalid_argument("color file '" + file.string() + "': expected .png or .exr");
  io::ExrFrame frame = io::readExr(file);
  const std::uint64_t sanitized = stereo::sanitizeColor(frame.color);
  if (sanitizedValues) *sanitizedValues += sanitized;
  ImageRGBA8 color(frame.color.width, frame.color.height);
  for (std::size_t i = 0; i < frame.color.pixels.size(); ++i) {
    const float value = frame.color.pixels[i];
    color.pixels[i] = i % 4 == 3 ? std::uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f))
                                 : stereo::encodeSrgb8(value);
  }
  return color;
}

constexpr float kPngSky = 65535.0f;

// The depth or disparity file's values as stored: an EXR channel, a 16-bit PNG (scaled, or normalized for
// hardware depth), or a 1-channel PFM.
DepthImage readScalarFile(const ConvertJobOptions& options, const char* what) {
  const fs::path& file = options.depth;
  requireFile(file, what);
  const std::string extension = lowerExtension(file);
  if (extension == ".exr") return io::readExrChannel(file, options.depthChannel);
  if (extension == ".pfm") {
    io::PfmImage pfm = io::readPfm(file);
    if (pfm.channels != 1)
      throw std::invalid_argument(std::string(what) + " file '" + file.string() +
                                  "' is a 3-channel PFM (PF): expected 1 channel (Pf)");
    DepthImage image(pfm.width, pfm.height);
    image.pixels = std::move(pfm.values);
    return image;
  }
  if (extension == ".png") {
    if (!(options.depthScale > 0.0f) || !std::isfinite(options.depthScale))
      throw std::invalid_argument("--depth-scale must be a positive number (got " + numberText(options.depthScale) + ")");
    const io::Gray16Image png = io::readPngGray16(file);
    DepthImage image(png.width, png.height);
    const bool normalized = !options.disparity && options.depthKind == DepthKind::Hardware;
    for (std::size_t i = 0; i < png.pixels.size(); ++i) {
      const float value = float(png.pixels[i]);
      if (normalized)
        image.pixels[i] = value / kPngSky;
      else if (!options.disparity && value == kPngSky)
        image.pixels[i] = INFINITY;  // the largest step is sky
      else if (value == 0.0f)
        image.pixels[i] = NAN;  // unknown (depth: no sample; disparity: the Middlebury / KITTI convention)
      else
        image.pixels[i] = value * options.depthScale;
    }
    return image;
  }
  throw std::invalid_argument(std::string(what) + " file '" + file.string() + "': expected .exr, .png (16-bit) or .pfm");
}

std::string pixelText(const char* what, const fs::path& file, std::size_t index, std::uint32_t width) {
  return std::string(what) + " file '" + file.string() + "' at pixel (" + std::to_string(index % width) + ", " +
         std::to_string(index / width) + ")";
}

// Focal length in pixels for Distance depth: given, or from the vertical field of view and the height.
float focalLengthPx(const ConvertJobOptions& options, std::uint32_t height) {
  if (options.focalLengthPx && options.verticalFovDegrees)
    throw std::invalid_argument("give either the vertical field of view or the focal length, not both");
  if (options.focalLengthPx) {
    if (!(*options.focalLengthPx > 0.0f) || !std::isfinite(*options.focalLengthPx))
      throw std::invalid_argument("the focal length must be a positive number of pixels");
    return *options.focalLengthPx;
  }
  if (options.verticalFovDegrees) {
    const float fov = *options.verticalFovDegrees;
    if (!(fov > 0.0f && fov < 180.0f)) throw std::invalid_argument("the vertical field of view must be in (0, 180) degrees");
    return 0.5f * float(height) / std::tan(0.5f * fov * std::numbers::pi_v<float> / 180.0f);
  }
  throw std::invalid_argument("distance depth needs the camera intrinsics: --fov-y or --focal-px");
}

// Unknown pixels (NaN) take the background's depth; a file without one known pixel is rejected.
std::uint64_t fillUnknown(DepthImage& depth, const ConvertJobOptions& options, const char* what) {
  const std::uint64_t unknown = stereo::fillUnknownDepthFromBackground(depth);
  if (unknown == depth.pixels.size())
    throw std::invalid_argument(std::string(what) + " file '" + options.depth.string() + "' has no known pixel");
  return unknown;
}

DepthImage readLinearDepth(const ConvertJobOptions& options, std::uint64_t& unknownPixels) {
  DepthImage depth = readScalarFile(options, "depth");
  gpu::LinearDepthParams hardware{};
  if (options.depthKind == DepthKind::Hardware) {
    if (!(options.nearPlane > 0.0f) || !(options.farPlane > options.nearPlane) || !std::isfinite(options.farPlane))
      throw std::invalid_argument("hardware depth needs 0 < --near < --far (got near " + numberText(options.nearPlane) +
                                  ", far " + numberText(options.farPlane) + ")");
    // One layer spanning device depth [0, 1]: no first-person range, 1.0 is sky.
    hardware.worldRatio = gpu::projectionRatio(options.nearPlane, options.farPlane, 0.0f, 1.0f);
    hardware.firstPersonDeviceDepthMax = -1.0f;
    hardware.skyDeviceDepth = 1.0f;
    hardware.firstPersonDepthScale = 1.0f;
  }
  const float focal = options.depthKind == DepthKind::Distance ? focalLengthPx(options, depth.height) : 0.0f;
  for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
    float& value = depth.pixels[i];
    if (std::isnan(value)) continue;  // unknown
    if (options.depthKind == DepthKind::Hardware) {
      if (value < 0.0f || value > 1.0f)
        throw std::invalid_argument(pixelText("depth", options.depth, i, depth.width) + " is outside [0, 1] for hardware depth");
      value = gpu::linearDepthFromDevice(hardware, value);
      continue;
    }
    if (!(value > 0.0f)) {
      value = NAN;  // zero or negative: unknown
      continue;
    }
    if (value >= 1e30f) {
      value = INFINITY;  // sky
    } else if (options.depthKind == DepthKind::Distance) {
      // Planar depth from the ray length: the ray through the pixel centre has direction (dx, dy, 1) / |.|.
      const float dx = (float(i % depth.width) + 0.5f - 0.5f * float(depth.width)) / focal;
      const float dy = (float(i / depth.width) + 0.5f - 0.5f * float(depth.height)) / focal;
      value /= std::sqrt(1.0f + dx * dx + dy * dy);
    }
  }
  unknownPixels = fillUnknown(depth, options, "depth");
  return depth;
}

// Disparity mode: a pseudo-depth whose parallax reproduces the disparity exactly and whose order is the
// scene's (a larger disparity is nearer). With zeroParallaxDistance 1 and maxSeparation m = max|d| / W,
// p(depth) = m (1 - 1 / depth) = -d / W for depth = 1 / (1 + d / (m W)): the pass's right eye shows a pixel at
// x + p W = x - d (the right view), its left eye at x + d (the left view). Unknown disparity (NaN, +-inf, 0 in a
// PNG) takes the background's depth and is counted in unknownPixels.
DepthImage depthFromDisparity(const ConvertJobOptions& options, stereo::StereoParameters& parameters,
                              std::uint64_t& unknownPixels) {
  DepthImage disparity = readScalarFile(options, "disparity");
  float largest = 0.0f;
  for (float& d : disparity.pixels) {
    if (!std::isfinite(d)) d = NAN;
    else largest = std::max(largest, std::abs(d));
  }
  const float width = float(disparity.width);
  const float separation = std::max(largest / width, 1.0f / (4.0f * width));  // > 0 even for an all-zero map
  if (separation > stereo::kMaxSeparationLimit)
    throw std::invalid_argument("disparity file '" + options.depth.string() + "' reaches " + numberText(largest) +
                                " px, beyond " + numberText(stereo::kMaxSeparationLimit) + " of the width (" +
                                numberText(stereo::kMaxSeparationLimit * width) + " px)");
  parameters.maxSeparation = separation;
  parameters.zeroParallaxDistance = 1.0f;
  for (float& value : disparity.pixels) {
    if (std::isnan(value)) continue;
    const float share = value / (separation * width);
    value = share <= -1.0f ? INFINITY : 1.0f / (1.0f + share);
  }
  unknownPixels = fillUnknown(disparity, options, "disparity");
  return disparity;
}

// Uploads the frame and runs the parameters' method on it (untimed once, then timed).
stereo::SynthesisResult synthesize(vk::Context& context, const ImageRGBA8& color, const DepthImage& depth,
                                   const stereo::StereoParameters& parameters) {
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image colorImage = vk::createImage(context, stereo::StereoPass::kColorFormat, color.width, color.height, usage);
  vk::Image depthImage = vk::createImage(context, stereo::StereoPass::kDepthFormat, color.width, color.height, usage);
  vk::uploadImage(context, colorImage, std::as_bytes(std::span(color.pixels)), vk::kComputeWrite);
  vk::uploadImage(context, depthImage, std::as_bytes(std::span(depth.pixels)), vk::kComputeWrite);
  return stereo::synthesizeTimed(context, colorImage, depthImage, parameters);
}

std::optional<ImageRGBA8> readReference(const std::optional<fs::path>& file, const ImageRGBA8& color, const char* which) {
  if (!file) return std::nullopt;
  ImageRGBA8 reference = readColor(*file);
  if (reference.width != color.width || reference.height != color.height)
    throw std::invalid_argument(std::string(which) + " reference '" + file->string() + "' is " +
                                sizeText(reference.width, reference.height) + ", the color is " +
                                sizeText(color.width, color.height));
  return reference;
}

nlohmann::json statsJson(const std::optional<stereo::ErrorStats>& stats) {
  if (!stats) return nullptr;
  return {{"psnrDb", stats->psnrDb}, {"meanAbsoluteError", stats->meanAbsoluteError},
          {"shareAbove8", stats->shareAbove8}, {"pixelCount", stats->pixelCount}};
}

bool matchesPattern(const std::string& name, const std::string& prefix, const std::string& suffix, std::string& key) {
  if (name.size() <= prefix.size() + suffix.size()) return false;
  if (name.compare(0, prefix.size(), prefix) != 0) return false;
  if (name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) return false;
  key = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  return true;
}

std::pair<std::string, std::string> splitPattern(const std::string& pattern, const char* option) {
  const std::size_t star = pattern.find('*');
  if (star == std::string::npos || pattern.find('*', star + 1) != std::string::npos ||
      pattern.find('/') != std::string::npos)
    throw std::invalid_argument(std::string(option) + " '" + pattern + "' must be a file name with exactly one '*'");
  return {pattern.substr(0, star), pattern.substr(star + 1)};
}

// The files one frame writes, in order.
std::vector<std::string> outputNames(const std::string& suffix, bool writeReport) {
  std::vector<std::string> names;
  for (const char* view : {"left", "right", "anaglyph", "sbs", "tab"}) names.push_back(view + suffix + ".png");
  if (writeReport) names.push_back("report" + suffix + ".json");
  return names;
}

}  // namespace

ConvertReport runConvertJob(vk::Context& context, const ConvertJobOptions& options) {
  // Every input is read and checked before any output exists.
  io::requireOutputsAreNotInputs(options.outputFolder, outputNames(options.fileSuffix, options.writeReport),
                                   {options.color, options.depth, options.referenceLeft.value_or(fs::path()),
                                    options.referenceRight.value_or(fs::path())});
  ConvertReport report;
  // The frame's memory from the color file's header, before a pixel is decoded.
  requireFile(options.color, "color");
  const io::ImageSize size = io::readImageSize(options.color);
  requirePackableEyes(size.width, size.height, true, options.sideBySide, true, options.topBottom, false);
  report.memory = frame::convertMemoryEstimate(size.width, size.height);
  frame::requireMemory(context, report.memory, options.memoryLimitBytes);
  const ImageRGBA8 color = readColor(options.color, &report.sanitizedColorValues);
  stereo::StereoParameters parameters = options.stereo;
  if (options.automaticMethod) parameters.method = stereo::automaticMethod(stereo::DepthSource::External);
  const DepthImage depth = options.disparity ? depthFromDisparity(options, parameters, report.unknownDepthPixels)
                                             : readLinearDepth(options, report.unknownDepthPixels);
  if (depth.width != color.width || depth.height != color.height)
    throw std::invalid_argument(std::string(options.disparity ? "disparity" : "depth") + " '" + options.depth.string() +
                                "' is " + sizeText(depth.width, depth.height) + ", color '" + options.color.string() +
                                "' is " + sizeText(color.width, color.height));
  const std::optional<ImageRGBA8> referenceLeft = readReference(options.referenceLeft, color, "left");
  const std::optional<ImageRGBA8> referenceRight = readReference(options.referenceRight, color, "right");
  stereo::validate(parameters);
  if (parameters.method == stereo::StereoMethod::Hybrid)
    throw std::invalid_argument("--method hybrid renders pixels from the eye cameras and needs a scene: s3d convert has "
                                "only the frames (use it in s3d render, bench, tune or regress)");
  const bool budgetOn = options.disparityBudget != comfort::DisparityBudgetRule::Off && !options.disparity;
  if (budgetOn) {
    // The depth range, reduced on the GPU, picks maxSeparation and the zero-parallax distance.
    const comfort::DisparityBudget budget = comfort::disparityBudget(options.display);
    std::optional<comfort::DisparityBudgetController> fresh;
    if (!options.budgetController) fresh.emplace(budget, false);
    const stereo::DepthRangePass reduction(context);
    vk::Image depthImage = vk::createImage(context, stereo::StereoPass::kDepthFormat, depth.width, depth.height,
                                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(context, depthImage, std::as_bytes(std::span(depth.pixels)), vk::kComputeWrite);
    report.budget = comfort::applyDisparityBudget(context, reduction, fresh ? &*fresh : options.budgetController, depthImage, {},
                                         1.0f / 30.0f, parameters);
    report.comfort = comfort::frameComfort(depth, parameters, options.display);
  }
  const gpu::StereoConstants constants = stereo::makeStereoConstants(parameters, color.width, color.height);

  report.deviceName = context.deviceName();
  report.color = options.color.string();
  report.depth = options.depth.string();
  report.width = color.width;
  report.height = color.height;
  report.stereo = parameters;
  report.automaticMethod = options.automaticMethod;
  report.cropColumns = std::uint32_t(constants.cropBegin);
  stereo::SynthesisResult synthesis = synthesize(context, color, depth, parameters);
  report.stereoPassGpuMs = synthesis.gpuMs;
  stereo::StereoPair eyes = std::move(synthesis.eyes);
  // Disparity mode: the synthesized view is the eye the disparity points to (depthFromDisparity).
  if (options.disparity == DisparityOutput::Right) eyes.left = color;
  if (options.disparity == DisparityOutput::Left) eyes.right = color;
  if (referenceLeft) report.left = stereo::compareDisplayImages(eyes.left, *referenceLeft, report.cropColumns);
  if (referenceRight) report.right = stereo::compareDisplayImages(eyes.right, *referenceRight, report.cropColumns);

  const fs::path& folder = options.outputFolder;
  auto write = [&](const std::string& name, const ImageRGBA8& image) {
    const std::string file = name + options.fileSuffix + ".png";
    io::writePng(folder / file, image);
    report.filesWritten.push_back(file);
  };
  write("left", eyes.left);
  write("right", eyes.right);
  write("anaglyph", stereo::makeAnaglyphDubois(eyes.left, eyes.right));
  write("sbs", stereo::makeSideBySide(eyes.left, eyes.right, options.sideBySide));
  write("tab", stereo::makeTopAndBottom(eyes.left, eyes.right, options.topBottom));
  if (options.writeReport) {
    const std::string file = "report" + options.fileSuffix + ".json";
    report.filesWritten.push_back(file);
    io::writeTextFile(folder / file, toJson(report).dump(2) + "\n");
  }
  return report;
}

nlohmann::json toJson(const ConvertReport& report) {
  return {{"device", report.deviceName},
          {"color", report.color},
          {"depth", report.depth},
          {"width", report.width},
          {"height", report.height},
          {"stereo",
           {{"maxSeparation", report.stereo.maxSeparation},
            {"zeroParallaxDistance", report.stereo.zeroParallaxDistance},
            {"method", stereo::methodName(report.stereo.method)},
            {"methodChosenBy", report.automaticMethod ? "auto" : "option"}}},
          {"cropColumns", report.cropColumns},
          {"gpuTimeMs", {{"stereoPass", report.stereoPassGpuMs ? nlohmann::json(*report.stereoPassGpuMs) : nullptr}}},
          {"error", {{"left", statsJson(report.left)}, {"right", statsJson(report.right)}}},
          {"sanitized", {{"colorValues", report.sanitizedColorValues}, {"unknownDepthPixels", report.unknownDepthPixels}}},
          {"disparityBudget", budgetJson(report.budget, report.comfort)},
          {"files", report.filesWritten}};
}

std::vector<ConvertFrame> pairFrames(const fs::path& folder, const std::string& colorPattern,
                                     const std::string& depthPattern) {
  const auto [colorPrefix, colorSuffix] = splitPattern(colorPattern, "--color-pattern");
  const auto [depthPrefix, depthSuffix] = splitPattern(depthPattern, "--depth-pattern");
  std::error_code error;
  if (fs::exists(folder, error) && !fs::is_directory(folder, error))
    throw std::invalid_argument("input folder '" + folder.string() + "' is a file, not a folder");
  if (!fs::is_directory(folder, error)) throw std::invalid_argument("input folder '" + folder.string() + "' does not exist");
  std::map<std::string, ConvertFrame> frames;
  std::map<std::string, fs::path> depths;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    std::string key;
    if (matchesPattern(name, colorPrefix, colorSuffix, key)) frames[key] = {key, entry.path(), {}};
    else if (matchesPattern(name, depthPrefix, depthSuffix, key)) depths[key] = entry.path();
  }
  if (frames.empty())
    throw std::invalid_argument("no file in '" + folder.string() + "' matches --color-pattern '" + colorPattern + "'");
  for (auto& [key, frame] : frames) {
    const auto depth = depths.find(key);
    if (depth == depths.end())
      throw std::invalid_argument("color frame '" + frame.color.filename().string() + "' has no depth file '" +
                                  depthPrefix + key + depthSuffix + "'");
    frame.depth = depth->second;
    depths.erase(depth);
  }
  if (!depths.empty())
    throw std::invalid_argument("depth file '" + depths.begin()->second.filename().string() + "' has no color frame '" +
                                colorPrefix + depths.begin()->first + colorSuffix + "'");
  std::vector<ConvertFrame> sorted;
  for (auto& entry : frames) sorted.push_back(std::move(entry.second));
  return sorted;
}

namespace {

// The options that shape a folder run's outputs: a manifest made with others cannot be resumed.
nlohmann::json settingsJson(const ConvertJobOptions& o) {
  const stereo::StereoParameters& p = o.stereo;
  return {{"depthChannel", o.depthChannel},
          {"depthScale", o.depthScale},
          {"depthKind", o.depthKind == DepthKind::Hardware ? "hardware" : o.depthKind == DepthKind::Distance ? "distance" : "linear"},
          {"near", o.nearPlane},
          {"far", o.farPlane},
          {"verticalFovDegrees", o.verticalFovDegrees ? nlohmann::json(*o.verticalFovDegrees) : nlohmann::json()},
          {"focalLengthPx", o.focalLengthPx ? nlohmann::json(*o.focalLengthPx) : nlohmann::json()},
          {"disparity", !o.disparity ? "" : *o.disparity == DisparityOutput::Left ? "left" : "right"},
          {"sideBySide", o.sideBySide == stereo::PackingMode::Full ? "full" : "half"},
          {"topBottom", o.topBottom == stereo::PackingMode::Full ? "full" : "half"},
          {"method", o.automaticMethod ? "auto" : stereo::methodName(p.method)},
          {"maxSeparation", p.maxSeparation},
          {"zeroParallaxDistance", p.zeroParallaxDistance},
          {"edgeCrop", p.edgeCrop},
          {"searchTaps", p.searchTaps},
          {"iterations", p.iterations},
          {"disparityBudget", comfort::disparityBudgetRuleName(o.disparityBudget)},
          {"display", displayJson(o.display)}};
}

// An input as the manifest remembers it: a changed size or modification time means the frame is stale.
nlohmann::json inputJson(const fs::path& file) {
  std::error_code error;
  const auto bytes = fs::file_size(file, error);
  const auto modified = fs::last_write_time(file, error);
  return {{"path", file.string()},
          {"bytes", error ? 0 : bytes},
          {"modifiedNs", error ? 0 : std::chrono::duration_cast<std::chrono::nanoseconds>(modified.time_since_epoch()).count()}};
}

// The frames an earlier run's report.json lists, by key; empty when there is none.
std::map<std::string, nlohmann::json> readManifest(const fs::path& folder, const nlohmann::json& settings) {
  const fs::path file = folder / "report.json";
  std::error_code error;
  if (!fs::exists(fs::symlink_status(file, error))) return {};
  const std::string where = "--resume: '" + file.string() + "'";
  nlohmann::json manifest;
  try {
    manifest = readJsonDocument(file, "--resume: report");
  } catch (const InputFileError& unreadable) {
    throw std::invalid_argument(std::string(unreadable.what()) + "; remove it or run without --resume");
  }
  if (!manifest.is_object() || !manifest.contains("frames") || !manifest["frames"].is_array() ||
      !manifest.contains("settings"))
    throw std::invalid_argument(where + " is not the report of an `s3d convert --input-folder` run: remove it or run "
                                        "without --resume");
  if (manifest["settings"] != settings)
    throw std::invalid_argument(where + " was made with other settings; run without --resume to convert every frame "
                                        "with these");
  std::map<std::string, nlohmann::json> frames;
  for (const nlohmann::json& frame : manifest["frames"])
    if (frame.is_object() && frame.contains("frame") && frame["frame"].is_string())
      frames[frame["frame"].get<std::string>()] = frame;
  return frames;
}

// An earlier run's frame is kept when its inputs are unchanged and every file it wrote is still there.
bool frameIsCurrent(const nlohmann::json& entry, const ConvertFrame& frame, const fs::path& folder) {
  if (!entry.contains("inputs") || entry["inputs"] != nlohmann::json{{"color", inputJson(frame.color)},
                                                                     {"depth", inputJson(frame.depth)}})
    return false;
  if (!entry.contains("files") || !entry["files"].is_array() || entry["files"].empty()) return false;
  std::error_code error;
  for (const nlohmann::json& file : entry["files"])
    if (!file.is_string() || !fs::is_regular_file(fs::symlink_status(folder / file.get<std::string>(), error)))
      return false;
  return true;
}

}  // namespace

std::vector<std::string> convertOutputNames(const ConvertJobOptions& options, const std::vector<ConvertFrame>& frames) {
  if (frames.empty()) return outputNames(options.fileSuffix, options.writeReport);
  std::vector<std::string> names{"report.json"};
  for (const ConvertFrame& frame : frames)
    for (std::string& name : outputNames("_" + frame.key, false)) names.push_back(std::move(name));
  return names;
}

ConvertFolderResult runConvertFolder(vk::Context& context, const ConvertJobOptions& options,
                                     const std::vector<ConvertFrame>& frames,
                                     const std::function<void(std::size_t, std::size_t, const std::string&)>& progress,
                                     FolderResume resume) {
  // A frame's outputs may be another frame's inputs: every name is checked against every input first.
  std::vector<fs::path> inputs{options.referenceLeft.value_or(fs::path()), options.referenceRight.value_or(fs::path())};
  for (const ConvertFrame& frame : frames) {
    inputs.push_back(frame.color);
    inputs.push_back(frame.depth);
  }
  io::requireOutputsAreNotInputs(options.outputFolder, convertOutputNames(options, frames), inputs);
  const nlohmann::json settings = settingsJson(options);
  const std::map<std::string, nlohmann::json> earlier =
      resume == FolderResume::Yes ? readManifest(options.outputFolder, settings) : std::map<std::string, nlohmann::json>{};
  ConvertFolderResult result;
  std::vector<nlohmann::json> frameJson(frames.size());  // null: not (yet) present
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (const auto entry = earlier.find(frames[i].key);
        entry != earlier.end() && frameIsCurrent(entry->second, frames[i], options.outputFolder)) {
      frameJson[i] = entry->second;
      result.kept.push_back(frames[i].key);
    }
  auto writeManifest = [&](bool complete) {
    nlohmann::json present = nlohmann::json::array();
    for (const nlohmann::json& entry : frameJson)
      if (!entry.is_null()) present.push_back(entry);
    io::writeTextFile(options.outputFolder / "report.json",
                      nlohmann::json{{"settings", settings}, {"complete", complete}, {"frames", present}}.dump(2) + "\n");
  };
  std::optional<comfort::DisparityBudgetController> budget;  // one over the whole sequence: smoothed, cuts detected
  if (options.disparityBudget != comfort::DisparityBudgetRule::Off && !options.budgetController)
    budget.emplace(comfort::disparityBudget(options.display), false);
  std::size_t done = 0;
  std::size_t present = result.kept.size();  // frames whose files are in the output folder (resuming)
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const ConvertFrame& frame = frames[i];
    if (frameJson[i].is_null()) {
      ConvertJobOptions frameOptions = options;
      frameOptions.color = frame.color;
      frameOptions.depth = frame.depth;
      frameOptions.fileSuffix = "_" + frame.key;
      frameOptions.writeReport = false;
      if (budget) frameOptions.budgetController = &*budget;
      // Resuming: each frame is its own transaction, committed with the manifest that lists it.
      std::optional<io::OutputTransaction> frameOutputs;
      if (resume == FolderResume::Yes) frameOutputs.emplace(options.outputFolder);
      try {
        result.converted.push_back(runConvertJob(context, frameOptions));
        nlohmann::json json = toJson(result.converted.back());
        json["frame"] = frame.key;
        json["inputs"] = {{"color", inputJson(frame.color)}, {"depth", inputJson(frame.depth)}};
        frameJson[i] = std::move(json);
        if (frameOutputs) {
          writeManifest(i + 1 == frames.size());
          frameOutputs->commit();
          ++present;
        }
      } catch (const std::exception& error) {
        std::string message = "frame '" + frame.key + "': " + error.what();
        if (resume == FolderResume::Yes) {
          message += " (" + std::to_string(present) + " of " + std::to_string(frames.size()) +
                     " frames are in the output folder, listed in its report.json; rerun with --resume to go on)";
        }
        throw std::runtime_error(message);
      }
    }
    if (progress) progress(++done, frames.size(), frame.key);
  }
  if (resume == FolderResume::No || result.converted.empty()) writeManifest(true);
  return result;
}

}  // namespace s3d::app
