// `s3d render` as a library: the default scene end to end (outputs, report.json, quality against the
// two-pass reference) and option validation that happens before anything is created.
#include <gtest/gtest.h>

#include <unistd.h>  // getpid: keeps parallel test runs in separate folders

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/render_job.h"
#include "s3d/io/image_io.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {
namespace fs = std::filesystem;

// Lowest accepted PSNR of each synthesized eye against its two-pass reference on the default scene at
// 320x180 with the default parameters (Listing 4.5, weapon pushed 1 m into the screen): measured 21.6 dB
// (left) and 21.7 dB (right). 19 dB leaves room for driver differences and still fails when the
// displacement goes wrong: swapped eyes measured 11.5-11.9 dB, and without the weapon push (whose
// negative parallax the seed's search cannot handle) 17.8 / 19.5 dB.
constexpr double kMinDefaultScenePsnrDb = 19.0;

constexpr std::uint32_t kWidth = 320;
constexpr std::uint32_t kHeight = 180;

fs::path scratchFolder(const std::string& name) {
  return fs::temp_directory_path() / ("s3d_render_job_" + std::to_string(::getpid()) + "_" + name);
}

// The default scene rendered once per test binary (the suite stays fast); the folder goes at exit.
struct DefaultRun {
  fs::path folder;
  RenderReport report;
  ~DefaultRun() {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
  }
};

const DefaultRun& defaultRun(vk::Context& context) {
  static const std::unique_ptr<DefaultRun> run = [&] {
    auto result = std::make_unique<DefaultRun>();
    result->folder = scratchFolder("default");
    std::error_code ignored;
    fs::remove_all(result->folder, ignored);
    RenderJobOptions options;
    options.width = kWidth;
    options.height = kHeight;
    options.outputFolder = result->folder;
    result->report = runRenderJob(context, options);
    return result;
  }();
  return *run;
}

std::vector<std::string> folderEntries(const fs::path& folder) {
  std::vector<std::string> names;
  std::error_code error;
  if (!fs::exists(folder, error)) return names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  return names;
}

// A JSON number that is finite (nlohmann writes NaN and infinity as null, so a number is finite on parse).
void expectFiniteNumber(const nlohmann::json& object, const std::string& key, const std::string& where) {
  ASSERT_TRUE(object.contains(key)) << where << "." << key << " is missing";
  const nlohmann::json& value = object.at(key);
  ASSERT_TRUE(value.is_number()) << where << "." << key << " is not a number: " << value.dump();
  EXPECT_TRUE(std::isfinite(value.get<double>())) << where << "." << key;
}

// Share of pixels whose RGB differs between two same-size images.
double differingPixelShare(const ImageRGBA8& a, const ImageRGBA8& b) {
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.pixelCount(); ++i)
    for (int c = 0; c < 3; ++c)
      if (a.pixels[i * 4 + c] != b.pixels[i * 4 + c]) {
        ++differing;
        break;
      }
  return double(differing) / double(a.pixelCount());
}

class RenderJob : public test::VulkanTest {};

TEST_F(RenderJob, WritesEveryOutputAtomically) {
  const DefaultRun& run = defaultRun(context());
  EXPECT_EQ(run.report.filesWritten, kAllOutputs);  // everything by default, in the documented order
  for (const std::string& name : kAllOutputs) {
    EXPECT_TRUE(fs::is_regular_file(run.folder / name)) << name;
    std::error_code error;
    EXPECT_GT(fs::file_size(run.folder / name, error), 0u) << name;
  }
  for (const std::string& name : folderEntries(run.folder)) EXPECT_NE(fs::path(name).extension(), ".tmp") << name;
  EXPECT_EQ(folderEntries(run.folder).size(), kAllOutputs.size());
}

TEST_F(RenderJob, ImagesHaveTheRequestedSizes) {
  const DefaultRun& run = defaultRun(context());
  for (const char* name : {"center.png", "left.png", "right.png", "left_reference.png", "right_reference.png",
                           "anaglyph.png", "sbs.png", "tab.png"}) {  // half packing by default: same size
    ImageRGBA8 image = io::readPng(run.folder / name);
    EXPECT_EQ(image.width, kWidth) << name;
    EXPECT_EQ(image.height, kHeight) << name;
  }
  io::ExrFrame exr = io::readExr(run.folder / "center.exr");
  EXPECT_EQ(exr.color.width, kWidth);
  EXPECT_EQ(exr.color.height, kHeight);
  EXPECT_TRUE(exr.hasDepth);
}

