// `s3d tune` without its window: parameters by name, comfort profiles, the input script, camera control, the
// view modes, and one frame of the session against `s3d render`'s offscreen render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "s3d/app/render_job.h"
#include "s3d/comfort/comfort_views.h"
#include "s3d/io/image_io.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/sanitize.h"
#include "s3d/tune/tune_script.h"
#include "s3d/tune/tune_session.h"
#include "s3d/tune/tune_views.h"
#include "vulkan_test.h"

namespace s3d::tune {
namespace {

namespace fs = std::filesystem;

fs::path scratchFolder(const std::string& name) {
  const fs::path folder = fs::temp_directory_path() / ("s3d_tune_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  return folder;
}

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(TuneViewModes, NamesRoundTripAndAnUnknownNameListsTheChoices) {
  for (const std::string& name : viewModeNames()) EXPECT_EQ(viewModeName(parseViewMode(name)), name);
  EXPECT_EQ(viewModeNames().size(), 8u);
  const std::string message = errorOf([] { (void)parseViewMode("stereo"); });
  EXPECT_NE(message.find("'stereo'"), std::string::npos) << message;
  EXPECT_NE(message.find("anaglyph, sbs, left, right, reference, error, parallax, comfort"), std::string::npos) << message;
}

TEST(TuneParameters, EveryNamedParameterCanBeSet) {
  TuneSettings settings;
  const std::vector<std::pair<std::string, std::string>> values = {
      {"maxSeparation", "0.03"},      {"zeroParallaxDistance", "2.5"}, {"edgeCrop", "0.01"},
      {"method", "search"},           {"taps", "12"},                  {"iterations", "4"},
      {"weaponDepthOffset", "0.5"},   {"weaponDepthScale", "1.5"},     {"zppControl", "on"},
      {"zppEngageDistance", "3"},     {"zppReleaseMargin", "0.5"},     {"zppMinimumDistance", "0.3"},
      {"zppResponseSeconds", "0.5"},  {"zppMaxChangePerSecond", "2"},  {"crosshairDistance", "6"},
      {"crosshairMargin", "0.5"},     {"display", "monitor27"},        {"allowNegativeParallax", "on"},
      {"hybridBudget", "0.25"},       {"hybridBase", "iterative"},     {"hybridCell", "2"},
      {"hybridScoreFloor", "0.4"},
      {"disparityMapping", "nonlinear"}};
  ASSERT_EQ(values.size(), parameterNames().size());
  for (const auto& [name, value] : values) setParameter(settings, name, value);
  EXPECT_FLOAT_EQ(settings.profile.stereo.maxSeparation, 0.03f);
  EXPECT_FLOAT_EQ(settings.profile.stereo.zeroParallaxDistance, 2.5f);
  EXPECT_FLOAT_EQ(settings.profile.stereo.edgeCrop, 0.01f);
  EXPECT_EQ(settings.profile.stereo.method, stereo::StereoMethod::Search);
  EXPECT_EQ(settings.profile.stereo.searchTaps, 12);
  EXPECT_EQ(settings.profile.stereo.iterations, 4);
  EXPECT_FLOAT_EQ(settings.profile.stereo.weaponDepthOffset, 0.5f);
  EXPECT_FLOAT_EQ(settings.profile.stereo.weaponDepthScale, 1.5f);
  EXPECT_TRUE(settings.zeroParallaxControl);
  EXPECT_FLOAT_EQ(settings.profile.zeroParallax.engageDistance, 3.0f);
  EXPECT_FLOAT_EQ(settings.profile.zeroParallax.releaseMargin, 0.5f);
  EXPECT_FLOAT_EQ(settings.profile.zeroParallax.minimumDistance, 0.3f);
  EXPECT_FLOAT_EQ(settings.profile.zeroParallax.responseSeconds, 0.5f);
  EXPECT_FLOAT_EQ(settings.profile.zeroParallax.maxChangePerSecond, 2.0f);
  EXPECT_FLOAT_EQ(settings.profile.crosshair.distance.value_or(0.0f), 6.0f);
  EXPECT_FLOAT_EQ(settings.profile.crosshair.margin, 0.5f);
  EXPECT_FLOAT_EQ(settings.profile.stereo.hybridBudget, 0.25f);
  EXPECT_EQ(settings.profile.stereo.hybridBase, stereo::StereoMethod::Iterative);
  EXPECT_EQ(settings.profile.stereo.hybridCell, 2);
  EXPECT_FLOAT_EQ(settings.profile.stereo.hybridScoreFloor, 0.4f);
  EXPECT_EQ(settings.profile.display.name, "monitor27");
  EXPECT_TRUE(settings.profile.allowNegativeParallax);
  EXPECT_EQ(settings.profile.stereo.disparityMapping, stereo::DisparityMapping::Nonlinear);
}

TEST(TuneParameters, AnInvalidValueNamesTheParameterAndChangesNothing) {
  TuneSettings settings;
  const std::string message = errorOf([&] { setParameter(settings, "maxSeparation", "-0.1"); });
  EXPECT_EQ(message.rfind("maxSeparation", 0), 0u) << message;
  EXPECT_FLOAT_EQ(settings.profile.stereo.maxSeparation, TuneSettings{}.profile.stereo.maxSeparation);
  EXPECT_NE(errorOf([&] { setParameter(settings, "taps", "2.5"); }).find("whole number"), std::string::npos);
  EXPECT_NE(errorOf([&] { setParameter(settings, "display", "cinema"); }).find("cinema"), std::string::npos);
  EXPECT_NE(errorOf([&] { setParameter(settings, "separation", "0.1"); }).find("unknown parameter 'separation'"),
            std::string::npos);
  EXPECT_EQ(settings.profile.display.name, "tv55");
}

TEST(TuneParameters, TheNonlinearMappingAndTheHybridMethodRefuseEachOtherInEitherOrder) {
  // The hybrid method renders its masked pixels from one pair of eye cameras; a nonlinear map has one per segment.
  TuneSettings settings;
  setParameter(settings, "method", "hybrid");
  const std::string mapping = errorOf([&] { setParameter(settings, "disparityMapping", "nonlinear"); });
  EXPECT_EQ(mapping.rfind("disparityMapping = nonlinear: ", 0), 0u) << mapping;
  EXPECT_NE(mapping.find("hybrid"), std::string::npos) << mapping;
  EXPECT_EQ(settings.profile.stereo.disparityMapping, stereo::DisparityMapping::Linear);  // unchanged
  setParameter(settings, "method", "search");
  setParameter(settings, "disparityMapping", "nonlinear");
  EXPECT_NE(errorOf([&] { setParameter(settings, "method", "hybrid"); }).find("disparityMapping nonlinear"),
            std::string::npos);
  EXPECT_EQ(settings.profile.stereo.method, stereo::StereoMethod::Search);
}

TEST(TuneProfiles, SaveAndLoadRoundTripTheComfortProfileAndKeepTheToolsSwitches) {
  TuneSettings settings;
  setParameter(settings, "maxSeparation", "0.035");
  setParameter(settings, "method", "iterative");
  setParameter(settings, "iterations", "9");
  setParameter(settings, "zppEngageDistance", "2.75");
  setParameter(settings, "crosshairDistance", "5");
  setParameter(settings, "display", "hmd");
  const fs::path file = scratchFolder("profile") / "comfort.json";
  saveProfile(file, settings);
  TuneSettings base;
  base.zeroParallaxControl = true;
  const TuneSettings loaded = loadProfile(file, base);
  EXPECT_EQ(comfort::toJson(loaded.profile), comfort::toJson(settings.profile));
  EXPECT_TRUE(loaded.zeroParallaxControl);  // a tool switch, not part of the profile
  fs::remove_all(file.parent_path());
}

TEST(TuneProfiles, AnUnknownKeyIsAnErrorNamingItAndTheFile) {
  const fs::path file = scratchFolder("bad_profile") / "bad.json";
  {
    std::ofstream(file) << R"({"stereo": {"maxSeperation": 0.02}})";
  }
  const std::string message = errorOf([&] { (void)loadProfile(file); });
  EXPECT_NE(message.find("maxSeperation"), std::string::npos) << message;
  EXPECT_NE(message.find("bad.json"), std::string::npos) << message;
  fs::remove_all(file.parent_path());
}

TEST(TuneScript, ParseErrorsNameTheLine) {
  EXPECT_EQ(errorOf([] { (void)parseScript("view anaglyph\n\njump 3\n", "s.txt"); }), "s.txt:3: unknown command 'jump'");
  EXPECT_NE(errorOf([] { (void)parseScript("wait 0\n", "s.txt"); }).find("s.txt:1:"), std::string::npos);
  EXPECT_NE(errorOf([] { (void)parseScript("hold x 2\n", "s.txt"); }).find("w a s d q e"), std::string::npos);
  EXPECT_NE(errorOf([] { (void)parseScript("set gain 2\n", "s.txt"); }).find("unknown parameter 'gain'"),
            std::string::npos);
  EXPECT_NE(errorOf([] { (void)parseScript("view 3d\n", "s.txt"); }).find("unknown view '3d'"), std::string::npos);
  EXPECT_NE(errorOf([] { (void)parseScript("quit now\n", "s.txt"); }).find("takes 0 argument(s)"), std::string::npos);
  EXPECT_NE(errorOf([] { (void)parseScript("supersample 5\n", "s.txt"); }).find("1, 2, 3 or 4"), std::string::npos);
}

TEST(TuneScript, CommandsRunBeforeTheFirstFrameOfTheirWait) {
  ScriptPlayer player(parseScript("set maxSeparation 0.03  # comment\nwait 2\nview sbs\nscreenshot a.png\nquit\n"));
  ScriptFrame first = player.next();
  ASSERT_EQ(first.commands.size(), 1u);
  EXPECT_EQ(first.commands[0].verb, "set");
  EXPECT_TRUE(player.next().commands.empty());  // the second frame of the wait
  ScriptFrame third = player.next();
  ASSERT_EQ(third.commands.size(), 3u);
  EXPECT_EQ(third.commands[2].verb, "quit");
  EXPECT_TRUE(player.finished());
}

TEST(TuneScript, HoldPressesAKeyForItsFramesAndLookMovesOnce) {
  ScriptPlayer player(parseScript("hold w 2\nlook 10 -4\nwait 3\n"));
  const ScriptFrame first = player.next(), second = player.next(), third = player.next();
  EXPECT_TRUE(first.input.forward);
  EXPECT_TRUE(second.input.forward);
  EXPECT_FALSE(third.input.forward);
  EXPECT_FALSE(first.input.back || first.input.left || first.input.right || first.input.up || first.input.down);
  EXPECT_EQ(first.input.lookPx, glm::vec2(10.0f, -4.0f));
  EXPECT_EQ(second.input.lookPx, glm::vec2(0.0f));
}

TEST(TuneCamera, WalkingForwardMovesAlongTheViewDirectionAtWalkSpeed) {
  renderer::Camera camera;
  camera.yawRadians = 0.5f;
  const glm::vec3 start = camera.position;
  FrameInput input;
  input.forward = true;
  moveCamera(camera, input, 0.5f);
  const glm::vec3 expected = start + 0.5f * kWalkSpeed * glm::vec3(-std::sin(0.5f), 0.0f, -std::cos(0.5f));
  EXPECT_NEAR(glm::distance(camera.position, expected), 0.0f, 1e-5f);
}

TEST(TuneCamera, MouseRightTurnsRightAndPitchStopsShortOfVertical) {
  renderer::Camera camera;
  FrameInput input;
  input.lookPx = {100.0f, -10000.0f};  // right, and far up
  moveCamera(camera, input, 0.0f);
  EXPECT_FLOAT_EQ(camera.yawRadians, -100.0f * kLookRadiansPerPixel);
  EXPECT_FLOAT_EQ(camera.pitchRadians, kMaxPitchRadians);
  input = {};
  input.right = true;  // strafing right after turning right: towards +x and -z
  const glm::vec3 before = camera.position;
  moveCamera(camera, input, 1.0f);
  EXPECT_GT(camera.position.x, before.x);
}

DepthImage depthRow(std::initializer_list<float> depths) {
  DepthImage image(std::uint32_t(depths.size()), 1);
  std::copy(depths.begin(), depths.end(), image.pixels.begin());
  return image;
}

TEST(TuneViews, ParallaxHeatMapIsWhiteOnTheScreenPlaneBlueAtInfinityRedInFront) {
  stereo::StereoParameters parameters;  // zpp 1 m, maxSeparation 0.02
  const ImageRGBA8 map = comfort::makeParallaxHeatMap(depthRow({1.0f, INFINITY, 0.5f, 0.25f}), parameters);
  auto rgb = [&](std::uint32_t x) { return std::array<int, 3>{map.at(x, 0)[0], map.at(x, 0)[1], map.at(x, 0)[2]}; };
  EXPECT_EQ(rgb(0), (std::array<int, 3>{255, 255, 255}));
  EXPECT_EQ(rgb(1), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(rgb(2), (std::array<int, 3>{255, 0, 0}));  // parallax -m: full scale in front
  EXPECT_EQ(rgb(3), (std::array<int, 3>{255, 0, 0}));  // beyond it: clamped
}

TEST(TuneViews, ComfortMaskMarksPixelsBeyondOneDegreeOfDisparity) {
  // tv55 at 2.5 m: 1 degree of uncrossed disparity is about 4.4 cm of parallax; 1000 px over 1.218 m and
  // maxSeparation 0.05 give 2 * 0.05 * 1.218 m = 12 cm at infinity (marked) and none at the screen plane.
  stereo::StereoParameters parameters;
  parameters.maxSeparation = 0.05f;
  DepthImage depth(1000, 1, 1.0f);
  depth.pixels[10] = INFINITY;
  const std::vector<std::uint8_t> mask =
      comfortViolationMask(depth, parameters, comfort::builtInDisplayProfile("tv55"));
  EXPECT_EQ(mask[10], 1);
  EXPECT_EQ(std::count(mask.begin(), mask.end(), std::uint8_t(1)), 1);
}

FrameImages syntheticFrame() {
  FrameImages frame;
  frame.eyes.left = ImageRGBA8(8, 6, 200);
  frame.eyes.right = ImageRGBA8(8, 6, 60);
  frame.stereoDepth = DepthImage(8, 6, 1.0f);
  frame.display = comfort::builtInDisplayProfile("tv55");
  return frame;
}

TEST(TuneViews, AnaglyphViewIsTheDuboisAnaglyphOfTheEyes) {
  const FrameImages frame = syntheticFrame();
  EXPECT_EQ(composeView(ViewMode::Anaglyph, frame).pixels,
            stereo::makeAnaglyphDubois(frame.eyes.left, frame.eyes.right).pixels);
  EXPECT_EQ(composeView(ViewMode::Left, frame).pixels, frame.eyes.left.pixels);
  EXPECT_EQ(composeView(ViewMode::Right, frame).pixels, frame.eyes.right.pixels);
}

TEST(TuneViews, ComfortOverlayMarksOnlyPixelsBeyondTheLimit) {
  FrameImages frame = syntheticFrame();
  frame.parameters.maxSeparation = 0.2f;  // 8 px wide on tv55: infinity lies 0.49 m apart, far beyond 1 degree
  frame.stereoDepth.pixels[0] = INFINITY;
  const ImageRGBA8 anaglyph = composeView(ViewMode::Anaglyph, frame);
  const ImageRGBA8 overlay = composeView(ViewMode::ComfortOverlay, frame);
  EXPECT_NE(std::vector<std::uint8_t>(overlay.at(0, 0), overlay.at(0, 0) + 3),
            std::vector<std::uint8_t>(anaglyph.at(0, 0), anaglyph.at(0, 0) + 3));
  EXPECT_EQ(std::vector<std::uint8_t>(overlay.pixels.begin() + 4, overlay.pixels.end()),
            std::vector<std::uint8_t>(anaglyph.pixels.begin() + 4, anaglyph.pixels.end()));
}

TEST(TuneViews, ComfortOverlayMarksWindowViolationsAndTheOneDegreeRuleInTheirOwnColours) {
  // monitor27 (0.60 m wide at 0.7 m), maxSeparation 0.03, no crop, 8 x 1: depth 0.9 at the left edge is a
  // crossed 4 mm run touching the edge (window violation, 20 arcmin); depth 3 gives 24 mm uncrossed
  // (117 arcmin, beyond 1 degree), infinity 36 mm (beyond too). Depth 1 is the screen plane: unmarked.
  FrameImages frame;
  frame.eyes.left = ImageRGBA8(8, 1, 200);
  frame.eyes.right = ImageRGBA8(8, 1, 60);
  frame.stereoDepth = DepthImage(8, 1, 1.0f);
  frame.stereoDepth.pixels[0] = 0.9f;
  frame.stereoDepth.pixels[3] = 3.0f;
  frame.stereoDepth.pixels[5] = INFINITY;
  frame.parameters = {0.03f, 1.0f, 0.0f};
  frame.display = comfort::builtInDisplayProfile("monitor27");
  const ImageRGBA8 anaglyph = composeView(ViewMode::Anaglyph, frame);
  const ImageRGBA8 overlay = composeView(ViewMode::ComfortOverlay, frame);
  auto marked = [&](std::uint32_t x, const std::array<int, 3>& color) {
    std::vector<int> expected;
    for (std::size_t c = 0; c < 3; ++c) expected.push_back((int(anaglyph.at(x, 0)[c]) + color[c] + 1) / 2);
    return expected;
  };
  auto rgb = [&](std::uint32_t x) { return std::vector<int>(overlay.at(x, 0), overlay.at(x, 0) + 3); };
  EXPECT_EQ(rgb(0), marked(0, comfort::kWindowViolationColor));
  EXPECT_EQ(rgb(3), marked(3, comfort::kBeyondLimitColor));
  EXPECT_EQ(rgb(5), marked(5, comfort::kBeyondLimitColor));
  for (std::uint32_t x : {1u, 2u, 4u, 6u, 7u}) EXPECT_EQ(rgb(x), std::vector<int>(anaglyph.at(x, 0), anaglyph.at(x, 0) + 3)) << x;
}

TEST(TuneViews, ViewsShowTheEyesWithTheHudButTheErrorHeatMapMeasuresWithout) {
  FrameImages frame = syntheticFrame();
  frame.reference = frame.eyes;
  frame.eyesWithHud = frame.eyes;
  frame.eyesWithHud->left.at(4, 3)[0] = 255;  // a HUD pixel in the left eye only
  EXPECT_EQ(composeView(ViewMode::Left, frame).pixels, frame.eyesWithHud->left.pixels);
  const ImageRGBA8 heat = composeView(ViewMode::ErrorHeatMap, frame);
  for (std::size_t i = 0; i < heat.pixels.size(); i += 4) EXPECT_EQ(heat.pixels[i], 0) << i;
}

TEST(TuneViews, SideBySideViewKeepsTheEyeSize) {
  const FrameImages frame = syntheticFrame();
  const ImageRGBA8 view = composeView(ViewMode::SideBySide, frame);
  EXPECT_EQ(view.width, 8u);
  EXPECT_EQ(view.height, 6u);
  EXPECT_EQ(view.at(0, 0)[0], 200);  // left half: the left eye
  EXPECT_EQ(view.at(7, 0)[0], 60);
}

TEST(TuneViews, ReferenceViewsNeedTheReferenceEyes) {
  FrameImages frame = syntheticFrame();
  EXPECT_NE(errorOf([&] { (void)composeView(ViewMode::ErrorHeatMap, frame); }).find("reference"), std::string::npos);
  frame.reference = frame.eyes;  // identical eyes: no error anywhere
  const ImageRGBA8 heat = composeView(ViewMode::ErrorHeatMap, frame);
  for (std::size_t i = 0; i < heat.pixels.size(); i += 4) EXPECT_EQ(heat.pixels[i], 0) << i;
  EXPECT_TRUE(viewNeedsReference(ViewMode::Reference) && viewNeedsReference(ViewMode::ErrorHeatMap));
  EXPECT_FALSE(viewNeedsReference(ViewMode::Anaglyph));
}

class TuneSessionTest : public test::VulkanTest {};

TEST_F(TuneSessionTest, AnaglyphOfTheFirstFrameEqualsTheOffscreenRender) {
  // Same scene, frame, parameters and size as `s3d render`: the same renderer, stereo pass and HUD, so the
  // images must match exactly.
  app::RenderJobOptions options;
  options.width = 64;
  options.height = 48;
  options.outputs = {"anaglyph.png"};
  options.stereo.edgeCrop = options.stereo.maxSeparation;  // s3d tune crops the edges (it has no guard band)
  options.outputFolder = scratchFolder("offscreen");
  (void)app::runRenderJob(context(), options);
  const ImageRGBA8 offscreen = io::readPng(options.outputFolder / "anaglyph.png");
  fs::remove_all(options.outputFolder);

  TuneSession session(context(), 64, 48);
  TuneState state;
  state.reference = false;
  session.loadScene(state);
  const TuneFrame frame = session.renderFrame(state, {}, 0.0f);
  ASSERT_EQ(frame.view.width, 64u);
  EXPECT_EQ(frame.view.pixels, offscreen.pixels);
  EXPECT_FALSE(frame.numbers.errorLeft.has_value());
}

TEST_F(TuneSessionTest, AllowingNegativeParallaxMatchesTheOffscreenRenderThatAllowsIt) {
  // The cover scene at its wall (frame 23): the no-negative-parallax rules change the frame there.
  app::RenderJobOptions options;
  options.width = 48;
  options.height = 32;
  options.scene = "cover";
  options.frame = 23;
  options.allowNegativeParallax = true;
  options.outputs = {"left.png"};
  options.stereo.edgeCrop = options.stereo.maxSeparation;  // s3d tune crops the edges (it has no guard band)
  options.outputFolder = scratchFolder("offscreen_negative");
  const app::RenderReport report = app::runRenderJob(context(), options);
  const ImageRGBA8 offscreen = io::readPng(options.outputFolder / "left.png");
  fs::remove_all(options.outputFolder);

  TuneSession session(context(), 48, 32);
  TuneState state;
  state.scene = "cover";
  state.reference = false;
  state.view = ViewMode::Left;
  session.loadScene(state);
  session.setPathFrame(state, 23);
  setParameter(state.settings, "allowNegativeParallax", "on");
  const TuneFrame frame = session.renderFrame(state, {}, 0.0f);
  EXPECT_EQ(frame.view.pixels, offscreen.pixels);
  EXPECT_FALSE(frame.numbers.zeroParallaxLimited);
  EXPECT_GT(frame.numbers.comfort.parallax.shareNegative, 0.0);  // what the rules would have prevented
  EXPECT_EQ(frame.numbers.comfort.windowViolationPixels, report.comfort.windowViolationPixels);
  EXPECT_EQ(frame.numbers.hudConflictPixels, report.hudConflictPixels);
}

TEST_F(TuneSessionTest, ReferenceNumbersAndTheComfortControlRunWhenAskedFor) {
  TuneSession session(context(), 48, 32);
  TuneState state;
  state.scene = "cover";
  session.loadScene(state);
  session.setPathFrame(state, 23);  // at the wall: the control pulls the screen plane in
  setParameter(state.settings, "zppControl", "on");
  state.view = ViewMode::ErrorHeatMap;
  const TuneFrame frame = session.renderFrame(state, {}, 1.0f);
  ASSERT_TRUE(frame.numbers.errorLeft.has_value());
  EXPECT_GT(frame.numbers.errorLeft->psnrDb, 15.0);  // a sanity floor: the eyes match their references roughly
  ASSERT_TRUE(frame.numbers.nearestSurface.has_value());
  EXPECT_LT(frame.numbers.zeroParallaxDistance, state.settings.profile.stereo.zeroParallaxDistance);
  EXPECT_EQ(frame.view.width, 48u);
}

TEST_F(TuneSessionTest, TheDisparityBudgetFitsEveryPixelAndIsShown) {
  TuneSession session(context(), 48, 32);
  TuneState state;
  state.settings.profile.display = comfort::builtInDisplayProfile("monitor27");
  state.disparityBudget = comfort::DisparityBudgetRule::OneDegree;
  session.loadScene(state);
  const TuneFrame frame = session.renderFrame(state, {}, 1.0f / 30.0f);
  EXPECT_EQ(frame.numbers.comfort.parallax.shareBeyondOneDegree, 0.0);
  EXPECT_EQ(frame.numbers.budget.rule, comfort::DisparityBudgetRule::OneDegree);
  EXPECT_EQ(frame.numbers.maxSeparation, frame.numbers.budget.choice.parameters.maxSeparation);
  EXPECT_GE(frame.numbers.budget.choice.usedShare, 0.8);
}

TEST_F(TuneSessionTest, ScriptCommandsSwitchSceneFrameViewAndRoundTripAProfile) {
  TuneSession session(context(), 32, 24);
  TuneState state;
  session.loadScene(state);
  const fs::path profile = scratchFolder("script_profile") / "p.json";
  WindowRequests requests;
  for (const ScriptCommand& command :
       parseScript("scene cover\nframe 20\nview parallax\nset maxSeparation 0.04\nsave-profile " + profile.string() +
                   "\nset maxSeparation 0.01\nload-profile " + profile.string() + "\nscreenshot s.png\nquit\n"))
    runScriptCommand(session, state, command, requests);
  EXPECT_EQ(state.scene, "cover");
  EXPECT_EQ(state.pathFrame, 20u);
  EXPECT_EQ(state.camera.position, renderer::cameraForFrame(renderer::makeBuiltInScene("cover"), 20).position);
  EXPECT_EQ(state.view, ViewMode::ParallaxHeatMap);
  EXPECT_FLOAT_EQ(state.settings.profile.stereo.maxSeparation, 0.04f);  // the saved value, loaded back
  EXPECT_EQ(requests.screenshot, fs::path("s.png"));
  EXPECT_TRUE(requests.quit);
  fs::remove_all(profile.parent_path());
}

TEST_F(TuneSessionTest, PlayingFollowsTheCameraPathAndWrapsAround) {
  TuneSession session(context(), 16, 16);
  TuneState state;
  state.reference = false;
  session.loadScene(state);
  const renderer::Scene scene = renderer::makeBuiltInScene(state.scene);
  session.setPathFrame(state, scene.cameraPath.size() - 1);
  state.playPath = true;
  FrameInput walk;
  walk.forward = true;  // ignored while playing
  (void)session.renderFrame(state, walk, 1.0f);
  EXPECT_EQ(state.camera.position, scene.cameraPath.back().position);
  EXPECT_EQ(state.pathFrame, 0u);
  (void)session.renderFrame(state, walk, 1.0f);
  EXPECT_EQ(state.camera.position, scene.cameraPath.front().position);
  EXPECT_EQ(state.pathFrame, 1u);
}

TEST_F(TuneSessionTest, AZeroParallaxPlaneBeyondTheFarPlaneIsClampedWithAWarningAsInSRender) {
  TuneSession session(context(), 16, 16);
  TuneState state;
  state.reference = false;
  session.loadScene(state);
  setParameter(state.settings, "zeroParallaxDistance", "5000");  // the scenes' far plane is 1000 m
  // Negative parallax allowed: otherwise the plane is then held at the frame's nearest depth, as in `s3d render`.
  setParameter(state.settings, "allowNegativeParallax", "on");
  const TuneFrame frame = session.renderFrame(state, {}, 0.0f);
  EXPECT_FLOAT_EQ(frame.numbers.zeroParallaxDistance, stereo::kMaxZppFractionOfFar * state.camera.farPlane);
  ASSERT_TRUE(frame.numbers.warning.has_value());
}

TEST_F(TuneSessionTest, AFailingScriptCommandNamesItsLine) {
  TuneSession session(context(), 32, 24);
  TuneState state;
  session.loadScene(state);
  WindowRequests requests;
  const std::vector<ScriptCommand> commands = parseScript("view left\nset zeroParallaxDistance 0\n");
  runScriptCommand(session, state, commands[0], requests);
  const std::string message = errorOf([&] { runScriptCommand(session, state, commands[1], requests); });
  EXPECT_EQ(message.rfind("script line 2 (set): zeroParallaxDistance", 0), 0u) << message;
}

}  // namespace
}  // namespace s3d::tune
