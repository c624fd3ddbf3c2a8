// The comfort report's viewing geometry: on-screen parallax to angular disparity, per display.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "s3d/comfort/display_profile.h"

namespace s3d::comfort {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(DisplayProfile, ZeroParallaxHasZeroDisparity) {
  EXPECT_DOUBLE_EQ(disparityArcminutes(builtInDisplayProfile("tv55"), 0.0), 0.0);
}

TEST(DisplayProfile, DisparityMatchesTheVergenceGeometryByHand) {
  // 1 cm uncrossed on a monitor 0.7 m away, 63 mm eyes: 2 atan(0.0315/0.7) - 2 atan(0.0265/0.7).
  // Tolerance 1e-5 arcmin: the profile holds its lengths as floats (about 7 significant digits).
  DisplayProfile monitor = builtInDisplayProfile("monitor27");
  double expected = (2.0 * std::atan(0.0315 / 0.7) - 2.0 * std::atan(0.0265 / 0.7)) * 180.0 * 60.0 / kPi;
  EXPECT_NEAR(disparityArcminutes(monitor, 0.01), expected, 1e-5);
  EXPECT_GT(disparityArcminutes(monitor, 0.01), 0.0);   // behind the screen: positive
  EXPECT_LT(disparityArcminutes(monitor, -0.01), 0.0);  // in front: negative
}

TEST(DisplayProfile, BuiltInScreensHaveTheirSizes) {
  // A 55-inch 16:9 panel is 1.218 m wide; the HMD's 90-degree view at 1.3 m spans 2.6 m. Tolerance 1 mm.
  EXPECT_NEAR(builtInDisplayProfile("tv55").screenWidthMeters, 1.2177, 1e-3);
  EXPECT_NEAR(builtInDisplayProfile("hmd").screenWidthMeters, 2.6, 1e-3);
  EXPECT_THROW(builtInDisplayProfile("cinema"), std::invalid_argument);
}

TEST(ParallaxStatistics, SkyAndTheScreenPlaneGiveTheHandValues) {
  // Half the pixels at the zero-parallax distance (0 px), half sky: 2 * 0.02 * 100 = 4 px, 4 % of the width.
  DepthImage depth(100, 2, 1.0f);
  for (std::uint32_t x = 0; x < 100; ++x) *depth.at(x, 1) = INFINITY;
  stereo::StereoParameters parameters{0.02f, 1.0f, -1.0f};
  DisplayProfile tv = builtInDisplayProfile("tv55");
  ParallaxStatistics stats = parallaxStatistics(depth, parameters, tv);
  EXPECT_DOUBLE_EQ(stats.minParallaxPx, 0.0);
  EXPECT_NEAR(stats.maxParallaxPx, 4.0, 1e-5);  // float parallax, 1e-5 px
  EXPECT_NEAR(stats.maxParallaxPercent, 4.0, 1e-5);
  EXPECT_NEAR(stats.maxDisparityArcmin, disparityArcminutes(tv, 0.04 * tv.screenWidthMeters), 1e-3);
  EXPECT_DOUBLE_EQ(stats.shareNegative, 0.0);
}

TEST(ParallaxStatistics, TheOneDegreeRuleCountsOnlyPixelsBeyondIt) {
  // On a 27-inch monitor at 0.7 m, 4 % of the width (24 mm) behind the screen is about 1.9 degrees: the
  // sky row breaks the rule, the screen-plane row does not.
  DepthImage depth(100, 2, 1.0f);
  for (std::uint32_t x = 0; x < 100; ++x) *depth.at(x, 1) = INFINITY;
  ParallaxStatistics stats = parallaxStatistics(depth, {0.02f, 1.0f, -1.0f}, builtInDisplayProfile("monitor27"));
  EXPECT_DOUBLE_EQ(stats.shareBeyondOneDegree, 0.5);
}

TEST(DisplayProfile, TheHeadMountedDisplayHasItsFocalDistanceAndFieldOfView) {
  const DisplayProfile hmd = builtInDisplayProfile("hmd");
  EXPECT_EQ(hmd.viewingDistanceMeters, 1.3f);  // the focal distance
  EXPECT_EQ(hmd.fieldOfViewDegrees, 90.0f);
  EXPECT_EQ(builtInDisplayProfile("tv55").fieldOfViewDegrees, 0.0f);  // a flat screen
}

TEST(DisplayProfile, LoadsFromAJsonFileWithTheDefaultInterocularDistance) {
  namespace fs = std::filesystem;
  const fs::path file = fs::temp_directory_path() / ("s3d_display_" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << R"({"name": "projector", "screenWidthMeters": 2.4, "viewingDistanceMeters": 3.5})";
  const DisplayProfile display = resolveDisplayProfile(file.string());
  fs::remove(file);
  EXPECT_EQ(display.name, "projector");
  EXPECT_EQ(display.screenWidthMeters, 2.4f);
  EXPECT_EQ(display.viewingDistanceMeters, 3.5f);
  EXPECT_EQ(display.interocularMeters, 0.063f);
}

TEST(DisplayProfile, AJsonProfileWithAnUnknownKeyOrABadValueIsRefused) {
  EXPECT_THROW(displayProfileFromJson(nlohmann::json::parse(
                   R"({"screenWidthMeters": 1, "viewingDistanceMeters": 2, "diagonalInches": 40})")),
               std::invalid_argument);
  EXPECT_THROW(displayProfileFromJson(nlohmann::json::parse(R"({"screenWidthMeters": -1, "viewingDistanceMeters": 2})")),
               std::invalid_argument);
  EXPECT_THROW(displayProfileFromJson(nlohmann::json::parse(R"({"focalDistanceMeters": 2, "fieldOfViewDegrees": 180})")),
               std::invalid_argument);  // tan(90 deg): no finite virtual screen
}

TEST(DisplayProfile, AHeadsetProfileCarriesItsEyeViews) {
  const DisplayProfile headset =
      loadDisplayProfile(std::string(S3D_TEST_DATA_DIR) + "/../../samples/views/headset-display.json");
  ASSERT_TRUE(headset.eyeViews.has_value());
  EXPECT_EQ(headset.eyeViews->eyes[0].width, 1832u);
  EXPECT_DOUBLE_EQ(headset.eyeViews->eyes[1].positionX, 0.0315);
  EXPECT_FLOAT_EQ(headset.viewingDistanceMeters, 1.3f);
  // Written and read back unchanged; a profile without views has none.
  const DisplayProfile again = displayProfileFromJson(toJson(headset));
  ASSERT_TRUE(again.eyeViews.has_value());
  EXPECT_EQ(toJson(*again.eyeViews), toJson(*headset.eyeViews));
  EXPECT_FALSE(builtInDisplayProfile("hmd").eyeViews.has_value());
}

TEST(DisplayProfile, BadEyeViewsAreRefusedNamingTheField) {
  nlohmann::json document = toJson(builtInDisplayProfile("hmd"));
  document["eyeViews"] = {{"views", {{"left", nlohmann::json::object()}}}};
  try {
    (void)displayProfileFromJson(document);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("display.eyeViews"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("views.left.position is missing"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace s3d::comfort
