// The cover sequence with the comfort controls running: the player walks up to a wall and back.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "s3d/app/sequence_job.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {

namespace fs = std::filesystem;

// Rendered once per test binary at 160x90 (48 frames x 4 renders), without frame images.
const SequenceReport& coverSequence(vk::Context& context) {
  static const SequenceReport report = [&] {
    SequenceJobOptions options;
    options.width = 160;
    options.height = 90;
    options.writeFrames = false;
    options.outputFolder = fs::temp_directory_path() / ("s3d_sequence_" + std::to_string(::getpid()));
    SequenceReport result = runSequenceJob(context, options);
    std::error_code ignored;
    fs::remove_all(options.outputFolder, ignored);
    return result;
  }();
  return report;
}

class CoverSequence : public test::VulkanTest {};

TEST_F(CoverSequence, PullsTheZeroParallaxPlaneInAtTheWall) {
  const SequenceReport& report = coverSequence(context());
  ASSERT_EQ(report.frames.size(), 48u);
  float smallest = 1e9f;
  for (const SequenceFrame& frame : report.frames) smallest = std::min(smallest, frame.zeroParallaxDistance);
  EXPECT_LT(smallest, 0.5f);  // at 0.6 m from the wall the target is 0.3 m
}

TEST_F(CoverSequence, ZeroParallaxChangesByNoMoreThanTheBoundPerFrame) {
  const SequenceReport& report = coverSequence(context());
  const float bound = comfort::ZeroParallaxControlSettings{}.maxChangePerSecond / SequenceJobOptions{}.framesPerSecond;
  for (std::size_t i = 1; i < report.frames.size(); ++i)
    EXPECT_LE(std::abs(report.frames[i].zeroParallaxDistance - report.frames[i - 1].zeroParallaxDistance), bound + 1e-6f)
        << "frame " << i;
}

TEST_F(CoverSequence, ReturnsToTheRestValueWhenThePlayerStepsBack) {
  // The path ends 4 m from the wall, beyond the 2.25 m release distance; 1 cm: the filter's tail.
  const SequenceReport& report = coverSequence(context());
  EXPECT_NEAR(report.frames.back().zeroParallaxDistance, 1.0f, 0.01f);
}

TEST_F(CoverSequence, ThePushedWeaponNeverLandsBehindTheWall) {
  const SequenceReport& report = coverSequence(context());
  std::uint64_t weaponPixels = 0;
  for (const SequenceFrame& frame : report.frames) {
    EXPECT_EQ(frame.weaponConflictPixels, 0u) << "frame " << frame.index;
    weaponPixels += frame.weaponPixels;
  }
  EXPECT_GT(weaponPixels, 0u);  // the check saw the weapon at all
}

}  // namespace
}  // namespace s3d::app
