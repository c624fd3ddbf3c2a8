// Image statistics of every built-in scene (requirement: "checked against stored statistics (mean, histogram) with
// tolerances, not against exact bytes"): the center view and the synthesized left eye of frame 0 at 96x54,
// compared with tests/data/scene_statistics.json.
//
// Regenerate the stored statistics after a deliberate change of the images (lighting, materials, scenes), in
// one process so the file is rewritten scene after scene:
//   S3D_UPDATE_SCENE_STATISTICS=1 build/tests/s3d_tests_frame --gtest_filter='BuiltInScenes/SceneStatistics.*'
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/synthesis.h"
#include "vulkan_test.h"

namespace s3d {
namespace {
namespace fs = std::filesystem;

constexpr std::uint32_t kWidth = 96, kHeight = 54;
constexpr std::size_t kBins = 8;  // luma histogram bins of 32 levels each
const fs::path kStoredStatistics = fs::path(S3D_TEST_DATA_DIR) / "scene_statistics.json";
constexpr const char* kUpdateVariable = "S3D_UPDATE_SCENE_STATISTICS";

// Tolerances. Means: 2 of 255 levels. A different Vulkan implementation rounds, filters and evaluates pow/exp
// slightly differently (a level here and there, the mean moves by well under one); a lighting change worth
// seeing moves it by more. Histogram: 2 % of the pixels may change bin (edge pixels, values on a bin border).
constexpr double kMeanTolerance = 2.0;
constexpr double kHistogramTolerance = 0.02;

struct ImageStatistics {
  std::array<double, 3> meanRgb{};
  double meanLuma = 0.0;                    // Rec. 709 weights on the sRGB-encoded 8-bit values
  std::array<double, kBins> lumaHistogram{};  // share of the pixels per 32-level bin
};

ImageStatistics statisticsOf(const ImageRGBA8& image) {
  ImageStatistics stats;
  const double count = double(image.width) * double(image.height);
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      const double luma = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      for (int c = 0; c < 3; ++c) stats.meanRgb[std::size_t(c)] += p[c] / count;
      stats.meanLuma += luma / count;
      stats.lumaHistogram[std::min(kBins - 1, std::size_t(luma / (256.0 / kBins)))] += 1.0 / count;
    }
  return stats;
}

double rounded(double value) { return std::round(value * 1e4) / 1e4; }

nlohmann::json toJson(const ImageStatistics& stats) {
  nlohmann::json histogram = nlohmann::json::array();
  for (double share : stats.lumaHistogram) histogram.push_back(rounded(share));
  return {{"meanRgb", {rounded(stats.meanRgb[0]), rounded(stats.meanRgb[1]), rounded(stats.meanRgb[2])}},
          {"meanLuma", rounded(stats.meanLuma)},
          {"lumaHistogram", histogram}};
}

void expectMatches(const ImageStatistics& measured, const nlohmann::json& stored, const std::string& view) {
  for (std::size_t c = 0; c < 3; ++c)
    EXPECT_NEAR(measured.meanRgb[c], stored.at("meanRgb").at(c).get<double>(), kMeanTolerance)
        << view << " mean of channel " << "RGB"[c];
  EXPECT_NEAR(measured.meanLuma, stored.at("meanLuma").get<double>(), kMeanTolerance) << view << " mean luma";
  for (std::size_t bin = 0; bin < kBins; ++bin)
    EXPECT_NEAR(measured.lumaHistogram[bin], stored.at("lumaHistogram").at(bin).get<double>(), kHistogramTolerance)
        << view << " luma histogram bin " << bin << " (levels " << bin * 32 << ".." << bin * 32 + 31 << ")";
}

// One line per view, so a regeneration reads as a short diff.
std::string formatted(const nlohmann::json& stored) {
  std::string text = "{\n \"about\": " + stored["about"].dump() + ",\n \"scenes\": {";
  bool firstScene = true;
  for (const auto& [scene, views] : stored["scenes"].items()) {
    text += std::string(firstScene ? "" : ",") + "\n  " + nlohmann::json(scene).dump() + ": {";
    bool firstView = true;
    for (const auto& [view, statistics] : views.items()) {
      text += std::string(firstView ? "" : ",") + "\n   " + nlohmann::json(view).dump() + ": " + statistics.dump();
      firstView = false;
    }
    text += "\n  }";
    firstScene = false;
  }
  return text + "\n }\n}\n";
}

nlohmann::json readStored() {
  std::ifstream in(kStoredStatistics);
  if (!in) return nlohmann::json::object();
  return nlohmann::json::parse(in);
}

class SceneStatistics : public test::VulkanTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(SceneStatistics, CenterViewAndLeftEyeMatchTheStoredStatistics) {
  const std::string name = GetParam();
  renderer::Scene scene = renderer::makeBuiltInScene(name);
  scene.camera = renderer::cameraForFrame(scene, 0);
  renderer::DeferredRenderer deferred(context(), kWidth, kHeight);
  deferred.setScene(scene);
  const stereo::StereoParameters parameters;  // the defaults `s3d render` uses
  deferred.render(renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight),
                                               {parameters.weaponDepthOffset, parameters.weaponDepthScale}));
  const ImageStatistics center = statisticsOf(deferred.readDisplayColor());
  const ImageStatistics left =
      statisticsOf(stereo::synthesizeTimed(context(), deferred.displayColor(), deferred.linearDepth(), parameters).eyes.left);

  if (std::getenv(kUpdateVariable) != nullptr) {
    nlohmann::json stored = readStored();
    stored["about"] = "Statistics of each built-in scene's frame 0 (center view, synthesized left eye) at 96x54, "
                      "checked by tests/frame/test_scene_statistics.cpp. Regenerate: S3D_UPDATE_SCENE_STATISTICS=1 "
                      "build/tests/s3d_tests_frame --gtest_filter='BuiltInScenes/SceneStatistics.*'";
    stored["scenes"][name] = {{"center", toJson(center)}, {"left", toJson(left)}};
    std::ofstream(kStoredStatistics) << formatted(stored);
    GTEST_SKIP() << "stored the statistics of '" << name << "' in " << kStoredStatistics.string();
  }
  const nlohmann::json stored = readStored();
  ASSERT_TRUE(stored.contains("scenes") && stored["scenes"].contains(name))
      << "no stored statistics for scene '" << name << "' in " << kStoredStatistics.string() << "; regenerate with "
      << kUpdateVariable << "=1 (see the top of this file)";
  expectMatches(center, stored["scenes"][name].at("center"), "center view");
  expectMatches(left, stored["scenes"][name].at("left"), "left eye");
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenes, SceneStatistics, ::testing::ValuesIn(renderer::builtInSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace s3d
