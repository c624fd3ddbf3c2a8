#pragma once
// Synthetic center views for the stereo tests: random color over depth in blocks with sharp edges.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "s3d/image.h"

namespace s3d::test {

struct SyntheticView {
  ImageRGBA8 color;
  DepthImage depth;
};

// Blocks blockHeight rows tall; each block is blockWidth columns wide (or 1..blockWidth at random when
// variableWidth), a quarter of them sky (+inf), the rest at a depth in [nearestDepth, 50].
inline SyntheticView makeBlockView(std::uint32_t width, std::uint32_t height, unsigned seed, float nearestDepth,
                                   std::uint32_t blockWidth, std::uint32_t blockHeight, bool variableWidth) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_real_distribution<float> depthDist(nearestDepth, 50.0f);
  SyntheticView view{ImageRGBA8(width, height), DepthImage(width, height)};
  for (auto& channel : view.color.pixels) channel = std::uint8_t(byte(random));
  for (std::uint32_t by = 0; by < height; by += blockHeight)
    for (std::uint32_t bx = 0; bx < width; bx += variableWidth ? 1 + std::uint32_t(random() % blockWidth) : blockWidth) {
      float blockDepth = (random() % 4 == 0) ? INFINITY : depthDist(random);
      for (std::uint32_t y = by; y < std::min(by + blockHeight, height); ++y)
        for (std::uint32_t x = bx; x < std::min(bx + blockWidth, width); ++x) *view.depth.at(x, y) = blockDepth;
    }
  return view;
}

inline int largestChannelDifference(const ImageRGBA8& a, const ImageRGBA8& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
}

}  // namespace s3d::test
