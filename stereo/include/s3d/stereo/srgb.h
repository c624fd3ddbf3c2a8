#pragma once
// sRGB transfer function (IEC 61966-2-1): display images are stored encoded, but filtering and
// colour mixing must happen in linear light, so every module converts through these helpers.
#include <array>
#include <cmath>
#include <cstdint>

namespace s3d::stereo {

// Encoded sRGB value in [0,1] -> linear light in [0,1].
inline float srgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;  // linear toe avoids an infinite slope at black
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Linear light in [0,1] -> encoded sRGB value in [0,1].
inline float linearToSrgb(float linear) {
  if (linear <= 0.0031308f) return linear * 12.92f;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// Linear light -> 8-bit sRGB code; out-of-gamut values are clamped (NaN maps to black) because a
// display image cannot represent them.
inline std::uint8_t encodeSrgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also catches NaN
  if (linear >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(linearToSrgb(linear) * 255.0f));
}

// All 256 decoded values, computed once: decoding is on every pixel's hot path.
inline const std::array<float, 256>& srgb8DecodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values{};
    for (std::size_t code = 0; code < values.size(); ++code)
      values[code] = srgbToLinear(static_cast<float>(code) / 255.0f);
    return values;
  }();
  return table;
}

// 8-bit sRGB code -> linear light in [0,1].
inline float decodeSrgb8(std::uint8_t code) { return srgb8DecodeTable()[code]; }

}  // namespace s3d::stereo
