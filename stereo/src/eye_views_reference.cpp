#include "s3d/stereo/eye_views_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace s3d::stereo {
namespace {

float depthAt(const DepthImage& depth, glm::dvec2 pixel) {
  const int x = std::clamp(int(std::floor(pixel.x)), 0, int(depth.width) - 1);
  const int y = std::clamp(int(std::floor(pixel.y)), 0, int(depth.height) - 1);
  const float d = depth.at(std::uint32_t(x), std::uint32_t(y))[0];
  return d > 0.0f ? d : INFINITY;  // invalid depth: no displacement
}

void bilinear(const ImageRGBA8& image, glm::dvec2 pixel, std::uint8_t* out) {
  const double fx = std::clamp(pixel.x - 0.5, 0.0, double(image.width - 1));
  const double fy = std::clamp(pixel.y - 0.5, 0.0, double(image.height - 1));
  const std::uint32_t x0 = std::uint32_t(fx), y0 = std::uint32_t(fy);
  const std::uint32_t x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const double ax = fx - x0, ay = fy - y0;
  for (int c = 0; c < 4; ++c) {
    const double top = image.at(x0, y0)[c] * (1 - ax) + image.at(x1, y0)[c] * ax;
    const double bottom = image.at(x0, y1)[c] * (1 - ax) + image.at(x1, y1)[c] * ax;
    out[c] = std::uint8_t(std::lround(top * (1 - ay) + bottom * ay));
  }
}

}  // namespace

ImageRGBA8 synthesizeEyeForView(const ImageRGBA8& centerColor, const DepthImage& centerDepth,
                                const ViewConfiguration& views, const CenterView& center, int eye,
                                DepthImage* eyeDepth) {
  requireSameSize(centerColor, centerDepth, "view synthesis (color vs depth)");
  const EyeView& view = views.eyes[std::size_t(eye)];
  ImageRGBA8 out(view.width, view.height);
  if (eyeDepth) *eyeDepth = DepthImage(view.width, view.height);
  for (std::uint32_t y = 0; y < view.height; ++y)
    for (std::uint32_t x = 0; x < view.width; ++x) {
      const glm::dvec2 eyePixel(x + 0.5, y + 0.5);
      double depth = INFINITY;
      glm::dvec2 source = centerPixelForEyePixel(views, center, eye, eyePixel, depth);
      for (int i = 0; i < kViewSearchIterations; ++i) {
        depth = depthAt(centerDepth, source);
        source = centerPixelForEyePixel(views, center, eye, eyePixel, depth);
      }
      bilinear(centerColor, source, out.at(x, y));
      out.at(x, y)[3] = 255;
      if (eyeDepth) *eyeDepth->at(x, y) = float(depth);
    }
  return out;
}

}  // namespace s3d::stereo
