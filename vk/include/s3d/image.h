#pragma once
// Plain CPU images shared by every module: row-major, top row first, tightly packed.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace s3d {

template <typename Channel, int ChannelCount>
struct Image {
  static constexpr int channels = ChannelCount;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<Channel> pixels;  // width * height * ChannelCount

  Image() = default;
  Image(std::uint32_t w, std::uint32_t h, Channel fill = Channel{})
      : width(w), height(h), pixels(std::size_t(w) * h * ChannelCount, fill) {}

  std::size_t pixelCount() const { return std::size_t(width) * height; }
  Channel* at(std::uint32_t x, std::uint32_t y) { return &pixels[(std::size_t(y) * width + x) * ChannelCount]; }
  const Channel* at(std::uint32_t x, std::uint32_t y) const {
    return &pixels[(std::size_t(y) * width + x) * ChannelCount];
  }
  bool empty() const { return pixels.empty(); }
};

using ImageRGBA8 = Image<std::uint8_t, 4>;   // display-referred, sRGB-encoded
using ImageRGBA32F = Image<float, 4>;        // scene-referred linear HDR
using DepthImage = Image<float, 1>;          // linear view depth in world units (+inf: sky)

template <typename A, typename B>
void requireSameSize(const A& a, const B& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument(std::string(what) + ": image sizes differ (" + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                                std::to_string(b.height) + ")");
}

}  // namespace s3d
