// PNG / OpenEXR / text I/O: round trips, error messages and the no-partial-file guarantee.
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>  // only to produce a non-RGBA PNG fixture

#include <unistd.h>  // getpid: keeps parallel test runs in separate folders

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "s3d/io/image_io.h"
#include "io_test_support.h"

namespace s3d::io {
namespace {
namespace fs = std::filesystem;

// A fresh, empty folder per test, removed afterwards.
class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = fs::temp_directory_path() /
              ("s3d_image_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }
  std::vector<std::string> folderEntries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder_)) names.push_back(entry.path().filename().string());
    return names;
  }
  fs::path folder_;
};

ImageRGBA8 patternImage(std::uint32_t width, std::uint32_t height) {
  ImageRGBA8 image(width, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = static_cast<std::uint8_t>(17 * x + 3 * y);
      p[1] = static_cast<std::uint8_t>(255 - 11 * y);
      p[2] = static_cast<std::uint8_t>(x * y);
      p[3] = static_cast<std::uint8_t>(128 + x);
    }
  return image;
}

ImageRGBA32F hdrImage(std::uint32_t width, std::uint32_t height) {
  ImageRGBA32F image(width, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      float* p = image.at(x, y);
      p[0] = 0.001f + 0.37f * float(x);  // spans small to > 1 (HDR)
      p[1] = 1000.0f / float(1 + y);
      p[2] = -0.25f * float(x);          // negative values are legal in linear EXR
      p[3] = 0.5f;
    }
  return image;
}

TEST_F(ImageIoTest, PngRoundTripIsExact) {
  const ImageRGBA8 original = patternImage(7, 5);  // odd sizes catch stride mistakes
  const fs::path file = folder_ / "pattern.png";
  writePng(file, original);
  const ImageRGBA8 loaded = readPng(file);
  EXPECT_EQ(loaded.width, 7u);
  EXPECT_EQ(loaded.height, 5u);
  EXPECT_EQ(loaded.pixels, original.pixels);  // PNG is lossless: exact
}

TEST_F(ImageIoTest, ReadPngExpandsGrayscaleToOpaqueRgba) {
  const fs::path file = folder_ / "gray.png";
  const std::uint8_t gray[2] = {10, 240};
  ASSERT_NE(stbi_write_png(file.string().c_str(), 2, 1, 1, gray, 2), 0);
  const ImageRGBA8 loaded = readPng(file);
  ASSERT_EQ(loaded.width, 2u);
  ASSERT_EQ(loaded.height, 1u);
  const std::vector<std::uint8_t> expected = {10, 10, 10, 255, 240, 240, 240, 255};
  EXPECT_EQ(loaded.pixels, expected);
}

TEST_F(ImageIoTest, SuccessfulWriteLeavesNoTemporaryFile) {
  writePng(folder_ / "a.png", patternImage(2, 2));
  writeExr(folder_ / "b.exr", hdrImage(2, 2), nullptr);
  writeTextFile(folder_ / "c.txt", "report\n");
  std::vector<std::string> entries = folderEntries();
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"a.png", "b.exr", "c.txt"}));
}

TEST_F(ImageIoTest, WriteCreatesMissingParentFolders) {
  const fs::path file = folder_ / "nested" / "deeper" / "out.png";
  writePng(file, patternImage(2, 2));
  EXPECT_TRUE(fs::is_regular_file(file));
}

TEST_F(ImageIoTest, WriteReplacesExistingFile) {
  const fs::path file = folder_ / "report.txt";
  writeTextFile(file, "old contents that are longer");
  writeTextFile(file, "new");
  EXPECT_EQ(test::readFileBytes(file), "new");
}

TEST_F(ImageIoTest, TextFileIsWrittenVerbatim) {
  const std::string text = std::string("line 1\r\nline 2\n\0binary", 22);
  writeTextFile(folder_ / "verbatim.txt", text);
  EXPECT_EQ(test::readFileBytes(folder_ / "verbatim.txt"), text);
}

TEST_F(ImageIoTest, ReadingMissingPngThrowsNamingTheFile) {
  const std::string message = test::runtimeErrorMessage([&] { readPng(folder_ / "absent.png"); });
  EXPECT_NE(message.find("absent.png"), std::string::npos) << message;
}

TEST_F(ImageIoTest, ReadingMissingExrThrowsNamingTheFile) {
  const std::string message = test::runtimeErrorMessage([&] { readExr(folder_ / "absent.exr"); });
  EXPECT_NE(message.find("absent.exr"), std::string::npos) << message;
}

TEST_F(ImageIoTest, ReadingCorruptPngThrowsNamingTheFile) {
  writeTextFile(folder_ / "corrupt.png", "this is not a PNG");
  const std::string message = test::runtimeErrorMessage([&] { readPng(folder_ / "corrupt.png"); });
  EXPECT_NE(message.find("corrupt.png"), std::string::npos) << message;
}

TEST_F(ImageIoTest, ReadingTruncatedPngThrowsNamingTheFile) {
  writePng(folder_ / "whole.png", patternImage(16, 16));
  const std::string bytes = test::readFileBytes(folder_ / "whole.png");
  writeTextFile(folder_ / "truncated.png", std::string_view(bytes).substr(0, bytes.size() / 2));
  const std::string message = test::runtimeErrorMessage([&] { readPng(folder_ / "truncated.png"); });
  EXPECT_NE(message.find("truncated.png"), std::string::npos) << message;
}

TEST_F(ImageIoTest, ReadingCorruptExrThrowsNamingTheFile) {
  writeTextFile(folder_ / "corrupt.exr", "this is not an OpenEXR file at all");
  const std::string message = test::runtimeErrorMessage([&] { readExr(folder_ / "corrupt.exr"); });
  EXPECT_NE(message.find("corrupt.exr"), std::string::npos) << message;
}

