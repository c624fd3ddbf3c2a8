#pragma once
// A PNG's chunk lengths held to its bytes before a decoder sees them, for every PNG s3d reads (image files and
// glTF textures): stb_image allocates what an IDAT chunk declares (up to 1 GiB per chunk, more over several)
// before it finds the bytes missing, so a file of a hundred bytes could take gigabytes.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace s3d {

inline constexpr std::string_view kPngSignature("\x89PNG\r\n\x1a\n", 8);

inline bool hasPngSignature(std::string_view bytes) { return bytes.substr(0, kPngSignature.size()) == kPngSignature; }

// The first chunk (before IEND) whose declared length runs past the end of `bytes`, a PNG after its signature.
struct PngChunkOverrun {
  std::string name;          // the chunk's four-letter type, as written
  std::uint64_t declared{};  // the length it declares, in bytes

  // For an error message: "chunk 'IDAT' declares N bytes, more than the `holder` holds".
  std::string describe(std::string_view holder) const {
    return "chunk '" + name + "' declares " + std::to_string(declared) + " bytes, more than the " +
           std::string(holder) + " holds";
  }
};

inline std::optional<PngChunkOverrun> pngChunkOverrun(std::string_view bytes) {
  for (std::size_t at = kPngSignature.size(); at + 8 <= bytes.size();) {
    const auto byte = [&](std::size_t i) { return std::uint32_t(static_cast<unsigned char>(bytes[at + i])); };
    const std::uint64_t length = (byte(0) << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
    if (length + 12 > bytes.size() - at) return PngChunkOverrun{std::string(bytes.substr(at + 4, 4)), length};
    if (bytes.substr(at + 4, 4) == "IEND") break;
    at += std::size_t(length) + 12;
  }
  return std::nullopt;
}

}  // namespace s3d
