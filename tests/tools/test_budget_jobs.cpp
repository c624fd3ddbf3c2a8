// The disparity budget in the jobs: `s3d render` and `--sequence` with the 1-degree rule fit every frame; the
// nonlinear depth-to-parallax mapping keeps that fit, and its per-layer reference picks each pixel's layer.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "s3d/app/convert_job.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/app/render_job.h"
#include "s3d/app/sequence_job.h"
#include "s3d/renderer/scene_file.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / ("s3d_budget_" + name + "_" + std::to_string(::getpid()));
}

// A small single-frame render under the 1-degree rule on `display`, writing nothing.
RenderJobOptions oneDegreeRender(const std::string& name, const std::string& display) {
  RenderJobOptions options;
  options.width = 128;
  options.height = 72;
  options.outputs = {};
  options.outputFolder = scratch(name);
  options.display = comfort::builtInDisplayProfile(display);
  options.disparityBudget = comfort::DisparityBudgetRule::OneDegree;
  return options;
}

class BudgetJobs : public test::VulkanTest {};

TEST_F(BudgetJobs, ACourtyardFrameOnAMonitorFitsTheOneDegreeRule) {
  // With the defaults (2 % separation) the sky alone, at 4 % of the width, breaks the 2.05 % budget of a 27-inch monitor.
  const RenderJobOptions options = oneDegreeRender("render", "monitor27");
  const RenderReport report = runRenderJob(context(), options);
  EXPECT_EQ(report.comfort.parallax.shareBeyondOneDegree, 0.0);
  EXPECT_GE(report.budget.choice.usedShare, 0.8);
  EXPECT_TRUE(report.budget.choice.cut);  // a single frame starts as a cut: the target itself
  EXPECT_EQ(report.stereo.maxSeparation, report.budget.choice.target.maxSeparation);
  EXPECT_GE(report.comfort.parallax.minParallaxPx, -1e-3);  // nothing in front of the screen
  const nlohmann::json json = toJson(report).at("disparityBudget");
  EXPECT_EQ(json.at("rule"), "1deg");
  EXPECT_EQ(json.at("shareOutside"), 0.0);
}

TEST_F(BudgetJobs, TheBudgetInPixelsIsInTheOutputEyesPixelsWithAGuardBand) {
  // The reduction runs over the wider rendered frame; report.json's budgetPx and bulkShare are in the output eyes'
  // pixels, as the comfort report's parallax (the rendered width would shrink the bulk share by 128 / 136).
  const RenderJobOptions options = oneDegreeRender("budget_px", "tv55");
  const RenderReport report = runRenderJob(context(), options);
  ASSERT_GT(report.guardBandColumns, 0u);
  const nlohmann::json json = toJson(report).at("disparityBudget");
  // Tolerance 1e-4 px: budgetPx is printed as a float.
  EXPECT_NEAR(json.at("budgetPx").at("uncrossed").get<double>(), report.budget.budget.uncrossedFraction * 128.0, 1e-4);
  const comfort::ParallaxStatistics& parallax = report.comfort.parallax;
  EXPECT_NEAR(json.at("bulkShare").get<double>(),
              (parallax.p95ParallaxPx - parallax.p05ParallaxPx) / (report.budget.budget.uncrossedFraction * 128.0), 1e-9);
}

// The cover sequence at 96x54 with the disparity budget, run once per test binary.
SequenceJobOptions budgetSequenceOptions() {
  SequenceJobOptions options;
  options.width = 96;
  options.height = 54;
  options.writeFrames = false;
  options.outputFolder = scratch("sequence");
  options.disparityBudget = comfort::DisparityBudgetRule::OneDegree;
  return options;
}
const SequenceReport& budgetSequence(vk::Context& context) {
  static const SequenceReport report = [&] {
    const SequenceJobOptions options = budgetSequenceOptions();
    SequenceReport result = runSequenceJob(context, options);
    std::error_code ignored;
    fs::remove_all(options.outputFolder, ignored);
    return result;
  }();
  return report;
}

TEST_F(BudgetJobs, TheCoverSequenceStaysWithinTheBudgetInEveryFrame) {
  const SequenceReport& report = budgetSequence(context());
  ASSERT_FALSE(report.frames.empty());
  for (const SequenceFrame& frame : report.frames) {
    EXPECT_EQ(frame.comfort.parallax.shareBeyondOneDegree, 0.0) << "frame " << frame.index;
    EXPECT_GE(frame.comfort.parallax.minParallaxPx, -1e-3) << "frame " << frame.index;
    EXPECT_EQ(frame.maxSeparation, frame.budget.choice.parameters.maxSeparation);
  }
}

