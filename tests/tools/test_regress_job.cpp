// `s3d regress`: the suite file's validation (every error names its place), base64, and a run that passes
// against its own fresh baselines and fails once a stereo parameter changes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "s3d/app/regress_job.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

json validSuite() {
  return json::parse(R"({
    "tolerances": {"psnrDropDb": 0.25},
    "cases": [{"name": "court", "scene": "courtyard", "resolution": "32x18",
               "stereo": {"method": "search", "searchTaps": 4, "maxSeparation": 0.03},
               "minPsnrDb": {"all": 10}}]})");
}

std::string suiteError(const json& document) {
  try {
    parseRegressSuite(document, "suites", "suite.json");
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  ADD_FAILURE() << "no std::invalid_argument";
  return {};
}

// The suite's error message contains `fragment` (printed in full when it does not).
void expectSuiteError(const json& document, const std::string& fragment) {
  const std::string message = suiteError(document);
  EXPECT_NE(message.find(fragment), std::string::npos) << message;
}

TEST(RegressSuite, AValidSuiteKeepsItsValuesAndFillsDefaults) {
  const RegressSuite suite = parseRegressSuite(validSuite(), "suites", "suite.json");
  ASSERT_EQ(suite.cases.size(), 1u);
  const RegressCase& entry = suite.cases[0];
  EXPECT_EQ(suite.baselineFolder, fs::path("suites") / "baselines");
  EXPECT_EQ(entry.width, 32u);
  EXPECT_EQ(entry.height, 18u);
  EXPECT_EQ(entry.frames, std::vector<std::size_t>{0});
  EXPECT_EQ(entry.profile.stereo.method, stereo::StereoMethod::Search);
  EXPECT_EQ(entry.profile.stereo.searchTaps, 4);
  EXPECT_FLOAT_EQ(entry.profile.stereo.maxSeparation, 0.03f);
  EXPECT_DOUBLE_EQ(entry.tolerances.psnrDropDb, 0.25);                        // from the suite
  EXPECT_DOUBLE_EQ(entry.tolerances.baselineImageMinPsnrDb, RegressTolerances{}.baselineImageMinPsnrDb);  // default
  EXPECT_DOUBLE_EQ(entry.minPsnrDb.at("all"), 10.0);
}

TEST(RegressSuite, AnUnknownKeyIsNamedWithItsPlaceAndTheKnownKeys) {
  json suite = validSuite();
  suite["cases"][0]["stereo"]["maxSeperation"] = 0.02;
  const std::string message = suiteError(suite);
  EXPECT_NE(message.find("suite.json: cases[0].stereo: unknown key 'maxSeperation'"), std::string::npos) << message;
  EXPECT_NE(message.find("maxSeparation"), std::string::npos) << message;
}

TEST(RegressSuite, AMissingFieldIsNamed) {
  json suite = validSuite();
  suite["cases"][0].erase("resolution");
  expectSuiteError(suite, "cases[0]: missing 'resolution'");
}

TEST(RegressSuite, AWrongTypeIsNamed) {
  json suite = validSuite();
  suite["cases"][0]["frames"] = {0, "one"};
  expectSuiteError(suite, "cases[0].frames[1]: expected a whole number");
}

TEST(RegressSuite, AnUnknownSceneIsNamed) {
  json suite = validSuite();
  suite["cases"][0]["scene"] = "moon";
  expectSuiteError(suite, "unknown scene 'moon'");
}

TEST(RegressSuite, AFrameBeyondTheCameraPathIsRejected) {
  json suite = validSuite();
  suite["cases"][0]["frames"] = {100000};
  expectSuiteError(suite, "cases[0]: ");
}

TEST(RegressSuite, ABadResolutionIsRejected) {
  json suite = validSuite();
  suite["cases"][0]["resolution"] = "32by18";
  expectSuiteError(suite, "cases[0].resolution: expected WxH");
}

TEST(RegressSuite, InvalidStereoParametersAreRejected) {
  json suite = validSuite();
  suite["cases"][0]["stereo"]["maxSeparation"] = -1;
  expectSuiteError(suite, "cases[0].stereo: ");
}

TEST(RegressSuite, AnUnknownRegionIsNamed) {
  json suite = validSuite();
  suite["cases"][0]["minPsnrDb"]["edges"] = 20;
  expectSuiteError(suite, "cases[0].minPsnrDb: unknown key 'edges'");
}

TEST(RegressSuite, DuplicateCaseNamesAreRejected) {
  json suite = validSuite();
  suite["cases"].push_back(suite["cases"][0]);
  expectSuiteError(suite, "cases[1].name: duplicate case name 'court'");
}

TEST(RegressSuite, AnEmptyCaseListIsRejected) {
  expectSuiteError(json{{"cases", json::array()}}, "cases: expected a non-empty array");
}

TEST(RegressSuite, AProfileSetsTheParametersAndStereoKeysOverrideIt) {
  json suite = validSuite();
  suite["cases"][0]["profile"] = json::parse(R"({"stereo": {"maxSeparation": 0.05, "zeroParallaxDistance": 3},
                                                  "display": "monitor27"})");
  const RegressCase entry = parseRegressSuite(suite, "suites", "suite.json").cases[0];
  EXPECT_FLOAT_EQ(entry.profile.stereo.zeroParallaxDistance, 3.0f);  // from the profile
  EXPECT_FLOAT_EQ(entry.profile.stereo.maxSeparation, 0.03f);        // the case's "stereo" wins
  EXPECT_EQ(entry.profile.display.name, "monitor27");
}

