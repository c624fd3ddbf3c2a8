// The cover sequence with the comfort controls running: the player walks up to a wall and back.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "s3d/frame/scene_world.h"
#include "s3d/app/sequence_job.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
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

TEST_F(CoverSequence, ReportsTheFlickerOfEveryFrameAfterTheFirst) {
  // The camera moves in every frame and the halo changes with it: some flicker, none on the first frame.
  const SequenceReport& report = coverSequence(context());
  EXPECT_FALSE(report.frames.front().flicker.has_value());
  for (std::size_t i = 1; i < report.frames.size(); ++i) {
    ASSERT_TRUE(report.frames[i].flicker.has_value()) << "frame " << i;
    for (const stereo::FlickerStats& eye : *report.frames[i].flicker) {
      EXPECT_GT(eye.all.pixelCount, 0u);
      EXPECT_GE(eye.all.meanLevels, 0.0);
    }
  }
  const std::array<stereo::FlickerStats, 2> mean = meanFlicker(report);
  EXPECT_GT(mean[0].all.meanLevels, 0.0);
  EXPECT_GT(mean[0].halo.meanLevels, mean[0].all.meanLevels);  // it concentrates where the method errs
  EXPECT_EQ(toJson(report).at("frames").at(0).at("flicker"), nullptr);
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

TEST_F(CoverSequence, TheCrosshairIsNeverBehindTheSurfaceItAimsAt) {
  // Checked with rays of its own along each frame's aim, not with what the job reports it saw.
  const SequenceReport& report = coverSequence(context());
  const renderer::Scene scene = renderer::makeBuiltInScene("cover");
  const comfort::WorldQueries world(frame::worldMeshes(scene));
  std::size_t framesWithAWall = 0;
  for (const SequenceFrame& frame : report.frames) {
    const renderer::Camera camera = renderer::cameraForFrame(scene, frame.index);
    const glm::mat4 worldFromView = glm::inverse(renderer::cameraView(camera));
    const std::optional<float> hit = world.castRay(glm::vec3(worldFromView[3]), -glm::vec3(worldFromView[2]), 1000.0f);
    if (!hit) continue;
    ++framesWithAWall;
    EXPECT_LE(frame.crosshairDepth, *hit) << "frame " << frame.index;
  }
  EXPECT_GT(framesWithAWall, 0u);  // the path does aim at the wall
}

TEST_F(CoverSequence, NothingHasNegativeParallaxWhenItIsDisallowed) {
  const SequenceReport& report = coverSequence(context());
  for (const SequenceFrame& frame : report.frames) {
    EXPECT_GE(frame.comfort.parallax.minParallaxPx, 0.0) << "frame " << frame.index;
    EXPECT_EQ(frame.comfort.parallax.shareNegative, 0.0) << "frame " << frame.index;
    EXPECT_EQ(frame.comfort.windowViolationPixels, 0u) << "frame " << frame.index;
    EXPECT_GE(frame.crosshairDepth, frame.zeroParallaxDistance) << "frame " << frame.index;
  }
}

TEST_F(CoverSequence, TheComfortNumbersOfTheFirstFrameMatchAHandComputation) {
  // Frame 0 at rest: zero-parallax distance 1 m, weapon pushed by 1 m at scale 1, sky in view. At 160 px and
  // maxSeparation 0.02 the sky is 2 * 0.02 * 160 = 6.4 px apart, the weapon's nearest point (its nearest vertex,
  // 0.27 m, pushed to 1.27 m) 6.4 * (1 - 1 / 1.27) px. On the 55-inch TV (16:9, 1.2177 m wide at 2.5 m,
  // 63 mm eyes) a parallax P in metres is 2 atan(e / 2v) - 2 atan((e - P) / 2v) of disparity.
  const SequenceReport& report = coverSequence(context());
  const SequenceFrame& frame = report.frames.front();
  ASSERT_EQ(frame.zeroParallaxDistance, 1.0f);
  const float weaponNearest = renderer::firstPersonDepthRange(renderer::makeBuiltInScene("cover"))->x;
  const double skyPx = 2.0 * 0.02 * 160.0;
  const double weaponPx = skyPx * (1.0 - 1.0 / (1.0 + double(weaponNearest)));
  const double screenWidth = 55.0 * 0.0254 * 16.0 / std::sqrt(16.0 * 16.0 + 9.0 * 9.0);
  auto arcmin = [&](double px) {
    const double p = px / 160.0 * screenWidth, e = 0.063, v = 2.5;
    return (2.0 * std::atan(e / (2.0 * v)) - 2.0 * std::atan((e - p) / (2.0 * v))) * 60.0 * 180.0 / 3.14159265358979;
  };
  const comfort::ParallaxStatistics& p = frame.comfort.parallax;
  EXPECT_NEAR(p.maxParallaxPx, skyPx, 1e-5);  // float parallax: 1e-5 px
  // The nearest vertex is the barrel's tip; pixel centers sample it within a millimetre: 0.01 px.
  EXPECT_NEAR(p.minParallaxPx, weaponPx, 0.01);
  EXPECT_NEAR(p.maxParallaxPercent, 4.0, 1e-5);
  EXPECT_NEAR(p.minParallaxPercent, weaponPx / 160.0 * 100.0, 0.01);
  EXPECT_NEAR(p.maxDisparityArcmin, arcmin(skyPx), 1e-3);  // float screen width: 1e-3 arcmin
  EXPECT_NEAR(p.minDisparityArcmin, arcmin(weaponPx), 0.02);
}

TEST_F(CoverSequence, EveryFrameIsFullFrameWithAGuardBand) {
  // No edge crop given: the center view is rendered ceil(m W) + 1 columns wider a side (m = 0.02 at 160 px: 5).
  const SequenceReport& report = coverSequence(context());
  for (const SequenceFrame& frame : report.frames) {
    EXPECT_EQ(frame.cropColumns, 0u) << "frame " << frame.index;
    EXPECT_EQ(frame.guardBandColumns, 5u) << "frame " << frame.index;
  }
  EXPECT_EQ(toJson(report).at("frames").at(3).at("cropColumns"), 0);
}

// A static camera (every frame the path's first), 64x36, without frame images.
SequenceReport staticCamera(vk::Context& context, stereo::StereoMethod method, bool previousFrameFill,
                            stereo::DisparityMapping mapping = stereo::DisparityMapping::Linear) {
  SequenceJobOptions options;
  options.width = 64;
  options.height = 36;
  options.writeFrames = false;
  options.writeReport = false;
  options.holdFrame = 0;
  options.stereo.method = method;
  options.stereo.previousFrameFill = previousFrameFill;
  options.stereo.disparityMapping = mapping;
  return runSequenceJob(context, options);
}

TEST_F(CoverSequence, AStaticCameraDoesNotFlicker) {
  // Nothing moves and the controls are at rest in the first frame, so every frame repeats the first: the
  // flicker of the default method, of the forward method and of its previous-frame fill is 0 (1e-9 levels: the
  // static reprojection's weights are 1 within float rounding), and no pixel counts as newly visible.
  for (auto [method, fill] : {std::pair{stereo::StereoMethod::Search, false}, std::pair{stereo::StereoMethod::Forward, false},
                              std::pair{stereo::StereoMethod::Forward, true}}) {
    const SequenceReport report = staticCamera(context(), method, fill);
    for (std::size_t i = 1; i < report.frames.size(); ++i) {
      ASSERT_TRUE(report.frames[i].flicker.has_value());
      for (const stereo::FlickerStats& eye : *report.frames[i].flicker) {
        EXPECT_NEAR(eye.all.meanLevels, 0.0, 1e-9) << stereo::methodName(method) << fill << " frame " << i;
        EXPECT_EQ(eye.newlyVisiblePixels, 0u);
        EXPECT_EQ(eye.all.pixelCount, 64u * 36u);
      }
    }
  }
}

TEST_F(CoverSequence, AStaticCameraDoesNotFlickerWithTheNonlinearMappingEither) {
  // Every frame repeats the first, its curve included, so its per-layer reference too: each pixel moves from its
  // own layer's camera to the same layer's camera of the previous frame (temporal.h), the identity. A metric that
  // moved a pixel between the cameras of different layers would see it shift by their offset.
  const SequenceReport report =
      staticCamera(context(), stereo::StereoMethod::Search, false, stereo::DisparityMapping::Nonlinear);
  for (std::size_t i = 1; i < report.frames.size(); ++i) {
    EXPECT_GT(report.frames[i].disparityMap.referenceLayers, 1u) << "frame " << i;
    ASSERT_TRUE(report.frames[i].flicker.has_value());
    for (const stereo::FlickerStats& eye : *report.frames[i].flicker) {
      EXPECT_NEAR(eye.all.meanLevels, 0.0, 1e-9) << "frame " << i;
      EXPECT_EQ(eye.newlyVisiblePixels, 0u) << "frame " << i;
    }
  }
}

TEST_F(CoverSequence, ThePreviousFrameFillRefusesTheNonlinearMapping) {
  SequenceJobOptions options;
  options.stereo.method = stereo::StereoMethod::Forward;
  options.stereo.previousFrameFill = true;
  options.stereo.disparityMapping = stereo::DisparityMapping::Nonlinear;
  EXPECT_THROW((void)runSequenceJob(context(), options), std::invalid_argument);
}

// Tolerance: one 8-bit level everywhere, so PSNR >= 48.1 dB. At budget 1 the hybrid method renders every eye pixel
// from the eye cameras, the reference's cameras on the same wide frame, so each frame's eyes are the reference's
// with the guard band as with any method (the eye renderer follows the band's width).
TEST_F(CoverSequence, AHybridSequenceAtBudgetOneIsTheReference) {
  SequenceJobOptions options;
  options.width = 64;
  options.height = 36;
  options.writeFrames = false;
  options.writeReport = false;
  options.stereo.method = stereo::StereoMethod::Hybrid;
  options.stereo.hybridBudget = 1.0f;
  const SequenceReport report = runSequenceJob(context(), options);
  ASSERT_FALSE(report.frames.empty());
  for (const SequenceFrame& frame : report.frames) {
    EXPECT_GT(frame.guardBandColumns, 0u);
    EXPECT_GE(frame.psnrLeftDb, 48.1) << "frame " << frame.index;
    EXPECT_GE(frame.psnrRightDb, 48.1) << "frame " << frame.index;
    EXPECT_EQ(frame.stereoPassGpuMs.has_value(), context().timestampPeriodNs() > 0.0) << "frame " << frame.index;
  }
}

TEST_F(CoverSequence, ThePreviousFrameFillNeedsTheForwardMethod) {
  SequenceJobOptions options;
  options.stereo.previousFrameFill = true;  // with the default method (search)
  EXPECT_THROW((void)runSequenceJob(context(), options), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::app
