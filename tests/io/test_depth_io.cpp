// Scalar-image inputs of `s3d convert`: PFM (both byte orders, 1 and 3 channels, bottom-to-top rows),
// 16-bit grey PNG and a named EXR channel; round trips and the errors for bad files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "s3d/io/depth_io.h"
#include "s3d/io/image_io.h"
#include "io_test_support.h"

namespace s3d::io {
namespace {
namespace fs = std::filesystem;

class DepthIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("s3d_depth_io_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                                           "_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }
  fs::path folder_;
};

PfmImage rampPfm(std::uint32_t width, std::uint32_t height, int channels) {
  PfmImage image{width, height, channels, {}};
  for (std::size_t i = 0; i < std::size_t(width) * height * std::size_t(channels); ++i)
    image.values.push_back(0.25f * float(i) - 3.0f);
  return image;
}

TEST_F(DepthIoTest, PfmRoundTripsExactlyInBothByteOrdersAndChannelCounts) {
  for (bool bigEndian : {false, true})
    for (int channels : {1, 3}) {
      const PfmImage original = rampPfm(5, 3, channels);
      writePfm(folder_ / "a.pfm", original, bigEndian);
      const PfmImage loaded = readPfm(folder_ / "a.pfm");
      EXPECT_EQ(loaded.width, 5u);
      EXPECT_EQ(loaded.height, 3u);
      EXPECT_EQ(loaded.channels, channels);
      EXPECT_EQ(loaded.values, original.values) << "bigEndian " << bigEndian << " channels " << channels;
    }
}

TEST_F(DepthIoTest, PfmRowsAreStoredBottomRowFirst) {
  // A hand-made little-endian 1x2 file: the first stored float is the bottom row.
  std::string bytes = "Pf\n1 2\n-1.0\n";
  for (float value : {7.0f, 9.0f}) {
    std::uint32_t word = std::bit_cast<std::uint32_t>(value);
    if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap32(word);
    bytes.append(reinterpret_cast<const char*>(&word), 4);
  }
  test::writeFileBytes(folder_ / "b.pfm", bytes);
  const PfmImage loaded = readPfm(folder_ / "b.pfm");
  EXPECT_EQ(loaded.values, (std::vector<float>{9.0f, 7.0f}));  // top row first in memory
}

TEST_F(DepthIoTest, TruncatedPfmNamesTheMissingBytes) {
  test::writeFileBytes(folder_ / "t.pfm", "Pf\n4 4\n-1.0\n" + std::string(60, '\0'));  // 64 bytes needed
  const std::string message = test::runtimeErrorMessage([&] { readPfm(folder_ / "t.pfm"); });
  EXPECT_NE(message.find("t.pfm"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}

TEST_F(DepthIoTest, PfmWithABadMagicIsRejected) {
  test::writeFileBytes(folder_ / "p.pfm", "P6\n1 1\n255\n\x01\x02\x03");
  EXPECT_NE(test::runtimeErrorMessage([&] { readPfm(folder_ / "p.pfm"); }).find("not a PFM"), std::string::npos);
}

TEST_F(DepthIoTest, PfmWithAZeroScaleIsRejected) {
  test::writeFileBytes(folder_ / "z.pfm", "Pf\n1 1\n0\n" + std::string(4, '\0'));
  EXPECT_NE(test::runtimeErrorMessage([&] { readPfm(folder_ / "z.pfm"); }).find("bad scale"), std::string::npos);
}

TEST_F(DepthIoTest, MissingPfmIsNamed) {
  EXPECT_NE(test::runtimeErrorMessage([&] { readPfm(folder_ / "none.pfm"); }).find("does not exist"), std::string::npos);
}

TEST_F(DepthIoTest, Gray16PngRoundTripsExactly) {
  Gray16Image original(3, 2);
  original.pixels = {0, 1, 255, 256, 40000, 65535};
  writePngGray16(folder_ / "d.png", original);
  const Gray16Image loaded = readPngGray16(folder_ / "d.png");
  EXPECT_EQ(loaded.width, 3u);
  EXPECT_EQ(loaded.height, 2u);
  EXPECT_EQ(loaded.pixels, original.pixels);
}

TEST_F(DepthIoTest, An8BitPngIsNotTakenForDepth) {
  writePng(folder_ / "c.png", ImageRGBA8(2, 2, 7));
  EXPECT_NE(test::runtimeErrorMessage([&] { readPngGray16(folder_ / "c.png"); }).find("8-bit"), std::string::npos);
}

TEST_F(DepthIoTest, TruncatedGray16PngIsRejected) {
  Gray16Image original(16, 16, 1234);
  writePngGray16(folder_ / "d.png", original);
  fs::resize_file(folder_ / "d.png", fs::file_size(folder_ / "d.png") / 2);
  EXPECT_NE(test::runtimeErrorMessage([&] { readPngGray16(folder_ / "d.png"); }).find("d.png"), std::string::npos);
}

TEST_F(DepthIoTest, ExrChannelIsReadByName) {
  DepthImage depth(2, 2);
  depth.pixels = {1.0f, 2.5f, INFINITY, 1000.0f};
  writeExr(folder_ / "f.exr", ImageRGBA32F(2, 2, 0.5f), &depth);
  EXPECT_EQ(readExrChannel(folder_ / "f.exr", "Z").pixels, depth.pixels);  // Z is FLOAT: exact
  EXPECT_EQ(readExrChannel(folder_ / "f.exr", "G").pixels, std::vector<float>(4, 0.5f));  // 0.5 is exact in half
}

TEST_F(DepthIoTest, AMissingExrChannelListsTheChannelsThere) {
  writeExr(folder_ / "f.exr", ImageRGBA32F(2, 2, 0.5f), nullptr);
  const std::string message = test::runtimeErrorMessage([&] { readExrChannel(folder_ / "f.exr", "depth"); });
  EXPECT_NE(message.find("no channel 'depth'"), std::string::npos) << message;
  EXPECT_NE(message.find("R"), std::string::npos) << message;
}

TEST_F(DepthIoTest, TruncatedExrIsRejected) {
  DepthImage depth(8, 8, 3.0f);
  writeExr(folder_ / "f.exr", ImageRGBA32F(8, 8, 0.5f), &depth);
  fs::resize_file(folder_ / "f.exr", fs::file_size(folder_ / "f.exr") - 40);
  EXPECT_NE(test::runtimeErrorMessage([&] { readExrChannel(folder_ / "f.exr", "Z"); }).find("f.exr"), std::string::npos);
}

TEST_F(DepthIoTest, AGray16PngWhoseHeaderClaimsAHugeImageIsRejectedBeforeDecoding) {
  // Found by the png_gray16 fuzzer: 234 x 2293762 pixels claimed by a 77-byte file made the decoder ask for a
  // wrapped-around 16 EiB buffer (AddressSanitizer: allocation-size-too-big). Now refused from the header.
  const fs::path file = fs::path(S3D_TEST_DATA_DIR) / ".." / "fuzz" / "corpus" / "png_gray16" / "huge_header_tiny_file.png";
  ASSERT_TRUE(fs::exists(file));
  const std::string message = test::runtimeErrorMessage([&] { readPngGray16(file); });
  EXPECT_NE(message.find("huge_header_tiny_file.png"), std::string::npos) << message;
  EXPECT_NE(message.find("beyond the readers' limit"), std::string::npos) << message;
}

TEST_F(DepthIoTest, ATiledExrWhoseOffsetsPointPastTheEndIsRejectedNamingIt) {
  // Found by the exr_channel fuzzer: a tile offset beyond the file's end made the in-memory stream's remaining
  // byte count wrap around, and the read ran past the buffer (AddressSanitizer: SEGV). Now a clean error.
  const fs::path file = fs::path(S3D_TEST_DATA_DIR) / ".." / "fuzz" / "corpus" / "exr_channel" / "tiled_offset_past_end.exr";
  ASSERT_TRUE(fs::exists(file));
  const std::string message = test::runtimeErrorMessage([&] { readExrChannel(file, "Z"); });
  EXPECT_NE(message.find("tiled_offset_past_end.exr"), std::string::npos) << message;
}

}  // namespace
}  // namespace s3d::io
