#pragma once
// A texture written as PNG for a test's scene, through Debian's libstb (it compiles stb_image_write in), so the
// library tests need no tool code to make one.
#include <stb/stb_image_write.h>

#include <filesystem>
#include <stdexcept>

#include "s3d/image.h"

namespace s3d::test {

inline void writePng(const std::filesystem::path& file, const ImageRGBA8& image) {
  const int stride = int(image.width) * 4;
  if (!stbi_write_png(file.c_str(), int(image.width), int(image.height), 4, image.pixels.data(), stride))
    throw std::runtime_error("cannot write the test texture '" + file.string() + "'");
}

}  // namespace s3d::test
