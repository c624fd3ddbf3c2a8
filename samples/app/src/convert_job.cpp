#include "s3d/app/convert_job.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "s3d/gpu/linear_depth.h"
#include "s3d/io/image_io.h"
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
  if (!fs::is_regular_file(file)) throw std::invalid_argument(std::string(what) + " file '" + file.string() + "' does not exist");
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

// NaN (and -inf) depth is replaced by the zero-parallax distance, as the stereo pass reads it, and counted.
DepthImage readLinearDepth(const ConvertJobOptions& options, std::uint64_t& sanitizedPixels) {
  requireFile(options.depth, "depth");
  if (lowerExtension(options.depth) != ".exr")
    throw std::invalid_argument("depth file '" + options.depth.string() + "': expected an .exr with a Z channel");
  io::ExrFrame frame = io::readExr(options.depth);
  if (!frame.hasDepth)
    throw std::invalid_argument("depth file '" + options.depth.string() + "' has no Z channel");
  DepthImage depth = std::move(frame.linearDepth);
  gpu::LinearDepthParams hardware{};
  if (options.depthKind == DepthKind::Hardware) {
    if (!(options.nearPlane > 0.0f) || !(options.farPlane > options.nearPlane) || !std::isfinite(options.farPlane))
      throw std::invalid_argument("hardware depth needs 0 < --near < --far (got near " + std::to_string(options.nearPlane) +
                                  ", far " + std::to_string(options.farPlane) + ")");
    // One layer spanning device depth [0, 1]: no first-person range, 1.0 is sky.
    hardware.worldRatio = gpu::projectionRatio(options.nearPlane, options.farPlane, 0.0f, 1.0f);
    hardware.firstPersonDeviceDepthMax = -1.0f;
    hardware.skyDeviceDepth = 1.0f;
    hardware.firstPersonDepthScale = 1.0f;
  }
  for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
    float& value = depth.pixels[i];
    const std::uint32_t x = std::uint32_t(i % depth.width), y = std::uint32_t(i / depth.width);
    const std::string where = "depth file '" + options.depth.string() + "' at pixel (" + std::to_string(x) + ", " +
                              std::to_string(y) + ")";
    if (std::isnan(value) || value == -INFINITY) {
      value = options.stereo.zeroParallaxDistance;  // gpu::sanitizedDepth's reading
      ++sanitizedPixels;
      continue;
    }
    if (options.depthKind == DepthKind::Hardware) {
      if (value < 0.0f || value > 1.0f) throw std::invalid_argument(where + " is outside [0, 1] for hardware depth");
      value = gpu::linearDepthFromDevice(hardware, value);
    } else {
      if (!(value > 0.0f)) throw std::invalid_argument(where + " is not positive (" + std::to_string(value) + ")");
      if (value >= 1e30f) value = INFINITY;  // sky
    }
  }
  return depth;
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
                                std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                                ", the color is " + std::to_string(color.width) + "x" + std::to_string(color.height));
  return reference;
}

nlohmann::json statsJson(const std::optional<stereo::ErrorStats>& stats) {
  if (!stats) return nullptr;
  return {{"psnrDb", stats->psnrDb}, {"meanAbsoluteError", stats->meanAbsoluteError},
          {"shareAbove8", stats->shareAbove8}, {"pixelCount", stats->pixelCount}};
}

}  // namespace

ConvertReport runConvertJob(vk::Context& context, const ConvertJobOptions& options) {
  // Every input is read and checked before any output exists.
  ConvertReport report;
  const ImageRGBA8 color = readColor(options.color, &report.sanitizedColorValues);
  const DepthImage depth = readLinearDepth(options, report.sanitizedDepthPixels);
  if (depth.width != color.width || depth.height != color.height)
    throw std::invalid_argument("depth '" + options.depth.string() + "' is " + std::to_string(depth.width) + "x" +
                                std::to_string(depth.height) + ", color '" + options.color.string() + "' is " +
                                std::to_string(color.width) + "x" + std::to_string(color.height));
  const std::optional<ImageRGBA8> referenceLeft = readReference(options.referenceLeft, color, "left");
  const std::optional<ImageRGBA8> referenceRight = readReference(options.referenceRight, color, "right");
  const gpu::StereoConstants constants = stereo::makeStereoConstants(options.stereo, color.width, color.height);

  report.deviceName = context.deviceName();
  report.width = color.width;
  report.height = color.height;
  report.cropColumns = std::uint32_t(constants.cropBegin);
  stereo::SynthesisResult synthesis = synthesize(context, color, depth, options.stereo);
  report.stereoPassGpuMs = synthesis.gpuMs;
  const stereo::StereoPair eyes = std::move(synthesis.eyes);
  if (referenceLeft) report.left = stereo::compareDisplayImages(eyes.left, *referenceLeft, report.cropColumns);
  if (referenceRight) report.right = stereo::compareDisplayImages(eyes.right, *referenceRight, report.cropColumns);

  const fs::path& folder = options.outputFolder;
  auto write = [&](const std::string& name, const ImageRGBA8& image) {
    io::writePng(folder / name, image);
    report.filesWritten.push_back(name);
  };
  write("left.png", eyes.left);
  write("right.png", eyes.right);
  write("anaglyph.png", stereo::makeAnaglyphDubois(eyes.left, eyes.right));
  write("sbs.png", stereo::makeSideBySide(eyes.left, eyes.right, options.sideBySide));
  write("tab.png", stereo::makeTopAndBottom(eyes.left, eyes.right, options.topBottom));
  report.filesWritten.push_back("report.json");
  io::writeTextFile(folder / "report.json", toJson(report).dump(2) + "\n");
  return report;
}

nlohmann::json toJson(const ConvertReport& report) {
  return {{"device", report.deviceName},
          {"width", report.width},
          {"height", report.height},
          {"cropColumns", report.cropColumns},
          {"gpuTimeMs", {{"stereoPass", report.stereoPassGpuMs ? nlohmann::json(*report.stereoPassGpuMs) : nullptr}}},
          {"error", {{"left", statsJson(report.left)}, {"right", statsJson(report.right)}}},
          {"sanitized", {{"colorValues", report.sanitizedColorValues}, {"depthPixels", report.sanitizedDepthPixels}}},
          {"files", report.filesWritten}};
}

}  // namespace s3d::app
