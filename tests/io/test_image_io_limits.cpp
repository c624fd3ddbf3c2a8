// The readers' size limit (kMaxImageSide / kMaxImagePixels): a header claiming a huge image is rejected
// with a clear error before any pixel memory is allocated. Found by tests/fuzz/fuzz_exr.cpp: a 30 KB EXR
// claiming 60000x60000 made readExr allocate 57 GB.
#include <gtest/gtest.h>

#include <unistd.h>  // getpid: keeps parallel test runs apart

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "s3d/io/depth_io.h"
#include "s3d/io/image_io.h"
#include "io_test_support.h"

namespace s3d::io {
namespace {
namespace fs = std::filesystem;

void putLittleEndian(std::string& bytes, std::size_t at, std::uint64_t value, int byteCount) {
  for (int i = 0; i < byteCount; ++i) bytes[at + std::size_t(i)] = char((value >> (8 * i)) & 0xff);
}

fs::path scratchFile(const std::string& name) {
  return fs::temp_directory_path() / ("s3d_io_limits_" + std::to_string(::getpid()) + "_" + name);
}

// A valid EXR whose header claims side x side pixels: a real 4x16 ZIP file (one 16-line block) with its
// data window enlarged and a line-offset table whose every entry points at that one block, so OpenEXR
// opens it and only the pixel read would notice the data is missing.
std::string exrClaiming(std::int32_t side) {
  const fs::path small = scratchFile("small.exr");
  ImageRGBA32F color(4, 16);
  writeExr(small, color, nullptr);
  std::string bytes = test::readFileBytes(small);
  fs::remove(small);
  const std::string key("dataWindow\0box2i\0", 17);
  const std::size_t window = bytes.find(key) + key.size() + 4;  // after the attribute's 4-byte size
  std::size_t table = 0;  // the one offset, which points just past itself
  for (std::size_t at = window; at + 8 <= bytes.size(); ++at) {
    std::uint64_t offset = 0;
    std::memcpy(&offset, bytes.data() + at, 8);  // EXR is little-endian, like the test machines
    if (offset == at + 8) {
      table = at;
      break;
    }
  }
  EXPECT_NE(table, 0u) << "line-offset table not found";
  std::string header = bytes.substr(0, table);
  const std::string block = bytes.substr(table + 8);
  putLittleEndian(header, window + 8, std::uint32_t(side - 1), 4);   // max.x
  putLittleEndian(header, window + 12, std::uint32_t(side - 1), 4);  // max.y
  const std::size_t blocks = (std::size_t(side) + 15) / 16;
  std::string offsets(8 * blocks, '\0');
  for (std::size_t i = 0; i < blocks; ++i) putLittleEndian(offsets, 8 * i, header.size() + offsets.size(), 8);
  return header + offsets + block;
}

TEST(ImageReadLimits, ExrClaimingAHugeImageIsRejectedBeforeItsPixelsAreAllocated) {
  const fs::path file = scratchFile("huge.exr");
  test::writeFileBytes(file, exrClaiming(60000));  // 60000^2 RGBA floats would be 57 GB
  const std::string message = test::runtimeErrorMessage([&] { readExr(file); });
  fs::remove(file);
  EXPECT_NE(message.find("60000x60000"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond the readers' limit"), std::string::npos) << message;
}

TEST(ImageReadLimits, ExrWithinTheLimitGetsAsFarAsItsMissingPixelData) {
  // Same construction at 64 pixels a side: the size passes, and the error is about the missing blocks.
  const fs::path file = scratchFile("small_claim.exr");
  test::writeFileBytes(file, exrClaiming(64));
  const std::string message = test::runtimeErrorMessage([&] { readExr(file); });
  fs::remove(file);
  EXPECT_EQ(message.find("beyond the readers' limit"), std::string::npos) << message;
  EXPECT_NE(message.find("corrupt EXR"), std::string::npos) << message;
}

// A PNG signature and an IHDR chunk for a width x height image, without data (stb does not check the CRC).
std::string pngClaiming(std::uint32_t width, std::uint32_t height, char bitDepth, char colourType) {
  std::string bytes("\x89PNG\r\n\x1a\n", 8);
  bytes += std::string("\0\0\0\x0dIHDR", 8);
  std::string ihdr(13, '\0');
  for (int i = 0; i < 4; ++i) {  // big-endian
    ihdr[std::size_t(i)] = char((width >> (24 - 8 * i)) & 0xff);
    ihdr[std::size_t(4 + i)] = char((height >> (24 - 8 * i)) & 0xff);
  }
  ihdr[8] = bitDepth;
  ihdr[9] = colourType;
  return bytes + ihdr + std::string(4, '\0');
}

// The message of `read` on a scratch file holding `bytes`.
template <typename Read>
std::string messageReading(const std::string& name, const std::string& bytes, Read read) {
  const fs::path file = scratchFile(name);
  test::writeFileBytes(file, bytes);
  const std::string message = test::runtimeErrorMessage([&] { read(file); });
  fs::remove(file);
  return message;
}

TEST(ImageReadLimits, PngClaimingMoreThanTheSideLimitIsRejected) {
  const std::string message = messageReading("wide.png", pngClaiming(20000, 4, 8, 6), [](const fs::path& f) { readPng(f); });
  EXPECT_NE(message.find("20000x4"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond the readers' limit"), std::string::npos) << message;
}

// The depth and disparity readers hold the colour readers' limit: sides within it, pixels beyond it.
TEST(ImageReadLimits, Gray16PngClaimingMoreThanThePixelLimitIsRejected) {
  const std::string message =
      messageReading("big16.png", pngClaiming(9000, 9000, 16, 0), [](const fs::path& f) { readPngGray16(f); });
  EXPECT_NE(message.find("9000x9000"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond the readers' limit"), std::string::npos) << message;
}

TEST(ImageReadLimits, PfmClaimingMoreThanThePixelLimitIsRejected) {
  const std::string message =
      messageReading("big.pfm", "Pf\n9000 9000\n-1.0\n" + std::string(64, '\0'), [](const fs::path& f) { readPfm(f); });
  EXPECT_NE(message.find("9000x9000"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond the readers' limit"), std::string::npos) << message;
}

TEST(ImageReadLimits, ExrChannelClaimingAHugeImageIsRejectedBeforeItsPixelsAreAllocated) {
  const std::string message =
      messageReading("huge_z.exr", exrClaiming(60000), [](const fs::path& f) { readExrChannel(f, "R"); });
  EXPECT_NE(message.find("60000x60000"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond the readers' limit"), std::string::npos) << message;
}

TEST(ImageReadLimits, PngChunkDeclaringMoreBytesThanTheFileHoldsIsRejectedByBothPngReaders) {
  // A signature and an IDAT chunk declaring 2 GB in a 24-byte file: stb would allocate the declared length
  // before finding the data short (found by fuzz_png), so both readers refuse it first.
  std::string bytes("\x89PNG\r\n\x1a\n", 8);
  bytes += std::string("\x7f\xff\xff\xf0IDAT", 8) + std::string(8, '\0');
  const fs::path file = scratchFile("long_chunk.png");
  test::writeFileBytes(file, bytes);
  const std::string colorMessage = test::runtimeErrorMessage([&] { readPng(file); });
  const std::string grayMessage = test::runtimeErrorMessage([&] { readPngGray16(file); });
  fs::remove(file);
  for (const std::string& message : {colorMessage, grayMessage})
    EXPECT_NE(message.find("chunk 'IDAT' declares 2147483632 bytes"), std::string::npos) << message;
}

}  // namespace
}  // namespace s3d::io
