#pragma once
// Image files: PNG display images, OpenEXR HDR colour + linear depth, text reports (a host's saved stereo frame,
// the tools' outputs).
// Every write is atomic (temporary file in the same folder, then rename), so a crash or error never
// leaves a truncated output behind; failures throw std::runtime_error naming the file and the reason.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "s3d/image.h"
#include "s3d/image_limits.h"

namespace s3d::io {

// Largest image the readers accept (s3d/image_limits.h: the same limits hold for glTF textures).
using s3d::kMaxImagePixels;
using s3d::kMaxImageSide;

// 8-bit RGBA PNG. The parent folder is created if missing.
// Throws std::invalid_argument for an empty or inconsistent image, std::runtime_error if writing fails.
void writePng(const std::filesystem::path& file, const ImageRGBA8& image);

// Any PNG (grey, grey+alpha, RGB, RGBA, palette; 16-bit is reduced to 8) expanded to RGBA8
// (missing alpha becomes 255). Throws std::runtime_error naming the file if it is missing, not a PNG or
// larger than kMaxImageSide / kMaxImagePixels.
ImageRGBA8 readPng(const std::filesystem::path& file);

// Scanline OpenEXR: R, G, B, A as HALF (values beyond +-65504 become +-inf, half precision is ~3 digits)
// and, if linearDepth is given, "Z" as FLOAT holding linear depth (+inf for sky is kept as +inf).
// Throws std::invalid_argument if the sizes differ or an image is empty, std::runtime_error if writing fails.
void writeExr(const std::filesystem::path& file, const ImageRGBA32F& color, const DepthImage* linearDepth);

struct ExrFrame {
  ImageRGBA32F color;       // R, G, B required in the file; A defaults to 1 when absent
  DepthImage linearDepth;   // empty unless hasDepth
  bool hasDepth = false;    // true when the file has a "Z" channel
};

// Reads the data window of a scanline or tiled single-part EXR into linear float images.
// Throws std::runtime_error naming the file if it is missing, corrupt, lacks R/G/B, uses subsampled channels
// or is larger than kMaxImageSide / kMaxImagePixels.
ExrFrame readExr(const std::filesystem::path& file);

// The width and height a PNG, EXR or PFM file's header declares (by its extension, case-insensitive), read
// without decoding a pixel, so a run can budget its memory before it allocates any. Throws std::runtime_error
// naming the file when it is missing, not of its kind, or its header is corrupt.
struct ImageSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};
ImageSize readImageSize(const std::filesystem::path& file);

// Writes text verbatim (no newline translation). The parent folder is created if missing.
void writeTextFile(const std::filesystem::path& file, std::string_view text);

}  // namespace s3d::io
