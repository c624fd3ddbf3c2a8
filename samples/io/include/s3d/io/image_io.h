#pragma once
// File input/output for the samples: PNG display images, OpenEXR HDR colour + linear depth, text reports.
// Every write is atomic (temporary file in the same folder, then rename), so a crash or error never
// leaves a truncated output behind; failures throw std::runtime_error naming the file and the reason.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "s3d/image.h"

namespace s3d::io {

// Largest image the readers accept. A header claiming more is rejected before any pixel memory is
// allocated, so a small corrupt or hostile file cannot exhaust memory (found by tests/fuzz/fuzz_exr.cpp).
// 16384 is the usual Vulkan maxImageDimension2D; 2^26 pixels (8192x8192, more than 8K UHD) keep an
// RGBA float frame at 1 GiB.
inline constexpr std::uint32_t kMaxImageSide = 16384;
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 26;

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

// Writes text verbatim (no newline translation). The parent folder is created if missing.
void writeTextFile(const std::filesystem::path& file, std::string_view text);

}  // namespace s3d::io
