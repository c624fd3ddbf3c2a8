// `s3d convert`: stereo from external color + depth files, and its refusal of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <unistd.h>

#include "s3d/app/convert_job.h"
#include "s3d/gpu/linear_depth.h"
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

int largestDifference(const ImageRGBA8& a, const ImageRGBA8& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
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

TEST_F(ConvertJob, NanDepthAndNonFiniteColorAreSanitizedAndCounted) {
  // Issue #4: NaN or inf input is replaced (depth by the zero-parallax plane, color by 0) and counted in
  // report.json, never propagated into the eyes.
  *depth_.at(7, 3) = NAN;
  *depth_.at(8, 3) = NAN;
  writeInputs(depth_);
  ImageRGBA32F color(48, 20, 0.5f);
  color.at(3, 2)[0] = NAN;
  color.at(4, 2)[1] = INFINITY;
  io::writeExr(folder_ / "color.exr", color, nullptr);
  options_.color = folder_ / "color.exr";
  const ConvertReport report = runConvertJob(context(), options_);
  EXPECT_EQ(report.sanitizedDepthPixels, 2u);
  EXPECT_EQ(report.sanitizedColorValues, 2u);
  const nlohmann::json json = toJson(report);
  EXPECT_EQ(json.at("sanitized").at("depthPixels"), 2);
  EXPECT_EQ(json.at("sanitized").at("colorValues"), 2);
}

TEST_F(ConvertJob, NegativeDepthIsRejected) {
  *depth_.at(0, 0) = -1.0f;
  writeInputs(depth_);
  EXPECT_THROW(runConvertJob(context(), options_), std::invalid_argument);
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
  EXPECT_THROW(runConvertJob(context(), options_), std::invalid_argument);
  EXPECT_TRUE(outputFolderIsEmpty());
}

TEST_F(ConvertJob, HardwareDepthWithoutNearAndFarIsRejected) {
  options_.depthKind = DepthKind::Hardware;
  EXPECT_THROW(runConvertJob(context(), options_), std::invalid_argument);
  EXPECT_TRUE(outputFolderIsEmpty());
}

}  // namespace
}  // namespace s3d::app
