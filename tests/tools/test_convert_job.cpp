// `s3d convert`: stereo from external color + depth files, and its refusal of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <unistd.h>

#include "s3d/app/convert_job.h"
#include "s3d/gpu/linear_depth.h"
#include "s3d/io/depth_io.h"
#include "s3d/io/image_io.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {

namespace fs = std::filesystem;

class ConvertJob : public test::VulkanTest {
 protected:
  void SetUp() override {
    test::VulkanTest::SetUp();
    folder_ = fs::temp_directory_path() / ("s3d_convert_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    // 48x20 random color; depth in vertical bands 1..8 m with sky on the right.
    std::mt19937 random(5);
    color_ = ImageRGBA8(48, 20);
    for (auto& channel : color_.pixels) channel = std::uint8_t(random() % 256);
    for (std::uint32_t i = 3; i < color_.pixels.size(); i += 4) color_.pixels[i] = 255;
    depth_ = DepthImage(48, 20);
    for (std::uint32_t y = 0; y < 20; ++y)
      for (std::uint32_t x = 0; x < 48; ++x) *depth_.at(x, y) = x >= 40 ? INFINITY : 1.0f + float(x / 6);
    writeInputs(depth_);
    options_.color = folder_ / "color.png";
    options_.depth = folder_ / "depth.exr";
    options_.outputFolder = folder_ / "out";
    options_.stereo.maxSeparation = 0.05f;
    options_.stereo.zeroParallaxDistance = 2.0f;
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
    test::VulkanTest::TearDown();
  }
  void writeInputs(const DepthImage& depth) {
    io::writePng(folder_ / "color.png", color_);
    io::writeExr(folder_ / "depth.exr", ImageRGBA32F(depth.width, depth.height, 0.5f), &depth);
  }
  bool outputFolderIsEmpty() const { return !fs::exists(options_.outputFolder) || fs::is_empty(options_.outputFolder); }

  fs::path folder_;
  ImageRGBA8 color_;
  DepthImage depth_;
  ConvertJobOptions options_;
};

std::string fileBytes(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

int largestDifference(const ImageRGBA8& a, const ImageRGBA8& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
}

// The eyes the C++ reference makes from the test's own linear depth, for loaders that must reproduce it.
void expectEyesOfLinearDepth(const ConvertJobOptions& options, const ImageRGBA8& color, const DepthImage& depth) {
  stereo::StereoPair expected =
      stereo::synthesizeStereoReference(color, depth, stereo::makeStereoConstants(options.stereo, 48, 20));
  // Tolerance 1 level: the GPU pass against its C++ reference, as in test_stereo_pass.cpp.
  EXPECT_LE(largestDifference(io::readPng(options.outputFolder / "left.png"), expected.left), 1);
  EXPECT_LE(largestDifference(io::readPng(options.outputFolder / "right.png"), expected.right), 1);
}

template <typename Exception = std::exception, typename Call>
std::string errorOf(Call call) {
  try {
    call();
  } catch (const Exception& error) {
    return error.what();
  }
  ADD_FAILURE() << "no exception";
  return {};
}

TEST_F(ConvertJob, EyesMatchTheCppStereoReference) {
  // Tolerance 1 level: the GPU pass against its C++ reference, as in test_stereo_pass.cpp.
  runConvertJob(context(), options_);
  stereo::StereoPair expected =
      stereo::synthesizeStereoReference(color_, depth_, stereo::makeStereoConstants(options_.stereo, 48, 20));
  EXPECT_LE(largestDifference(io::readPng(options_.outputFolder / "left.png"), expected.left), 1);
  EXPECT_LE(largestDifference(io::readPng(options_.outputFolder / "right.png"), expected.right), 1);
  for (const char* name : {"anaglyph.png", "sbs.png", "tab.png", "report.json"})
    EXPECT_TRUE(fs::exists(options_.outputFolder / name)) << name;
}

TEST_F(ConvertJob, HardwareDepthGivesTheSameEyesAsItsLinearDepth) {
  // Device depth of a near 0.1 / far 100 projection, converted back: same eyes within 1 level.
  const float nearPlane = 0.1f, farPlane = 100.0f;
  DepthImage device(48, 20);
  for (std::size_t i = 0; i < device.pixels.size(); ++i) {
    const double d = depth_.pixels[i];
    device.pixels[i] = std::isinf(d) ? 1.0f : float(farPlane / (farPlane - nearPlane) - farPlane * nearPlane / ((farPlane - nearPlane) * d));
  }
  writeInputs(device);
  options_.depthKind = DepthKind::Hardware;
  options_.nearPlane = nearPlane;
  options_.farPlane = farPlane;
  runConvertJob(context(), options_);
  stereo::StereoPair expected =
      stereo::synthesizeStereoReference(color_, depth_, stereo::makeStereoConstants(options_.stereo, 48, 20));
  EXPECT_LE(largestDifference(io::readPng(options_.outputFolder / "left.png"), expected.left), 1);
}

TEST_F(ConvertJob, AReferenceViewIsMeasured) {
  options_.referenceLeft = folder_ / "color.png";  // the unshifted view as a stand-in second view
  ConvertReport report = runConvertJob(context(), options_);
  ASSERT_TRUE(report.left.has_value());
  EXPECT_FALSE(report.right.has_value());
  EXPECT_LT(report.left->psnrDb, stereo::kMaxPsnrDb);  // the eye was displaced, so it differs
}

TEST_F(ConvertJob, AMissingColorFileIsNamedAndNothingIsWritten) {
  options_.color = folder_ / "missing.png";
  try {
    runConvertJob(context(), options_);
    FAIL() << "no exception";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("missing.png"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, WritingOverItsOwnInputIsRefusedAndTheInputKept) {
  fs::copy_file(folder_ / "color.png", folder_ / "left.png");
  options_.color = folder_ / "left.png";
  options_.outputFolder = folder_;
  const std::string before = fileBytes(folder_ / "left.png");
  const std::string message = errorOf([&] { runConvertJob(context(), options_); });
  EXPECT_NE(message.find("would overwrite input"), std::string::npos) << message;
  EXPECT_NE(message.find("left.png"), std::string::npos) << message;
  EXPECT_EQ(fileBytes(folder_ / "left.png"), before);
  EXPECT_FALSE(fs::exists(folder_ / "right.png"));
}

TEST_F(ConvertJob, FolderModeRefusesAnOutputThatIsAnotherFramesInput) {
  // Frame "1" writes left_1.png, which is frame "left_1"'s color input.
  fs::create_directories(folder_ / "in");
  io::writePng(folder_ / "in" / "left_1.png", color_);
  io::writeExr(folder_ / "in" / "left_1.exr", ImageRGBA32F(48, 20, 0.5f), &depth_);
  io::writePng(folder_ / "in" / "1.png", color_);
  io::writeExr(folder_ / "in" / "1.exr", ImageRGBA32F(48, 20, 0.5f), &depth_);
  options_.outputFolder = folder_ / "in";
  const std::vector<ConvertFrame> frames = pairFrames(folder_ / "in", "*.png", "*.exr");
  ASSERT_EQ(frames.size(), 2u);
  const std::string message = errorOf([&] { runConvertFolder(context(), options_, frames, {}); });
  EXPECT_NE(message.find("left_1.png"), std::string::npos) << message;
  EXPECT_EQ(io::readPng(folder_ / "in" / "left_1.png").pixels, color_.pixels);
  EXPECT_FALSE(fs::exists(folder_ / "in" / "right_1.png"));
}

TEST_F(ConvertJob, NonFiniteColorIsSanitizedAndCounted) {
  // NaN or inf color is replaced by 0 and counted in report.json, never propagated into the eyes.
  writeInputs(depth_);
  ImageRGBA32F color(48, 20, 0.5f);
  color.at(3, 2)[0] = NAN;
  color.at(4, 2)[1] = INFINITY;
  io::writeExr(folder_ / "color.exr", color, nullptr);
  options_.color = folder_ / "color.exr";
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_EQ(report.sanitizedColorValues, 2u);
  EXPECT_EQ(toJson(report).at("sanitized").at("colorValues"), 2);
}

TEST_F(ConvertJob, UnknownDepthTakesTheBackgroundBesideItAndIsCounted) {
  // Column 6 (depth 2) lies between 1 m (column 5) and 2 m (column 7): NaN, zero and negative there must
  // become 2 m, the farther side, so the eyes equal those of the original depth.
  DepthImage holes = depth_;
  *holes.at(6, 3) = NAN;
  *holes.at(6, 4) = 0.0f;
  *holes.at(6, 5) = -1.0f;
  writeInputs(holes);
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_EQ(report.unknownDepthPixels, 3u);
  EXPECT_EQ(toJson(report).at("sanitized").at("unknownDepthPixels"), 3);
  expectEyesOfLinearDepth(options_, color_, depth_);
}

TEST_F(ConvertJob, ADepthFileWithoutAKnownPixelIsRejected) {
  writeInputs(DepthImage(48, 20, NAN));
  EXPECT_NE(errorOf([&] { runConvertJob(context(), options_); }).find("has no known pixel"), std::string::npos);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, MismatchedSizesAreRejectedWithBothSizes) {
  DepthImage small(30, 20, 2.0f);
  io::writeExr(folder_ / "depth.exr", ImageRGBA32F(30, 20, 0.5f), &small);
  try {
    runConvertJob(context(), options_);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("30x20"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("48x20"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, AnExrWithoutDepthIsRejected) {
  io::writeExr(folder_ / "depth.exr", ImageRGBA32F(48, 20, 0.5f), nullptr);
  EXPECT_NE(errorOf([&] { runConvertJob(context(), options_); }).find("no channel 'Z'"), std::string::npos);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, HardwareDepthWithoutNearAndFarIsRejected) {
  options_.depthKind = DepthKind::Hardware;
  EXPECT_THROW(runConvertJob(context(), options_), std::invalid_argument);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, PfmDepthGivesTheSameEyes) {
  io::PfmImage pfm{48, 20, 1, depth_.pixels};
  io::writePfm(folder_ / "depth.pfm", pfm, /*bigEndian=*/true);
  options_.depth = folder_ / "depth.pfm";
  runConvertJob(context(), options_);
  expectEyesOfLinearDepth(options_, color_, depth_);
}

TEST_F(ConvertJob, Scaled16BitPngDepthGivesTheSameEyes) {
  io::Gray16Image png(48, 20);
  for (std::size_t i = 0; i < png.pixels.size(); ++i)
    png.pixels[i] = std::isinf(depth_.pixels[i]) ? 65535 : std::uint16_t(depth_.pixels[i] * 1000.0f);  // mm steps
  io::writePngGray16(folder_ / "depth.png", png);
  options_.depth = folder_ / "depth.png";
  options_.depthScale = 0.001f;
  runConvertJob(context(), options_);
  expectEyesOfLinearDepth(options_, color_, depth_);
}

TEST_F(ConvertJob, DepthIsReadFromTheNamedExrChannel) {
  ImageRGBA32F frame(48, 20, 0.5f);
  for (std::size_t i = 0; i < depth_.pixels.size(); ++i) frame.pixels[i * 4] = depth_.pixels[i];  // R: exact in half
  io::writeExr(folder_ / "depth.exr", frame, nullptr);
  options_.depthChannel = "R";
  runConvertJob(context(), options_);
  expectEyesOfLinearDepth(options_, color_, depth_);
}

TEST_F(ConvertJob, AMissingExrChannelIsNamed) {
  options_.depthChannel = "depth";
  EXPECT_NE(errorOf([&] { runConvertJob(context(), options_); }).find("no channel 'depth'"), std::string::npos);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, DistanceAlongTheRayIsConvertedToPlanarDepth) {
  const float focal = 30.0f;
  DepthImage distance = depth_;
  for (std::uint32_t y = 0; y < 20; ++y)
    for (std::uint32_t x = 0; x < 48; ++x) {
      const float dx = (float(x) + 0.5f - 24.0f) / focal, dy = (float(y) + 0.5f - 10.0f) / focal;
      *distance.at(x, y) *= std::sqrt(1.0f + dx * dx + dy * dy);
    }
  writeInputs(distance);
  options_.depthKind = DepthKind::Distance;
  options_.focalLengthPx = focal;
  runConvertJob(context(), options_);
  expectEyesOfLinearDepth(options_, color_, depth_);
}

TEST_F(ConvertJob, DistanceDepthWithoutIntrinsicsIsRejected) {
  options_.depthKind = DepthKind::Distance;
  EXPECT_NE(errorOf([&] { runConvertJob(context(), options_); }).find("intrinsics"), std::string::npos);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, ADisparityMapGivesTheRightViewAtXMinusD) {
  // Uniform d = 4 px: the right view at x shows the input's x + 4; the left view is the input itself.
  io::writePfm(folder_ / "disparity.pfm", io::PfmImage{48, 20, 1, std::vector<float>(48 * 20, 4.0f)});
  options_.depth = folder_ / "disparity.pfm";
  options_.disparity = DisparityOutput::Right;
  options_.stereo.edgeCrop = 0.0f;
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_FLOAT_EQ(report.stereo.maxSeparation, 4.0f / 48.0f);
  EXPECT_EQ(io::readPng(options_.outputFolder / "left.png").pixels, color_.pixels);
  const ImageRGBA8 right = io::readPng(options_.outputFolder / "right.png");
  for (std::uint32_t y = 0; y < 20; ++y)
    for (std::uint32_t x = 0; x + 4 < 48; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(right.at(x, y)[c], color_.at(x + 4, y)[c]) << x << ", " << y;
}

TEST_F(ConvertJob, ADisparityMapGivesTheLeftViewAtXPlusD) {
  io::writePfm(folder_ / "disparity.pfm", io::PfmImage{48, 20, 1, std::vector<float>(48 * 20, 4.0f)});
  options_.depth = folder_ / "disparity.pfm";
  options_.disparity = DisparityOutput::Left;
  options_.stereo.edgeCrop = 0.0f;
  runConvertJob(context(), options_);
  EXPECT_EQ(io::readPng(options_.outputFolder / "right.png").pixels, color_.pixels);
  const ImageRGBA8 left = io::readPng(options_.outputFolder / "left.png");
  for (std::uint32_t y = 0; y < 20; ++y)
    for (std::uint32_t x = 4; x < 48; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(left.at(x, y)[c], color_.at(x - 4, y)[c]) << x << ", " << y;
}

// Disparity of a foreground block (columns >= 24, d = 8) over a background (d = 2): in the right view the block
// lands on columns 16..39 and covers the background's 16..21.
DepthImage stepDisparity() {
  DepthImage disparity(48, 20);
  for (std::uint32_t y = 0; y < 20; ++y)
    for (std::uint32_t x = 0; x < 48; ++x) *disparity.at(x, y) = x >= 24 ? 8.0f : 2.0f;
  return disparity;
}

TEST_F(ConvertJob, TheLargerDisparityIsNearerAndCoversTheSmaller) {
  io::writePfm(folder_ / "disparity.pfm", io::PfmImage{48, 20, 1, stepDisparity().pixels});
  options_.depth = folder_ / "disparity.pfm";
  options_.disparity = DisparityOutput::Right;
  options_.stereo.edgeCrop = 0.0f;
  options_.stereo.method = stereo::StereoMethod::Forward;
  runConvertJob(context(), options_);
  const ImageRGBA8 right = io::readPng(options_.outputFolder / "right.png");
  for (std::uint32_t y = 0; y < 20; ++y)
    for (std::uint32_t x = 16; x < 40; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(right.at(x, y)[c], color_.at(x + 8, y)[c]) << x << ", " << y;
}

TEST_F(ConvertJob, MethodAutoPicksForwardForFiles) {
  options_.automaticMethod = true;
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_EQ(report.stereo.method, stereo::StereoMethod::Forward);
  EXPECT_EQ(toJson(report).at("stereo").at("methodChosenBy"), "auto");
}

TEST_F(ConvertJob, NonFiniteDisparityIsUnknownAndTakesTheBackground) {
  // Foreground pixels (5, 2) and (30, 2) unknown: (30, 2) sits inside the block, (5, 2) in the background.
  DepthImage disparity = stepDisparity();
  *disparity.at(30, 2) = INFINITY;
  *disparity.at(5, 2) = NAN;
  io::writePfm(folder_ / "disparity.pfm", io::PfmImage{48, 20, 1, disparity.pixels});
  options_.depth = folder_ / "disparity.pfm";
  options_.disparity = DisparityOutput::Right;
  options_.stereo.edgeCrop = 0.0f;
  options_.stereo.method = stereo::StereoMethod::Forward;
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_EQ(report.unknownDepthPixels, 2u);
  const ImageRGBA8 right = io::readPng(options_.outputFolder / "right.png");
  for (int c = 0; c < 3; ++c) EXPECT_EQ(right.at(3, 2)[c], color_.at(5, 2)[c]);  // background: d = 2
}

TEST_F(ConvertJob, ZeroIn16BitPngDisparityIsUnknown) {
  io::Gray16Image png(48, 20, 4 * 256);
  png.pixels[48 + 10] = 0;  // pixel (10, 1)
  io::writePngGray16(folder_ / "disparity.png", png);
  options_.depth = folder_ / "disparity.png";
  options_.depthScale = 1.0f / 256.0f;
  options_.disparity = DisparityOutput::Right;
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_EQ(report.unknownDepthPixels, 1u);
  EXPECT_FLOAT_EQ(report.stereo.maxSeparation, 4.0f / 48.0f);
}

TEST_F(ConvertJob, DisparityBeyondTheSeparationLimitIsRejected) {
  io::writePfm(folder_ / "disparity.pfm", io::PfmImage{48, 20, 1, std::vector<float>(48 * 20, 20.0f)});  // > 48/4
  options_.depth = folder_ / "disparity.pfm";
  options_.disparity = DisparityOutput::Right;
  EXPECT_THROW(runConvertJob(context(), options_), std::invalid_argument);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, ATruncatedPfmDepthIsRejected) {
  io::writePfm(folder_ / "depth.pfm", io::PfmImage{48, 20, 1, depth_.pixels});
  fs::resize_file(folder_ / "depth.pfm", fs::file_size(folder_ / "depth.pfm") - 8);
  options_.depth = folder_ / "depth.pfm";
  EXPECT_NE(errorOf([&] { runConvertJob(context(), options_); }).find("truncated"), std::string::npos);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, A3ChannelPfmIsNotTakenForDepth) {
  io::writePfm(folder_ / "depth.pfm", io::PfmImage{48, 20, 3, std::vector<float>(48 * 20 * 3, 2.0f)});
  options_.depth = folder_ / "depth.pfm";
  EXPECT_NE(errorOf([&] { runConvertJob(context(), options_); }).find("3-channel"), std::string::npos);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, FramesArePairedByTheirKey) {
  for (const char* key : {"0002", "0001"}) {
    io::writePng(folder_ / ("color_" + std::string(key) + ".png"), color_);
    io::writePfm(folder_ / ("depth_" + std::string(key) + ".pfm"), io::PfmImage{48, 20, 1, depth_.pixels});
  }
  const std::vector<ConvertFrame> frames = pairFrames(folder_, "color_*.png", "depth_*.pfm");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].key, "0001");
  EXPECT_EQ(frames[0].depth.filename(), "depth_0001.pfm");
  options_.outputFolder = folder_ / "sequence";
  std::size_t progressCalls = 0;
  runConvertFolder(context(), options_, frames, [&](std::size_t, std::size_t, const std::string&) { ++progressCalls; });
  EXPECT_EQ(progressCalls, 2u);
  for (const char* name : {"left_0001.png", "right_0002.png", "sbs_0002.png", "report.json"})
    EXPECT_TRUE(fs::exists(options_.outputFolder / name)) << name;
}

TEST_F(ConvertJob, AColorFrameWithoutItsDepthIsNamed) {
  io::writePng(folder_ / "color_0007.png", color_);
  EXPECT_NE(errorOf<std::invalid_argument>([&] { pairFrames(folder_, "color_*.png", "depth_*.pfm"); }).find("depth_0007.pfm"),
            std::string::npos);
}

TEST_F(ConvertJob, APatternNeedsExactlyOneStar) {
  EXPECT_THROW(pairFrames(folder_, "color.png", "depth_*.pfm"), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::app
