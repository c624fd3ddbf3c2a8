// The render job's report carries the stereo core's warnings (a clamped zero-parallax distance, a capped guard
// band) in report.warnings and in report.json.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "s3d/app/render_job.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

class StereoNumericsRender : public test::VulkanTest {};

TEST_F(StereoNumericsRender, ARenderJobReportsTheClampedZeroParallaxDistanceInItsWarnings) {
  // The whole job at 32x16 (quick on lavapipe), writing no files: report and report.json carry the warning.
  app::RenderJobOptions options;
  options.width = 32;
  options.height = 16;
  options.outputs = {};
  options.stereo.zeroParallaxDistance = 5000.0f;  // the courtyard's far plane is 1000
  options.allowNegativeParallax = true;  // else the comfort rule lowers it further, to the nearest surface
  const app::RenderReport report = app::runRenderJob(context(), options);
  EXPECT_EQ(report.stereo.zeroParallaxDistance, 500.0f);
  // The clamp, then the guard band: 500 m over the 0.1 m near plane needs ~5000 widths, capped at half of one.
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[0].find("zeroParallaxDistance"), std::string::npos) << report.warnings[0];
  EXPECT_NE(report.warnings[1].find("guard band capped at 16 columns"), std::string::npos) << report.warnings[1];
  EXPECT_EQ(app::toJson(report).at("warnings").at(0), report.warnings[0]);
}

}  // namespace
}  // namespace s3d::stereo
