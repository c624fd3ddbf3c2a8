// `s3d render --views`: the eye synthesis through the view mapping, and a whole job on small views.
#include <gtest/gtest.h>

#include <cmath>

#include "s3d/app/views_job.h"
#include "s3d/stereo/eye_views_reference.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {

comfort::ViewConfiguration smallViews(bool headset) {
  comfort::ViewConfiguration views;
  if (headset) {  // asymmetric, mirrored (samples/views/headset-pair.json at 1/38 of its size)
    views.eyes[0] = {-0.0315, -0.7854, 0.6981, 0.7330, -0.8203, 48, 50};
    views.eyes[1] = {0.0315, -0.6981, 0.7854, 0.7330, -0.8203, 48, 50};
  } else {  // the TV pair of samples/views/tv-pair.json at 1/40 of its size
    views.eyes[0] = {-0.0325, -0.45047, 0.47717, 0.27564, -0.27564, 48, 27};
    views.eyes[1] = {0.0325, -0.47717, 0.45047, 0.27564, -0.27564, 48, 27};
  }
  return views;
}

TEST(ViewSynthesis, AnEyeAtTheCenterWithTheCentersFrustumIsTheCenterImage) {
  comfort::ViewConfiguration views;
  views.eyes[0] = {0.0, -0.5, 0.5, 0.4, -0.4, 10, 8};  // no offset: no displacement
  views.eyes[1] = {0.0, -0.5, 0.5, 0.4, -0.4, 10, 8};
  const comfort::CenterView center = comfort::centerViewFor(views, 1.0);
  ASSERT_EQ(center.width, 10u);
  ASSERT_EQ(center.height, 8u);
  ImageRGBA8 color(10, 8);
  for (std::size_t i = 0; i < color.pixels.size(); ++i) color.pixels[i] = std::uint8_t(i * 7);
  const DepthImage depth(10, 8, 0.5f);
  const ImageRGBA8 eye = synthesizeEyeForView(color, depth, views, center, 0);
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < 10; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(eye.at(x, y)[c], color.at(x, y)[c]) << x << "," << y;
}

class ViewsJob : public test::VulkanTest {};

TEST_F(ViewsJob, BothEyesOfATvAndAHeadsetPairAreCloseToTheirDirectRenders) {
  for (bool headset : {false, true}) {
    ViewsJobOptions options;
    options.views = smallViews(headset);
    options.writeImages = false;
    const ViewsReport report = runViewsJob(context(), options);
    EXPECT_GT(report.center.width, 48u);  // the union of both frusta plus the guard band
    for (const stereo::ErrorStats& error : report.error) {
      EXPECT_EQ(error.pixelCount, std::uint64_t(48) * options.views.eyes[0].height);  // the whole eye
      EXPECT_GT(error.psnrDb, 15.0) << (headset ? "headset" : "tv");
    }
  }
}

TEST_F(ViewsJob, ReportsEachEyesShareBeyondTheOneDegreeRuleAgainstTheFocalPlane) {
  // The headset pair on the hmd profile (focal plane 1.3 m): the default scene's sky verges 2.8 degrees from the
  // focal plane's, so each eye has pixels beyond the rule, and the report carries that share per eye.
  ViewsJobOptions options;
  options.views = smallViews(true);
  options.writeImages = false;
  const ViewsReport report = runViewsJob(context(), options);
  const nlohmann::json document = toJson(report);
  for (int e = 0; e < 2; ++e) {
    const comfort::EyeViewComfort& comfort = report.comfort[std::size_t(e)];
    EXPECT_GT(comfort.shareBeyondOneDegree, 0.0);
    EXPECT_LT(comfort.shareBeyondOneDegree, 1.0);
    const nlohmann::json& eye = document["comfort"][e == 0 ? "left" : "right"];
    EXPECT_DOUBLE_EQ(eye["shareBeyondOneDegree"].get<double>(), comfort.shareBeyondOneDegree);
    EXPECT_FALSE(eye.contains("shareOutsideComfortZone"));  // no zone of comfort in s3d
    EXPECT_GT(eye["maxConflictDiopters"].get<double>(), 0.0);
  }
}

}  // namespace
}  // namespace s3d::app
