#pragma once
// Largest image any s3d reader accepts (PNG/EXR/PFM files, glTF textures), in one place. A header claiming
// more is rejected before any pixel memory is allocated, so a small corrupt or hostile file cannot exhaust
// memory (found by tests/fuzz/fuzz_exr.cpp). 16384 is the usual Vulkan maxImageDimension2D; 2^26 pixels
// (8192x8192, more than 8K UHD) keep an RGBA float frame at 1 GiB.
#include <cstdint>

namespace s3d {
inline constexpr std::uint32_t kMaxImageSide = 16384;
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 26;
}  // namespace s3d
