#include "s3d/stereo/output_formats.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "s3d/stereo/srgb.h"

namespace s3d::stereo {
namespace {

using Matrix3 = std::array<std::array<float, 3>, 3>;  // row-major: output channel x input channel

// E. Dubois, "A projection method to generate anaglyph stereo images", ICASSP 2001; red-cyan matrices
// as published on Dubois' anaglyph page for that method (applied to linear RGB). His 2009 revision
// (0.437, 0.449, ...) targets different display/filter measurements; we keep the ICASSP 2001 set.
constexpr Matrix3 kDuboisRedCyanLeft = {{
    {0.456f, 0.500f, 0.176f},
    {-0.040f, -0.038f, -0.016f},
    {-0.015f, -0.021f, -0.005f},
}};
constexpr Matrix3 kDuboisRedCyanRight = {{
    {-0.043f, -0.088f, -0.002f},
    {0.378f, 0.734f, -0.018f},
    {-0.072f, -0.113f, 1.226f},
}};

// A struct's public fields can disagree with each other; catch that before indexing out of bounds.
void requireConsistentImage(const ImageRGBA8& image, const char* what) {
  if (image.width == 0 || image.height == 0)
    throw std::invalid_argument(std::string(what) + ": image is empty (" + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + ")");
  if (image.pixels.size() != image.pixelCount() * ImageRGBA8::channels)
    throw std::invalid_argument(std::string(what) + ": pixel buffer holds " + std::to_string(image.pixels.size()) +
                                " values, expected " + std::to_string(image.pixelCount() * ImageRGBA8::channels) +
                                " for " + std::to_string(image.width) + "x" + std::to_string(image.height) + " RGBA");
}

void requireStereoPair(const ImageRGBA8& left, const ImageRGBA8& right, const char* what) {
  requireSameSize(left, right, what);
  requireConsistentImage(left, what);
  requireConsistentImage(right, what);
}

// One source sample's share of a destination sample along one axis.
struct AxisTap {
  std::uint32_t source;
  float weight;
};

// Area-weighted box filter from sourceLength to targetLength samples (targetLength <= sourceLength).
// Target k covers [k*n, (k+1)*n) and source s covers [s*m, (s+1)*m) in units of 1/(n*m) of the axis,
// so overlaps are exact integers; for n == 2m every target is exactly the mean of one source pair.
std::vector<std::vector<AxisTap>> boxFilterTaps(std::uint32_t sourceLength, std::uint32_t targetLength) {
  const std::uint64_t n = sourceLength;
  const std::uint64_t m = targetLength;
  std::vector<std::vector<AxisTap>> taps(targetLength);
  for (std::uint64_t k = 0; k < m; ++k) {
    const std::uint64_t begin = k * n;
    const std::uint64_t end = (k + 1) * n;
    for (std::uint64_t s = begin / m; s * m < end; ++s) {
      const std::uint64_t overlap = std::min(end, (s + 1) * m) - std::max(begin, s * m);
      if (overlap == 0) continue;
      taps[k].push_back({static_cast<std::uint32_t>(s), static_cast<float>(static_cast<double>(overlap) / double(n))});
    }
  }
  return taps;
}

// Squeeze one eye into a targetWidth x targetHeight block of the frame at (originX, originY).
// Colour is averaged in linear light (averaging sRGB codes would darken edges); alpha is already linear.
void packEyeFiltered(const ImageRGBA8& eye, ImageRGBA8& frame, std::uint32_t originX, std::uint32_t originY,
                     std::uint32_t targetWidth, std::uint32_t targetHeight) {
  const auto columnTaps = boxFilterTaps(eye.width, targetWidth);
  const auto rowTaps = boxFilterTaps(eye.height, targetHeight);
  for (std::uint32_t y = 0; y < targetHeight; ++y) {
    for (std::uint32_t x = 0; x < targetWidth; ++x) {
      std::array<float, 4> sum{};
      for (const AxisTap& row : rowTaps[y]) {
        for (const AxisTap& column : columnTaps[x]) {
          const float weight = row.weight * column.weight;
          const std::uint8_t* source = eye.at(column.source, row.source);
          for (int c = 0; c < 3; ++c) sum[c] += weight * decodeSrgb8(source[c]);
          sum[3] += weight * static_cast<float>(source[3]);
        }
      }
      std::uint8_t* target = frame.at(originX + x, originY + y);
      for (int c = 0; c < 3; ++c) target[c] = encodeSrgb8(sum[c]);
      target[3] = static_cast<std::uint8_t>(std::lround(std::clamp(sum[3], 0.0f, 255.0f)));
    }
  }
}

// Full-resolution packing is a plain copy: no resampling, so no colour conversion either.
void copyEye(const ImageRGBA8& eye, ImageRGBA8& frame, std::uint32_t originX, std::uint32_t originY) {
  const std::size_t rowBytes = std::size_t(eye.width) * ImageRGBA8::channels;
  for (std::uint32_t y = 0; y < eye.height; ++y)
    std::copy_n(eye.at(0, y), rowBytes, frame.at(originX, originY + y));
}

}  // namespace

ImageRGBA8 makeAnaglyphDubois(const ImageRGBA8& left, const ImageRGBA8& right) {
  requireStereoPair(left, right, "makeAnaglyphDubois");
  ImageRGBA8 anaglyph(left.width, left.height);
  for (std::size_t i = 0; i < left.pixelCount(); ++i) {
    const std::uint8_t* l = &left.pixels[i * 4];
    const std::uint8_t* r = &right.pixels[i * 4];
    const std::array<float, 3> leftLinear = {decodeSrgb8(l[0]), decodeSrgb8(l[1]), decodeSrgb8(l[2])};
    const std::array<float, 3> rightLinear = {decodeSrgb8(r[0]), decodeSrgb8(r[1]), decodeSrgb8(r[2])};
    std::uint8_t* out = &anaglyph.pixels[i * 4];
    for (std::size_t row = 0; row < 3; ++row) {
      float mixed = 0.0f;
      for (std::size_t c = 0; c < 3; ++c)
        mixed += kDuboisRedCyanLeft[row][c] * leftLinear[c] + kDuboisRedCyanRight[row][c] * rightLinear[c];
      out[row] = encodeSrgb8(std::clamp(mixed, 0.0f, 1.0f));
    }
    out[3] = 255;  // an anaglyph is one opaque picture; eye alpha has no meaning after mixing
  }
  return anaglyph;
}

PackingMode parsePackingMode(std::string_view name) {
  if (name == "half") return PackingMode::Half;
  if (name == "full") return PackingMode::Full;
  throw std::invalid_argument("unknown packing mode '" + std::string(name) + "' (choices: half, full)");
}

ImageRGBA8 makeSideBySide(const ImageRGBA8& left, const ImageRGBA8& right, PackingMode mode) {
  requireStereoPair(left, right, "makeSideBySide");
  const std::uint32_t eyeWidth = left.width;
  const std::uint32_t eyeHeight = left.height;
  if (mode == PackingMode::Full) {
    ImageRGBA8 frame(2 * eyeWidth, eyeHeight);
    copyEye(left, frame, 0, 0);
    copyEye(right, frame, eyeWidth, 0);
    return frame;
  }
  if (eyeWidth < 2) throw std::invalid_argument("side-by-side half packing needs eyes at least 2 pixels wide");
  const std::uint32_t leftColumns = (eyeWidth + 1) / 2;  // odd width: the left eye takes the spare column
  const std::uint32_t rightColumns = eyeWidth - leftColumns;
  ImageRGBA8 frame(eyeWidth, eyeHeight);
  packEyeFiltered(left, frame, 0, 0, leftColumns, eyeHeight);
  packEyeFiltered(right, frame, leftColumns, 0, rightColumns, eyeHeight);
  return frame;
}

ImageRGBA8 makeTopAndBottom(const ImageRGBA8& left, const ImageRGBA8& right, PackingMode mode) {
  requireStereoPair(left, right, "makeTopAndBottom");
  const std::uint32_t eyeWidth = left.width;
  const std::uint32_t eyeHeight = left.height;
  if (mode == PackingMode::Full) {
    ImageRGBA8 frame(eyeWidth, 2 * eyeHeight);
    copyEye(left, frame, 0, 0);
    copyEye(right, frame, 0, eyeHeight);
    return frame;
  }
  if (eyeHeight < 2) throw std::invalid_argument("top-and-bottom half packing needs eyes at least 2 pixels tall");
  const std::uint32_t topRows = (eyeHeight + 1) / 2;  // odd height: the top (left) eye takes the spare row
  const std::uint32_t bottomRows = eyeHeight - topRows;
  ImageRGBA8 frame(eyeWidth, eyeHeight);
  packEyeFiltered(left, frame, 0, 0, eyeWidth, topRows);
  packEyeFiltered(right, frame, 0, topRows, eyeWidth, bottomRows);
  return frame;
}

}  // namespace s3d::stereo
