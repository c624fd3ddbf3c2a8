// The crosshair's entry in the render job's report.json.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "s3d/app/render_job.h"

namespace s3d::app {
namespace {

TEST(CrosshairReportJson, HasDepthHitWorldAndParallax) {
  RenderReport report;
  report.crosshair = {1.75f, true, 22.4f};
  const nlohmann::json json = toJson(report).at("crosshair");
  EXPECT_EQ(json.at("depth").get<double>(), 1.75);  // exact: tidy() writes the float's shortest decimal
  EXPECT_EQ(json.at("hitWorld").get<bool>(), true);
  EXPECT_EQ(json.at("parallaxPx").get<double>(), 22.4);
}

}  // namespace
}  // namespace s3d::app
