#include "s3d/comfort/comfort_views.h"

#include <algorithm>
#include <cmath>

#include "s3d/comfort/comfort_report.h"
#include "s3d/stereo/metrics.h"

namespace s3d::comfort {
namespace {

// The stereo pass's parallax between the eyes in pixels (sky and invalid depth: infinity / screen plane).
float parallaxBetweenEyesPx(float depth, const stereo::StereoParameters& parameters, std::uint32_t width) {
  const float d = gpu::sanitizedDepth(depth, parameters.zeroParallaxDistance);
  return 2.0f * gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, d) * float(width);
}

}  // namespace

ImageRGBA8 makeParallaxHeatMap(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters) {
  ImageRGBA8 image(stereoDepth.width, stereoDepth.height);
  const float fullScale = std::max(2.0f * parameters.maxSeparation * float(stereoDepth.width), 1.0e-6f);
  for (std::uint32_t y = 0; y < stereoDepth.height; ++y)
    for (std::uint32_t x = 0; x < stereoDepth.width; ++x) {
      const float t =
          std::clamp(parallaxBetweenEyesPx(*stereoDepth.at(x, y), parameters, stereoDepth.width) / fullScale, -1.0f, 1.0f);
      const auto level = [](float v) { return std::uint8_t(std::lround(255.0f * v)); };
      std::uint8_t* pixel = image.at(x, y);
      pixel[0] = level(t > 0.0f ? 1.0f - t : 1.0f);
      pixel[1] = level(1.0f - std::abs(t));
      pixel[2] = level(t < 0.0f ? 1.0f + t : 1.0f);
      pixel[3] = 255;
    }
  return image;
}

std::vector<std::uint8_t> comfortViolationMask(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                                               const DisplayProfile& display, double limitArcmin) {
  std::vector<std::uint8_t> mask(std::size_t(stereoDepth.width) * stereoDepth.height, 0);
  const double metresPerPixel = double(display.screenWidthMeters) / double(stereoDepth.width);
  for (std::uint32_t y = 0; y < stereoDepth.height; ++y)
    for (std::uint32_t x = 0; x < stereoDepth.width; ++x) {
      const double parallaxMetres =
          double(parallaxBetweenEyesPx(*stereoDepth.at(x, y), parameters, stereoDepth.width)) * metresPerPixel;
      if (std::abs(disparityArcminutes(display, parallaxMetres)) > limitArcmin)
        mask[std::size_t(y) * stereoDepth.width + x] = 1;
    }
  return mask;
}

void markComfortViolations(ImageRGBA8& image, const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                           const DisplayProfile& display) {
  requireSameSize(image, stereoDepth, "comfort overlay (image vs depth)");
  const std::vector<std::uint8_t> beyond = comfortViolationMask(stereoDepth, parameters, display);
  std::vector<std::uint8_t> violations;  // kWindowViolation flags
  (void)frameComfort(stereoDepth, parameters, display, &violations);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    const std::array<int, 3>* color = violations[i] & kWindowViolation ? &kWindowViolationColor
                                      : beyond[i]                      ? &kBeyondLimitColor
                                                                       : nullptr;
    if (!color) continue;
    std::uint8_t* pixel = &image.pixels[i * 4];
    for (std::size_t c = 0; c < 3; ++c) pixel[c] = std::uint8_t((int(pixel[c]) + (*color)[c] + 1) / 2);
  }
}

}  // namespace s3d::comfort