TEST_F(RenderJob, ReportJsonHasEveryFieldAndOnlyFiniteNumbers) {
  const DefaultRun& run = defaultRun(context());
  std::ifstream stream(run.folder / "report.json");
  ASSERT_TRUE(stream) << "report.json missing";
  nlohmann::json report;
  ASSERT_NO_THROW(report = nlohmann::json::parse(stream));

  EXPECT_EQ(report.at("device"), context().deviceName());
  EXPECT_EQ(report.at("scene"), "courtyard");
  EXPECT_EQ(report.at("width"), kWidth);
  EXPECT_EQ(report.at("height"), kHeight);

  const nlohmann::json& stereo = report.at("stereo");
  for (const char* key : {"maxSeparation", "zeroParallaxDistance", "edgeCrop", "cropColumns", "guardBandColumns", "renderedWidth"})
    expectFiniteNumber(stereo, key, "stereo");
  EXPECT_EQ(stereo.at("method"), "search");  // the default: 4 taps
  EXPECT_EQ(stereo.at("searchTaps"), 4);
  EXPECT_DOUBLE_EQ(stereo.at("maxSeparation").get<double>(), 0.02);
  EXPECT_DOUBLE_EQ(stereo.at("edgeCrop").get<double>(), 0.0);  // the default: full-frame eyes
  EXPECT_EQ(stereo.at("cropColumns"), 0);
  EXPECT_EQ(stereo.at("guardBandColumns"), 8);  // ceil(0.02 * 320) + 1: sky's parallax and the filter texel
  EXPECT_EQ(stereo.at("renderedWidth"), kWidth + 16);

  // lavapipe has timestamps, so every time must be a number.
  for (const char* key : {"centerFrame", "stereoPass", "referenceEye"})
    expectFiniteNumber(report.at("gpuTimeMs"), key, "gpuTimeMs");
  ASSERT_TRUE(report.at("centerPasses").is_array());
  EXPECT_FALSE(report.at("centerPasses").empty());
  for (const nlohmann::json& pass : report.at("centerPasses")) {
    EXPECT_TRUE(pass.at("name").is_string());
    expectFiniteNumber(pass, "gpuMs", "centerPasses[]");
  }
  expectFiniteNumber(report.at("ratios"), "stereoPassToReferenceEye", "ratios");

  for (const char* eye : {"left", "right"}) {
    const nlohmann::json& error = report.at("error").at(eye);
    for (const char* key : {"psnrDb", "ssim", "meanAbsoluteError", "shareAbove8", "pixelCount"})
      expectFiniteNumber(error, key, std::string("error.") + eye);
    EXPECT_EQ(error.at("pixelCount"), std::uint64_t(kWidth) * kHeight);  // the whole frame
    for (const char* region : {"halo", "disocclusion", "transparent", "foliage", "rest"})
      expectFiniteNumber(error.at(region), "ssim", std::string("error.") + eye + "." + region);
    EXPECT_EQ(error.at("transparent").at("pixelCount"), 0);  // the courtyard has no transparent objects
    EXPECT_EQ(error.at("foliage").at("pixelCount"), 0);      // nor alpha cut-outs
    const nlohmann::json& hdr = error.at("hdr");
    for (const char* key : {"psnrDb", "ssim", "meanAbsoluteError", "pixelCount"})
      expectFiniteNumber(hdr, key, std::string("error.") + eye + ".hdr");
    for (const char* region : {"halo", "disocclusion", "transparent", "foliage", "rest"})
      expectFiniteNumber(hdr.at(region), "psnrDb", std::string("error.") + eye + ".hdr." + region);
  }
  EXPECT_EQ(report.at("sanitized").at("colorValues"), 0);  // the renderer writes no NaN or inf
  EXPECT_EQ(report.at("sanitized").at("depthPixels"), 0);
  EXPECT_TRUE(report.at("warnings").is_array() && report.at("warnings").empty());
  EXPECT_EQ(report.at("files").get<std::vector<std::string>>(), kAllOutputs);
}

