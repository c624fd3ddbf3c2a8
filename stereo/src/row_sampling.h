#pragma once
// CPU side of the stereo shaders' color fetch, shared by every C++ reference implementation.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "s3d/image.h"

namespace s3d::stereo::detail {

inline int clampInt(int value, int low, int high) { return std::min(std::max(value, low), high); }

// Horizontal linear filter at texel coordinate u (texel centers at integers), clamped to the edge: what a
// bilinear texture fetch does on one row. Written as the shaders write it so both round alike.
inline void sampleRow(const ImageRGBA8& image, int y, float u, std::uint8_t* out) {
  float base = std::floor(u);
  float fraction = u - base;
  int x0 = clampInt(int(base), 0, int(image.width) - 1);
  int x1 = clampInt(int(base) + 1, 0, int(image.width) - 1);
  const std::uint8_t* a = image.at(std::uint32_t(x0), std::uint32_t(y));
  const std::uint8_t* b = image.at(std::uint32_t(x1), std::uint32_t(y));
  for (int channel = 0; channel < 4; ++channel) {
    float va = float(a[channel]) / 255.0f;
    float vb = float(b[channel]) / 255.0f;
    float value = va * (1.0f - fraction) + vb * fraction;
    out[channel] = std::uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
  }
}

}  // namespace s3d::stereo::detail
