// Comfort profiles: every stereo and comfort parameter in one JSON file, read strictly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>

#include "s3d/comfort/comfort_profile.h"

namespace s3d::comfort {
namespace {
namespace fs = std::filesystem;

class ComfortProfileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("s3d_comfort_profile_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name, std::ios::binary) << text;
    return folder_ / name;
  }
  fs::path folder_;
};

// A profile with every field away from its default, so a field the round trip drops cannot go unnoticed.
ComfortProfile unusualProfile() {
  ComfortProfile p;
  p.stereo.maxSeparation = 0.031f;
  p.stereo.zeroParallaxDistance = 2.75f;
  p.stereo.edgeCrop = 0.01f;
  p.stereo.method = stereo::StereoMethod::Search;
  p.stereo.searchTaps = 5;
  p.stereo.iterations = 9;
  p.stereo.hybridBudget = 0.35f;
  p.stereo.hybridCell = 2;
  p.stereo.hybridScoreFloor = 0.4f;
  p.stereo.weaponDepthOffset = 0.4f;
  p.stereo.weaponDepthScale = 1.7f;
  p.stereo.disparityMapping = stereo::DisparityMapping::Nonlinear;
  p.zeroParallax.engageDistance = 3.5f;
  p.zeroParallax.releaseMargin = 0.6f;
  p.zeroParallax.minimumDistance = 0.3f;
  p.zeroParallax.responseSeconds = 0.4f;
  p.zeroParallax.maxChangePerSecond = 1.3f;
  p.zeroParallax.ringRays = 6;
  p.zeroParallax.ringAngleRadians = 0.15f;
  p.crosshair.distance = 6.5f;
  p.crosshair.margin = 0.1f;
  p.crosshair.responseSeconds = 0.2f;
  p.display = DisplayProfile{"wall", 3.1f, 4.2f, 0.061f};
  p.allowNegativeParallax = true;
  return p;
}

void expectSameProfile(const ComfortProfile& a, const ComfortProfile& b) {
  // Exact: JSON numbers are printed with enough digits to give the same float back.
  EXPECT_EQ(a.stereo.maxSeparation, b.stereo.maxSeparation);
  EXPECT_EQ(a.stereo.zeroParallaxDistance, b.stereo.zeroParallaxDistance);
  EXPECT_EQ(a.stereo.edgeCrop, b.stereo.edgeCrop);
  EXPECT_EQ(a.stereo.method, b.stereo.method);
  EXPECT_EQ(a.stereo.searchTaps, b.stereo.searchTaps);
  EXPECT_EQ(a.stereo.iterations, b.stereo.iterations);
  EXPECT_EQ(a.stereo.hybridBudget, b.stereo.hybridBudget);
  EXPECT_EQ(a.stereo.hybridCell, b.stereo.hybridCell);
  EXPECT_EQ(a.stereo.hybridScoreFloor, b.stereo.hybridScoreFloor);
  EXPECT_EQ(a.stereo.weaponDepthOffset, b.stereo.weaponDepthOffset);
  EXPECT_EQ(a.stereo.weaponDepthScale, b.stereo.weaponDepthScale);
  EXPECT_EQ(a.stereo.disparityMapping, b.stereo.disparityMapping);
  EXPECT_EQ(a.zeroParallax.engageDistance, b.zeroParallax.engageDistance);
  EXPECT_EQ(a.zeroParallax.releaseMargin, b.zeroParallax.releaseMargin);
  EXPECT_EQ(a.zeroParallax.minimumDistance, b.zeroParallax.minimumDistance);
  EXPECT_EQ(a.zeroParallax.responseSeconds, b.zeroParallax.responseSeconds);
  EXPECT_EQ(a.zeroParallax.maxChangePerSecond, b.zeroParallax.maxChangePerSecond);
  EXPECT_EQ(a.zeroParallax.ringRays, b.zeroParallax.ringRays);
  EXPECT_EQ(a.zeroParallax.ringAngleRadians, b.zeroParallax.ringAngleRadians);
  EXPECT_EQ(a.crosshair.distance, b.crosshair.distance);
  EXPECT_EQ(a.crosshair.margin, b.crosshair.margin);
  EXPECT_EQ(a.crosshair.responseSeconds, b.crosshair.responseSeconds);
  EXPECT_EQ(a.display.name, b.display.name);
  EXPECT_EQ(a.display.screenWidthMeters, b.display.screenWidthMeters);
  EXPECT_EQ(a.display.viewingDistanceMeters, b.display.viewingDistanceMeters);
  EXPECT_EQ(a.display.interocularMeters, b.display.interocularMeters);
  EXPECT_EQ(a.display.fieldOfViewDegrees, b.display.fieldOfViewDegrees);
  EXPECT_EQ(a.allowNegativeParallax, b.allowNegativeParallax);
}

std::string messageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "(no exception)";
}

TEST_F(ComfortProfileFiles, SaveThenLoadGivesEveryFieldBack) {
  const ComfortProfile saved = unusualProfile();
  saveComfortProfile(folder_ / "profile.json", saved);
  expectSameProfile(loadComfortProfile(folder_ / "profile.json"), saved);
  EXPECT_FALSE(fs::exists(folder_ / "profile.json.tmp"));  // written through a temporary renamed into place
}

TEST(ComfortProfile, DefaultsRoundTripWithTheAutomaticCropAndTheScenesCrosshairDistance) {
  const ComfortProfile defaults;
  const nlohmann::json document = toJson(defaults);
  EXPECT_TRUE(document["stereo"]["edgeCrop"].is_null());
  EXPECT_TRUE(document["crosshair"]["distance"].is_null());
  EXPECT_EQ(document["display"], "tv55");  // a built-in display is saved by its name
  expectSameProfile(comfortProfileFromJson(document), defaults);
}