TEST_F(RenderJob, CrosshairIsPlacedByTheAimRayAndReported) {
  // The courtyard's aim ray is open for the scene's 8 m default, or the crosshair sits before a hit.
  const RenderReport& report = defaultRun(context()).report;
  EXPECT_GT(report.crosshair.depth, 0.0f);
  EXPECT_LE(report.crosshair.depth, 8.0f);
  if (!report.crosshair.hitWorld) {
    EXPECT_FLOAT_EQ(report.crosshair.depth, 8.0f);
  }
  // parallax = 0.02 * (1 - 1 / depth) * 320 px
  EXPECT_NEAR(report.crosshair.parallaxPx, 0.02f * (1.0f - 1.0f / report.crosshair.depth) * 320.0f, 1e-3f);
  std::ifstream stream(defaultRun(context()).folder / "report.json");
  nlohmann::json json = nlohmann::json::parse(stream);
  for (const char* key : {"depth", "parallaxPx"}) expectFiniteNumber(json.at("crosshair"), key, "crosshair");
  EXPECT_TRUE(json.at("crosshair").at("hitWorld").is_boolean());
}

TEST_F(RenderJob, SynthesizedEyesAreCloseToTheTwoPassReference) {
  const RenderReport& report = defaultRun(context()).report;
  EXPECT_GE(report.left.display.psnrDb, kMinDefaultScenePsnrDb);
  EXPECT_GE(report.right.display.psnrDb, kMinDefaultScenePsnrDb);
  ASSERT_TRUE(report.centerFrameGpuMs && report.stereoPassGpuMs && report.referenceEyeGpuMs);
  EXPECT_GT(*report.centerFrameGpuMs, 0.0);
  EXPECT_GT(*report.stereoPassGpuMs, 0.0);
  EXPECT_GT(*report.referenceEyeGpuMs, 0.0);
}

TEST_F(RenderJob, BothEyesDifferFromTheCenter) {
  const DefaultRun& run = defaultRun(context());
  const ImageRGBA8 center = io::readPng(run.folder / "center.png");
  const ImageRGBA8 left = io::readPng(run.folder / "left.png");
  const ImageRGBA8 right = io::readPng(run.folder / "right.png");
  // Full-frame eyes: no crop strip, so the differences are the parallax's.
  EXPECT_GT(differingPixelShare(left, center), 0.06);
  EXPECT_GT(differingPixelShare(right, center), 0.06);
  EXPECT_GT(differingPixelShare(left, right), 0.06);
  const ImageRGBA8 leftReference = io::readPng(run.folder / "left_reference.png");
  const ImageRGBA8 rightReference = io::readPng(run.folder / "right_reference.png");
  EXPECT_GT(differingPixelShare(leftReference, center), 0.02);
  EXPECT_GT(differingPixelShare(rightReference, center), 0.02);
}

TEST_F(RenderJob, WritesExactlyTheSelectedOutputs) {
  const fs::path folder = scratchFolder("subset");
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  RenderJobOptions options;
  options.width = 64;
  options.height = 36;
  options.outputFolder = folder;
  options.outputs = {"sbs.png", "tab.png"};
  options.sideBySide = stereo::PackingMode::Full;
  options.topBottom = stereo::PackingMode::Full;
  const RenderReport report = runRenderJob(context(), options);
  EXPECT_EQ(report.filesWritten, (std::vector<std::string>{"sbs.png", "tab.png"}));
  std::vector<std::string> entries = folderEntries(folder);
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"sbs.png", "tab.png"}));
  const ImageRGBA8 sbs = io::readPng(folder / "sbs.png");
  const ImageRGBA8 tab = io::readPng(folder / "tab.png");
  EXPECT_EQ(sbs.width, 128u);
  EXPECT_EQ(sbs.height, 36u);
  EXPECT_EQ(tab.width, 64u);
  EXPECT_EQ(tab.height, 72u);
  fs::remove_all(folder, ignored);
}

