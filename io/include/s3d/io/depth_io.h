#pragma once
// Scalar-image inputs of `s3d convert` (depth, disparity): PFM, 16-bit grey PNG and one named OpenEXR channel.
// Same rules as image_io.h: writes are atomic (temporary file, then rename); failures throw std::runtime_error
// naming the file and the problem (missing, not the format, truncated, missing channel, or a header claiming more
// than every reader's limit in s3d/image_limits.h).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "s3d/image.h"

namespace s3d::io {

// Portable float map: "PF" (3 channels) or "Pf" (1 channel), then width, height and a scale whose sign gives
// the byte order (negative: little-endian, positive: big-endian), then float rows stored bottom row first.
struct PfmImage {
  std::uint32_t width = 0, height = 0;
  int channels = 1;           // 1 or 3
  std::vector<float> values;  // width * height * channels, top row first (flipped from the file), interleaved
};

// Throws std::runtime_error for a missing file, a bad header, or fewer pixel bytes than the header promises.
PfmImage readPfm(const std::filesystem::path& file);
// Writes bottom row first with scale -1 (little-endian) or +1 (big-endian).
// Throws std::invalid_argument for an empty or inconsistent image or a channel count other than 1 or 3.
void writePfm(const std::filesystem::path& file, const PfmImage& image, bool bigEndian = false);

using Gray16Image = Image<std::uint16_t, 1>;

// A 16-bit single-channel (grey, or grey + alpha: alpha ignored) PNG. Throws std::runtime_error naming the file
// when it is missing, corrupt, 8-bit or colour: depth stored in 8 bits or RGB is almost certainly a mistake.
Gray16Image readPngGray16(const std::filesystem::path& file);
// 16-bit grey PNG (stored, uncompressed deflate blocks: tiny images for tests and depth exports).
void writePngGray16(const std::filesystem::path& file, const Gray16Image& image);

// One channel of a scanline or tiled single-part EXR as float (HALF and UINT are converted), over its data window.
// Throws std::runtime_error naming the file and the channels it has when `channel` is absent.
DepthImage readExrChannel(const std::filesystem::path& file, const std::string& channel);

}  // namespace s3d::io