TEST(ComfortProfile, KeysLeftOutKeepTheirDefaults) {
  const ComfortProfile profile = comfortProfileFromJson(nlohmann::json::parse(R"({"stereo": {"maxSeparation": 0.03}})"));
  EXPECT_EQ(profile.stereo.maxSeparation, 0.03f);
  ComfortProfile expected;
  expected.stereo.maxSeparation = 0.03f;
  expectSameProfile(profile, expected);
}

TEST(ComfortProfile, AnUnknownKeyIsNamedWithItsPath) {
  const std::string message = messageOf(
      [] { comfortProfileFromJson(nlohmann::json::parse(R"({"stereo": {"maxSeperation": 0.03}})")); });
  EXPECT_NE(message.find("unknown key 'stereo.maxSeperation'"), std::string::npos) << message;
  EXPECT_NE(message.find("maxSeparation"), std::string::npos) << message;  // the known keys are listed
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"colour": 1})")), std::invalid_argument);
}

TEST(ComfortProfile, AnOutOfRangeValueIsNamedWithItsRange) {
  const std::string message = messageOf(
      [] { comfortProfileFromJson(nlohmann::json::parse(R"({"stereo": {"maxSeparation": 0.5}})")); });
  EXPECT_NE(message.find("'stereo.maxSeparation' = 0.5 is outside [0, 0.25]"), std::string::npos) << message;
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"zeroParallaxControl": {"ringRays": 65}})")),
               std::invalid_argument);
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"stereo": {"method": "magic"}})")),
               std::invalid_argument);
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"stereo": {"disparityMapping": "log"}})")),
               std::invalid_argument);
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"allowNegativeParallax": 1})")), std::invalid_argument);
}

TEST_F(ComfortProfileFiles, ErrorsInAFileNameTheFile) {
  const fs::path file = write("bad.json", R"({"weapon": {"depthScale": 0}})");
  const std::string message = messageOf([&] { loadComfortProfile(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("weapon.depthScale"), std::string::npos) << message;
}

TEST_F(ComfortProfileFiles, ACorruptFileIsAnErrorNamingTheFile) {
  const fs::path file = write("corrupt.json", "{\"stereo\": {\"maxSeparation\": 0.0");
  const std::string message = messageOf([&] { loadComfortProfile(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not valid JSON"), std::string::npos) << message;
  EXPECT_THROW(loadComfortProfile(folder_ / "missing.json"), std::runtime_error);
}

TEST_F(ComfortProfileFiles, ANumberBeyondDoubleRangeIsAnErrorNamingTheFile) {
  // nlohmann::json reports this as out_of_range, not parse_error (found by tests/fuzz/fuzz_comfort_profile.cpp).
  const fs::path file = write("overflow.json", "{\"stereo\": {\"maxSeparation\": 1e400}}");
  const std::string message = messageOf([&] { loadComfortProfile(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not valid JSON"), std::string::npos) << message;
}

TEST_F(ComfortProfileFiles, AnInvalidProfileIsNotSaved) {
  ComfortProfile profile;
  profile.stereo.maxSeparation = 0.9f;
  EXPECT_THROW(saveComfortProfile(folder_ / "profile.json", profile), std::invalid_argument);
  EXPECT_FALSE(fs::exists(folder_ / "profile.json"));
}

TEST_F(ComfortProfileFiles, SavingNeverWritesThroughALinkPlantedBesideOrAtTheFile) {
  // --save-profile may name a file in a shared folder: a link at the old predictable temporary name
  // (profile.json.tmp) or at the name itself must leave its target untouched.
  const fs::path victim = folder_ / "victim.txt";
  std::ofstream(victim) << "precious";
  fs::create_symlink(victim, folder_ / "profile.json.tmp");
  fs::create_symlink(victim, folder_ / "profile.json");
  saveComfortProfile(folder_ / "profile.json", ComfortProfile{});
  std::ifstream in(victim);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), "precious");
  EXPECT_FALSE(fs::is_symlink(folder_ / "profile.json"));
  EXPECT_EQ(loadComfortProfile(folder_ / "profile.json").stereo.maxSeparation, ComfortProfile{}.stereo.maxSeparation);
}

TEST(ComfortProfile, ADisplayObjectDescribesAScreenOrAHeadMountedDisplay) {
  const ComfortProfile screen = comfortProfileFromJson(nlohmann::json::parse(
      R"({"display": {"name": "desk", "screenWidthMeters": 0.6, "viewingDistanceMeters": 0.8}})"));
  EXPECT_EQ(screen.display.name, "desk");
  EXPECT_EQ(screen.display.interocularMeters, 0.063f);  // the default interocular distance
  const ComfortProfile hmd = comfortProfileFromJson(
      nlohmann::json::parse(R"({"display": {"focalDistanceMeters": 2.0, "fieldOfViewDegrees": 90}})"));
  EXPECT_NEAR(hmd.display.screenWidthMeters, 4.0f, 1e-5f);  // 2 f tan(45 deg); float rounding
  EXPECT_EQ(hmd.display.viewingDistanceMeters, 2.0f);
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"display": {"screenWidthMeters": 0.6}})")),
               std::invalid_argument);  // a screen needs its viewing distance
  EXPECT_THROW(comfortProfileFromJson(nlohmann::json::parse(R"({"display": "cinema"})")), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::comfort