TEST_F(RenderJob, BadOptionsThrowBeforeAnythingIsWritten) {
  struct Case {
    const char* what;
    void (*apply)(RenderJobOptions&);
  };
  const Case cases[] = {
      {"zero width", [](RenderJobOptions& o) { o.width = 0; }},
      {"zero height", [](RenderJobOptions& o) { o.height = 0; }},
      {"absurd width", [](RenderJobOptions& o) { o.width = kMaxImageSize + 1; }},
      {"maxSeparation 0.9", [](RenderJobOptions& o) { o.stereo.maxSeparation = 0.9f; }},
      {"zeroParallaxDistance 0", [](RenderJobOptions& o) { o.stereo.zeroParallaxDistance = 0.0f; }},
      {"unknown scene", [](RenderJobOptions& o) { o.scene = "no_such_scene"; }},
      {"unknown output", [](RenderJobOptions& o) { o.outputs = {"center.png", "center.jpg"}; }},
      {"crop leaves no columns", [](RenderJobOptions& o) {
         o.width = 2;
         o.stereo.edgeCrop = 0.25f;  // ceil(0.25 * 2) = 1 column on each side of 2
       }},
  };
  for (const Case& c : cases) {
    for (bool folderExists : {false, true}) {
      const fs::path folder = scratchFolder(std::string("bad_") + (folderExists ? "existing" : "absent"));
      std::error_code ignored;
      fs::remove_all(folder, ignored);
      if (folderExists) fs::create_directories(folder);
      RenderJobOptions options;
      options.width = 32;
      options.height = 18;
      options.outputFolder = folder;
      c.apply(options);
      EXPECT_THROW(validateRenderJobOptions(options), std::invalid_argument) << c.what;
      EXPECT_THROW(runRenderJob(context(), options), std::invalid_argument) << c.what;
      EXPECT_EQ(fs::exists(folder), folderExists) << c.what;
      EXPECT_TRUE(folderEntries(folder).empty()) << c.what;
      fs::remove_all(folder, ignored);
    }
  }
}