TEST_F(ImageIoTest, WritingBelowARegularFileThrowsAndLeavesNothing) {
  // A parent "folder" that is a regular file cannot be created or written into (works even as root,
  // unlike permission bits).
  writeTextFile(folder_ / "blocker", "x");
  const fs::path file = folder_ / "blocker" / "out.png";
  const std::string message = test::runtimeErrorMessage([&] { writePng(file, patternImage(2, 2)); });
  EXPECT_NE(message.find("out.png"), std::string::npos) << message;
  EXPECT_EQ(folderEntries(), std::vector<std::string>{"blocker"});
}

TEST_F(ImageIoTest, FailedRenameRemovesTemporaryFile) {
  // The target is an existing folder: the temporary file is written, then rename fails; it must be cleaned up.
  const fs::path file = folder_ / "occupied.exr";
  fs::create_directories(file / "inside");
  const std::string message = test::runtimeErrorMessage([&] { writeExr(file, hdrImage(2, 2), nullptr); });
  EXPECT_NE(message.find("occupied.exr"), std::string::npos) << message;
  EXPECT_EQ(folderEntries(), std::vector<std::string>{"occupied.exr"});
  EXPECT_TRUE(fs::is_directory(file));
}

TEST_F(ImageIoTest, ObjectAtAPredictableTemporaryNameIsNeitherUsedNorRemoved) {
  const fs::path file = folder_ / "keep.txt";
  writeTextFile(file, "previous");
  fs::create_directories(folder_ / "keep.txt.tmp" / "x");
  writeTextFile(file, "replacement");
  EXPECT_EQ(test::readFileBytes(file), "replacement");
  EXPECT_TRUE(fs::is_directory(folder_ / "keep.txt.tmp" / "x"));  // not ours: must not be touched
}

TEST_F(ImageIoTest, PlantedLinkAtATemporaryNameIsNeverWrittenThrough) {
  const fs::path victim = folder_ / "victim.txt";
  writeTextFile(victim, "precious");
  for (const char* name : {"out.txt.tmp", ".out.txt.tmp", "out.txt~"})
    fs::create_symlink(victim, folder_ / name);
  writeTextFile(folder_ / "out.txt", "new");
  EXPECT_EQ(test::readFileBytes(victim), "precious");
  EXPECT_EQ(test::readFileBytes(folder_ / "out.txt"), "new");
}

TEST_F(ImageIoTest, PlantedLinkAtTheFinalNameIsReplacedNotFollowed) {
  const fs::path victim = folder_ / "victim.txt";
  writeTextFile(victim, "precious");
  fs::create_symlink(victim, folder_ / "out.txt");
  writeTextFile(folder_ / "out.txt", "new");
  EXPECT_EQ(test::readFileBytes(victim), "precious");
  EXPECT_FALSE(fs::is_symlink(folder_ / "out.txt"));
  EXPECT_EQ(test::readFileBytes(folder_ / "out.txt"), "new");
}

TEST_F(ImageIoTest, WritingEmptyPngThrowsInvalidArgument) {
  EXPECT_THROW(writePng(folder_ / "empty.png", ImageRGBA8{}), std::invalid_argument);
  EXPECT_TRUE(folderEntries().empty());
}

TEST_F(ImageIoTest, ExrColorRoundTripsWithinHalfPrecision) {
  const ImageRGBA32F original = hdrImage(5, 3);
  const fs::path file = folder_ / "color.exr";
  writeExr(file, original, nullptr);
  const ExrFrame frame = readExr(file);
  ASSERT_EQ(frame.color.width, 5u);
  ASSERT_EQ(frame.color.height, 3u);
  EXPECT_FALSE(frame.hasDepth);
  EXPECT_TRUE(frame.linearDepth.empty());
  // HALF has a 10-bit mantissa and rounds to nearest: relative error <= 2^-11 for normal values;
  // the absolute floor covers values that land in half's subnormal range.
  for (std::size_t i = 0; i < original.pixels.size(); ++i) {
    const float expected = original.pixels[i];
    EXPECT_NEAR(frame.color.pixels[i], expected, std::abs(expected) * std::ldexp(1.0f, -11) + 1e-7f) << "index " << i;
  }
}

TEST_F(ImageIoTest, ExrDepthRoundTripsExactlyIncludingInfiniteSky) {
  const ImageRGBA32F color = hdrImage(3, 2);
  DepthImage depth(3, 2);
  const float sky = std::numeric_limits<float>::infinity();
  depth.pixels = {0.1f, 1.2345678f, 98765.4321f, sky, 1e-3f, 70000.0f};  // 70000 would overflow HALF
  const fs::path file = folder_ / "depth.exr";
  writeExr(file, color, &depth);
  const ExrFrame frame = readExr(file);
  ASSERT_TRUE(frame.hasDepth);
  ASSERT_EQ(frame.linearDepth.width, 3u);
  ASSERT_EQ(frame.linearDepth.height, 2u);
  EXPECT_EQ(frame.linearDepth.pixels, depth.pixels);  // stored as FLOAT: bit-exact
  EXPECT_TRUE(std::isinf(frame.linearDepth.pixels[3]) && frame.linearDepth.pixels[3] > 0);
}

TEST_F(ImageIoTest, WritingExrWithMismatchedDepthThrowsAndLeavesNothing) {
  DepthImage depth(2, 2, 1.0f);
  EXPECT_THROW(writeExr(folder_ / "bad.exr", hdrImage(3, 2), &depth), std::invalid_argument);
  EXPECT_TRUE(folderEntries().empty());
}

}  // namespace
}  // namespace s3d::io