// The memory estimate, checked before anything is allocated, counts a band at least as wide as any frame's.
TEST_F(BudgetJobs, TheSequenceMemoryEstimateCoversEveryFramesGuardBand) {
  const SequenceReport& report = budgetSequence(context());
  const stereo::GuardBand widest = widestSequenceGuardBand(budgetSequenceOptions());
  for (const SequenceFrame& frame : report.frames)
    EXPECT_LE(frame.guardBandColumns, widest.columns) << "frame " << frame.index;
  EXPECT_NE(sequenceMemoryEstimate(budgetSequenceOptions()).what.find("guard band 2 x " + std::to_string(widest.columns)),
            std::string::npos);
}

// The textured quad seen from 0.5 m filling the frame: one depth, no sky, so the controller chooses its largest
// separation (a wider guard band than the run's first estimate assumed).
fs::path flatWallScene(const fs::path& folder) {
  fs::create_directories(folder);
  const fs::path data = S3D_TEST_DATA_DIR;
  for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_base_color.png",
                           "textured_quad_normal.png", "textured_quad.scene.json"})
    fs::copy_file(data / name, folder / name, fs::copy_options::overwrite_existing);
  std::ifstream in(folder / "textured_quad.scene.json");
  nlohmann::json description = nlohmann::json::parse(in);
  description["camera"] = {{"position", {0.0, 0.0, 0.5}}, {"verticalFovDegrees", 60.0}};
  std::ofstream(folder / "textured_quad.scene.json") << description.dump();
  return folder / "textured_quad.gltf";
}

RenderJobOptions flatWallOptions(const std::string& name) {
  RenderJobOptions options = oneDegreeRender(name, "tv55");
  options.outputs = {"report.json"};
  options.scene = flatWallScene(scratch(name + "_scene")).string();
  return options;
}

TEST_F(BudgetJobs, TheReportedMemoryEstimateCountsTheGuardBandTheControllerChose) {
  const RenderJobOptions options = flatWallOptions("wall_estimate");
  const RenderReport report = runRenderJob(context(), options);
  ASSERT_GT(report.guardBandColumns, 0u);
  EXPECT_NEAR(report.stereo.maxSeparation, comfort::DisparityBudgetSettings{}.maximumSeparation, 1e-6);
  EXPECT_GT(report.memory.totalBytes(), renderJobMemoryEstimate(options).totalBytes());
  EXPECT_NE(report.memory.what.find("guard band 2 x " + std::to_string(report.guardBandColumns) + " columns"),
            std::string::npos);
}