TEST_F(RenderJob, ErrorMessagesNameTheProblem) {
  RenderJobOptions options;
  options.scene = "no_such_scene";
  try {
    validateRenderJobOptions(options);
    ADD_FAILURE() << "unknown scene accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_scene"), std::string::npos) << error.what();
  }
  options = {};
  options.stereo.maxSeparation = 0.9f;
  try {
    validateRenderJobOptions(options);
    ADD_FAILURE() << "maxSeparation 0.9 accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("maxSeparation"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace s3d::app

namespace s3d::app {
namespace {

TEST(RenderJobOptionsCheck, AFrameBeyondTheScenesPathIsRejectedWithItsCount) {
  RenderJobOptions options;
  options.scene = "cover";
  options.frame = 1000;
  try {
    validateRenderJobOptions(options);
    FAIL() << "no exception";
  } catch (const std::out_of_range& error) {
    EXPECT_NE(std::string(error.what()).find("1000"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace s3d::app

namespace s3d::app {
namespace {

class RenderJobMethods : public test::VulkanTest {};

TEST_F(RenderJobMethods, TheIterativeMethodRunsEndToEndAndReportsFilledPixels) {
  const fs::path folder = scratchFolder("iterative");
  RenderJobOptions options;
  options.width = 96;
  options.height = 54;
  options.outputFolder = folder;
  options.outputs = {"report.json"};
  options.stereo.method = stereo::StereoMethod::Iterative;
  const RenderReport report = runRenderJob(context(), options);
  std::ifstream stream(folder / "report.json");
  const nlohmann::json json = nlohmann::json::parse(stream);
  EXPECT_EQ(json.at("stereo").at("method"), "iterative");
  EXPECT_EQ(json.at("stereo").at("iterations"), 6);
  EXPECT_GT(report.filledPixels[0] + report.filledPixels[1], 0u);  // the weapon and pillars disocclude something
  EXPECT_GT(report.left.display.pixelCount, 0u);  // its quality is held to the seed's in test_iterative.cpp
  std::error_code ignored;
  fs::remove_all(folder, ignored);
}

TEST_F(RenderJobMethods, TheForwardMethodRunsEndToEndWithItsHdrEyes) {
  const fs::path folder = scratchFolder("forward");
  RenderJobOptions options;
  options.width = 96;
  options.height = 54;
  options.outputFolder = folder;
  options.outputs = {"report.json"};
  options.stereo.method = stereo::StereoMethod::Forward;
  const RenderReport report = runRenderJob(context(), options);
  std::ifstream stream(folder / "report.json");
  EXPECT_EQ(nlohmann::json::parse(stream).at("stereo").at("method"), "forward");
  EXPECT_GT(report.left.display.pixelCount, 0u);
  ASSERT_TRUE(report.left.hdr.has_value());  // the HDR eyes use the same samples (test_hdr_gather.cpp)
  EXPECT_GT(report.left.hdr->all.pixelCount, 0u);
  std::error_code ignored;
  fs::remove_all(folder, ignored);
}

TEST_F(RenderJob, NegativeParallaxAppearsOnlyWhenAllowed) {
  // A zero-parallax plane 3 m out puts the weapon (pushed to 1.27-1.6 m) and the near courtyard in front of
  // the screen; disallowed, the weapon is pushed onto the plane and the plane held at the nearest surface.
  RenderJobOptions options;
  options.width = 64;
  options.height = 36;
  options.outputs = {};
  options.stereo.zeroParallaxDistance = 3.0f;
  options.allowNegativeParallax = true;
  const RenderReport allowed = runRenderJob(context(), options);
  EXPECT_GT(allowed.comfort.parallax.shareNegative, 0.0);
  EXPECT_LT(allowed.comfort.parallax.minParallaxPx, 0.0);
  options.allowNegativeParallax = false;
  const RenderReport disallowed = runRenderJob(context(), options);
  EXPECT_EQ(disallowed.comfort.parallax.shareNegative, 0.0);
  EXPECT_GE(disallowed.comfort.parallax.minParallaxPx, 0.0);
  EXPECT_EQ(disallowed.comfort.windowViolationPixels, 0u);
  EXPECT_GE(disallowed.crosshair.depth, disallowed.stereo.zeroParallaxDistance);
}

TEST_F(RenderJob, EyesAreFullFrameByDefault) {
  // The guard band gives every eye column a source: no column is black from edge to edge.
  const DefaultRun& run = defaultRun(context());
  for (const char* name : {"left.png", "right.png"}) {
    const ImageRGBA8 eye = io::readPng(run.folder / name);
    for (std::uint32_t x = 0; x < eye.width; ++x) {
      bool lit = false;
      for (std::uint32_t y = 0; y < eye.height && !lit; ++y) lit = eye.at(x, y)[0] || eye.at(x, y)[1] || eye.at(x, y)[2];
      EXPECT_TRUE(lit) << name << " column " << x << " is black";
    }
  }
}

TEST_F(RenderJob, EdgeCropRendersTheOutputSizeAndBlacksOutTheStrips) {
  RenderJobOptions options;
  options.width = 64;
  options.height = 36;
  options.outputs = {};
  options.stereo.edgeCrop = 0.05f;  // ceil(3.2) = 4 columns a side
  const RenderReport report = runRenderJob(context(), options);
  EXPECT_EQ(report.cropColumns, 4u);
  EXPECT_EQ(report.guardBandColumns, 0u);
  EXPECT_EQ(report.renderedWidth, 64u);
}

TEST_F(RenderJob, AllowedNegativeParallaxWidensTheGuardBandToTheNearPlane) {
  RenderJobOptions options;
  options.width = 64;
  options.height = 36;
  options.outputs = {};
  const RenderReport held = runRenderJob(context(), options);
  EXPECT_EQ(held.guardBandColumns, 3u);  // ceil(0.02 * 64) + 1: the sky's parallax, nothing in front
  options.allowNegativeParallax = true;
  const RenderReport allowed = runRenderJob(context(), options);
  EXPECT_GT(allowed.guardBandColumns, held.guardBandColumns);
  EXPECT_EQ(allowed.renderedWidth, 64u + 2 * allowed.guardBandColumns);
}

TEST_F(RenderJob, TheHudFadesBehindTheWeaponAndTheOutputsAreOpaque) {
  // Courtyard: the weapon covers the lower right, where the ammo panel (2.5 m, behind the weapon) sits.
  const DefaultRun& run = defaultRun(context());
  ASSERT_EQ(run.report.hud.size(), 3u);  // health, ammo, crosshair
  const HudElementReport& ammo = run.report.hud[1];
  EXPECT_EQ(ammo.name, "ammo");
  EXPECT_TRUE(ammo.behindWeapon);
  EXPECT_GT(ammo.fadedPixels[0], 0u);
  EXPECT_GT(ammo.fadedPixels[1], 0u);
  EXPECT_EQ(run.report.hud[0].fadedPixels[0], 0u);  // health, lower left: nothing of the weapon there
  const ImageRGBA8 left = io::readPng(run.folder / "left.png");
  for (std::size_t i = 0; i < left.pixelCount(); ++i) ASSERT_EQ(left.pixels[4 * i + 3], 255) << "pixel " << i;
}

}  // namespace
}  // namespace s3d::app