TEST(RegressSuite, AProfileFileIsReadRelativeToTheSuite) {
  const fs::path folder = fs::temp_directory_path() / ("s3d_regress_profile_" + std::to_string(::getpid()));
  fs::create_directories(folder / "profiles");
  std::ofstream(folder / "profiles" / "wide.json") << R"({"stereo": {"zeroParallaxDistance": 4}})";
  json suite = validSuite();
  suite["cases"][0]["profile"] = "profiles/wide.json";
  const RegressCase entry = parseRegressSuite(suite, folder, "suite.json").cases[0];
  EXPECT_FLOAT_EQ(entry.profile.stereo.zeroParallaxDistance, 4.0f);
  suite["cases"][0]["profile"] = "profiles/missing.json";
  expectSuiteError(suite, "cases[0].profile: ");
  fs::remove_all(folder);
}

TEST(RegressSuite, ANumberBeyondDoubleRangeInTheFileIsAnErrorNamingIt) {
  // nlohmann::json reports this as out_of_range, not parse_error: it must still be the suite's clear error.
  const fs::path file = fs::temp_directory_path() / ("s3d_regress_overflow_" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << R"({"cases": [{"name": "a", "scene": "courtyard", "frames": [1e400]}]})";
  try {
    loadRegressSuite(file);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(file.string()), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("not valid JSON"), std::string::npos) << error.what();
  }
  fs::remove(file);
}

TEST(RegressSuite, AnUnknownProfileKeyIsNamed) {
  json suite = validSuite();
  suite["cases"][0]["profile"] = json::parse(R"({"stereo": {"separation": 0.05}})");
  expectSuiteError(suite, "cases[0].profile: ");
  expectSuiteError(suite, "separation");
}

TEST(RegressSuite, Base64MatchesRfc4648TestVectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

class RegressRunTest : public test::VulkanTest {
 protected:
  void SetUp() override {
    test::VulkanTest::SetUp();
    folder_ = fs::temp_directory_path() / ("s3d_regress_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
    test::VulkanTest::TearDown();
  }
  fs::path folder_;
};

TEST_F(RegressRunTest, FreshBaselinesPassAndAChangedSeparationFails) {
  RegressSuite suite = parseRegressSuite(validSuite(), folder_, "suite.json");
  RegressOptions options;
  options.outputFolder = folder_ / "report";
  const RegressResult missing = runRegressSuite(context(), suite, options);
  EXPECT_EQ(missing.failedRuns, 1u);  // no baseline yet
  options.updateBaselines = true;
  runRegressSuite(context(), suite, options);
  EXPECT_TRUE(fs::exists(folder_ / "baselines" / "court_f0.png"));
  options.updateBaselines = false;
  EXPECT_EQ(runRegressSuite(context(), suite, options).failedRuns, 0u);
  suite.cases[0].profile.stereo.maxSeparation = 0.04f;
  const RegressResult changed = runRegressSuite(context(), suite, options);
  EXPECT_EQ(changed.failedRuns, 1u);
  std::ifstream html(changed.htmlReport);
  const std::string text((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("data:image/png;base64,"), std::string::npos);  // self-contained
  EXPECT_NE(text.find("FAIL"), std::string::npos);
}

}  // namespace
}  // namespace s3d::app