TEST_F(BudgetJobs, AChosenGuardBandBeyondTheMemoryLimitFailsBeforeAnyOutput) {
  // The limit admits the first estimate (the display's budget) but not the band the controller then chooses.
  RenderJobOptions options = flatWallOptions("wall_limit");
  options.memoryLimitBytes = renderJobMemoryEstimate(options).totalBytes();
  try {
    (void)runRenderJob(context(), options);
    FAIL() << "the run should stop at the chosen guard band's estimate";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("--disparity-budget chose"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("--memory-limit"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(options.outputFolder / "report.json"));
}

TEST_F(BudgetJobs, ConvertFitsAFileDepthMapIntoTheBudget) {
  // The 8x4 fixture spans 1 to 8 m: with the budget the separation fills 90 % of the monitor's budget.
  ConvertJobOptions options;
  options.color = fs::path(S3D_TEST_DATA_DIR) / "convert" / "color.png";
  options.depth = fs::path(S3D_TEST_DATA_DIR) / "convert" / "depth.pfm";
  options.outputFolder = scratch("convert");
  options.display = comfort::builtInDisplayProfile("monitor27");
  options.disparityBudget = comfort::DisparityBudgetRule::OneDegree;
  const ConvertReport report = runConvertJob(context(), options);
  std::error_code ignored;
  fs::remove_all(options.outputFolder, ignored);
  EXPECT_EQ(report.comfort.parallax.shareBeyondOneDegree, 0.0);
  EXPECT_NEAR(report.budget.choice.usedShare, 0.9, 1e-4);
  EXPECT_EQ(report.stereo.maxSeparation, report.budget.choice.parameters.maxSeparation);
}

TEST_F(BudgetJobs, TheNonlinearMappingKeepsTheFitAndGivesTheSceneMoreOfTheBudget) {
  // The courtyard on a monitor, linear and nonlinear: the same parameters and full range (the map keeps the
  // nearest depth and the sky), nothing beyond 1 degree or in front of the screen, and the 5-95 % of the scene's
  // pixels spread over more of the budget. The per-layer reference takes one rendering per segment; pixels no
  // layer claims stay a small share, and the error against it is of the linear error's order.
  RenderReport reports[2];
  for (const stereo::DisparityMapping mapping : {stereo::DisparityMapping::Linear, stereo::DisparityMapping::Nonlinear}) {
    RenderJobOptions options;
    options.width = 160;
    options.height = 90;
    options.outputs = {"report.json"};
    options.outputFolder = scratch("mapping");
    options.display = comfort::builtInDisplayProfile("monitor27");
    options.disparityBudget = comfort::DisparityBudgetRule::OneDegree;
    options.stereo.disparityMapping = mapping;
    reports[int(mapping)] = runRenderJob(context(), options);
    std::error_code ignored;
    fs::remove_all(options.outputFolder, ignored);
  }
  const RenderReport& linear = reports[0];
  const RenderReport& nonlinear = reports[1];
  EXPECT_EQ(nonlinear.stereo.maxSeparation, linear.stereo.maxSeparation);
  EXPECT_EQ(nonlinear.stereo.zeroParallaxDistance, linear.stereo.zeroParallaxDistance);
  EXPECT_EQ(nonlinear.comfort.parallax.shareBeyondOneDegree, 0.0);
  EXPECT_GE(nonlinear.comfort.parallax.minParallaxPx, -1e-3);
  // The full range: float parallax of the same nearest and farthest pixels (1e-3 px).
  EXPECT_NEAR(nonlinear.comfort.parallax.maxParallaxPx, linear.comfort.parallax.maxParallaxPx, 1e-3);
  EXPECT_NEAR(nonlinear.comfort.parallax.minParallaxPx, linear.comfort.parallax.minParallaxPx, 1e-3);
  const auto bulk = [](const RenderReport& r) { return r.comfort.parallax.p95ParallaxPx - r.comfort.parallax.p05ParallaxPx; };
  EXPECT_GT(bulk(nonlinear), bulk(linear));
  EXPECT_EQ(linear.disparityMap.referenceLayers, 1u);
  EXPECT_GT(nonlinear.disparityMap.referenceLayers, 2u);
  for (std::uint64_t unresolved : nonlinear.disparityMap.unresolvedPixels) EXPECT_LT(unresolved, 160u * 90u / 20u);
  EXPECT_GT(nonlinear.left.display.psnrDb, linear.left.display.psnrDb - 3.0);
  EXPECT_GT(nonlinear.right.display.psnrDb, linear.right.display.psnrDb - 3.0);
  EXPECT_EQ(toJson(nonlinear).at("disparityMapping").at("mapping"), "nonlinear");
}

TEST(ReferenceLayers, EachPixelTakesTheNearestSurfaceInItsOwnSegment) {
  // Two segments split at 4 m (u = 0.25). Pixel 0: layer 0 sees 10 m (in its segment), layer 1 sees 2 m (in
  // its own): the nearer wins. Pixel 1: layer 0 sees 3 m, layer 1 sees 9 m, neither in its own segment:
  // unresolved, taken from the layer whose segment lies nearer in inverse depth (layer 0: 1/3 is 0.083 past
  // 0.25; layer 1: 1/9 is 0.139 short of it). Pixel 2: only layer 0 qualifies (its sky).
  const std::vector<stereo::DisparityMapSegment> segments = {{0.0, 0.25, 0.5, 0.0}, {0.25, INFINITY, 1.5, -0.25}};
  DepthImage layer0(3, 1), layer1(3, 1);
  layer0.pixels = {10.0f, 3.0f, INFINITY};
  layer1.pixels = {2.0f, 9.0f, 7.0f};
  std::uint64_t unresolved = 0;
  const std::vector<std::uint8_t> chosen = frame::chooseReferenceLayers({layer0, layer1}, segments, &unresolved);
  EXPECT_EQ(chosen, (std::vector<std::uint8_t>{1, 0, 0}));
  EXPECT_EQ(unresolved, 1u);
}

TEST(ReferenceLayers, TheLinearMappingsReferenceIsTheExactEyeCameras) {
  // The identity segment gives exactly the cameras of stereo::offAxisEyeCamera (the two-pass reference).
  renderer::Scene scene = renderer::loadScene("courtyard");
  const renderer::ViewMatrices center = renderer::centerViewMatrices(scene, 16.0f / 9.0f, {1.0f, 1.0f});
  stereo::StereoParameters parameters;
  const renderer::ViewMatrices view = frame::referenceEyeView(scene, center, stereo::Eye::Left, parameters);
  const stereo::EyeCamera expected =
      stereo::offAxisEyeCamera(center.worldView, center.worldProjection, stereo::Eye::Left, parameters.maxSeparation,
                               parameters.zeroParallaxDistance);
  EXPECT_EQ(view.worldView, expected.view);
  EXPECT_EQ(view.worldProjection, expected.projection);
  EXPECT_EQ(stereo::disparityMapSegments(stereo::identityDisparityMap()).size(), 1u);
}

}  // namespace
}  // namespace s3d::app
