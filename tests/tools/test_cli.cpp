// The s3d tool as a user or a script meets it: help that states the defaults a run uses, the version, the
// memory estimate, eyes that are the center view at zero separation for every method, outputs that a planted
// link or folder cannot redirect, and a folder conversion that resumes. Its own binary, since every test runs
// the tool (S3D_TOOL) as a process.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/bench_job.h"
#include "s3d/app/convert_job.h"
#include "s3d/app/render_job.h"
#include "s3d/io/depth_io.h"
#include "s3d/io/image_io.h"
#include "s3d/stereo/stereo.h"
#include "s3d/tune/tune_state.h"

namespace s3d {
// The memory estimate is of the images a run holds; under AddressSanitizer the process holds far more.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitizedBuild = true;
#else
constexpr bool kSanitizedBuild = false;
#endif
#else
constexpr bool kSanitizedBuild = false;
#endif

namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

struct ToolRun {
  int status = -1;
  std::string out, err;
  double seconds = 0.0;
};

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("s3d_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
               std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }

  // `s3d ARGUMENTS` with stdout and stderr captured (arguments are passed to the shell as written).
  ToolRun run(const std::string& arguments) const {
    const fs::path out = folder_ / "stdout.txt", err = folder_ / "stderr.txt";
    // S3D_TOOL in the environment runs another build of the tool (e.g. an older one, to see a test fail).
    const char* tool = std::getenv("S3D_TOOL") ? std::getenv("S3D_TOOL") : S3D_TOOL;
    const std::string command = std::string("'") + tool + "' " + arguments + " >'" + out.string() + "' 2>'" +
                                err.string() + "'";
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    ToolRun result;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = readText(out);
    result.err = readText(err);
    return result;
  }

  // The default CLI11 prints for `option` in `help` ("--taps INT:INT in [1 - 16]=4" gives "4").
  static std::string helpDefault(const std::string& help, const std::string& option) {
    std::smatch match;
    if (!std::regex_search(help, match, std::regex("\\n\\s*" + option + " [^\\n]*?=([^ \\n]+)"))) return "<none>";
    return match[1];
  }

  fs::path folder_;
};

TEST_F(Cli, HelpDefaultsEqualTheLibrarysParameterStructs) {
  const stereo::StereoParameters stereo;
  const app::RenderJobOptions render;
  const app::ConvertJobOptions convert;
  const app::BenchOptions bench;
  const tune::TuneState tune;
  auto number = [](const std::string& text) { return std::stof(text); };

  const std::string renderHelp = run("render --help").out;
  EXPECT_EQ(helpDefault(renderHelp, "--method"), stereo::methodName(stereo.method));
  EXPECT_EQ(number(helpDefault(renderHelp, "--max-separation")), stereo.maxSeparation);
  EXPECT_EQ(number(helpDefault(renderHelp, "--zero-parallax-distance")), stereo.zeroParallaxDistance);
  EXPECT_EQ(number(helpDefault(renderHelp, "--taps")), float(stereo.searchTaps));
  EXPECT_EQ(number(helpDefault(renderHelp, "--iterations")), float(stereo.iterations));
  EXPECT_EQ(number(helpDefault(renderHelp, "--weapon-depth-offset")), stereo.weaponDepthOffset);
  EXPECT_EQ(number(helpDefault(renderHelp, "--weapon-depth-scale")), stereo.weaponDepthScale);
  EXPECT_EQ(number(helpDefault(renderHelp, "--width")), float(render.width));
  EXPECT_EQ(number(helpDefault(renderHelp, "--height")), float(render.height));
  EXPECT_EQ(number(helpDefault(renderHelp, "--supersample")), float(render.supersample));
  EXPECT_EQ(helpDefault(renderHelp, "--scene"), render.scene);
  EXPECT_EQ(helpDefault(renderHelp, "--hud"), app::hudModeName(render.hud));
  EXPECT_EQ(number(helpDefault(renderHelp, "--frames-per-second")), render.framesPerSecond);

  // convert's default is auto (forward for depth from files, stereo::automaticMethod); the rest is shared.
  const std::string convertHelp = run("convert --help").out;
  EXPECT_EQ(helpDefault(convertHelp, "--method"), "auto");
  EXPECT_EQ(number(helpDefault(convertHelp, "--max-separation")), stereo.maxSeparation);
  EXPECT_EQ(number(helpDefault(convertHelp, "--zero-parallax-distance")), stereo.zeroParallaxDistance);
  EXPECT_EQ(number(helpDefault(convertHelp, "--taps")), float(stereo.searchTaps));
  EXPECT_EQ(helpDefault(convertHelp, "--depth-channel"), convert.depthChannel);
  EXPECT_EQ(number(helpDefault(convertHelp, "--depth-scale")), convert.depthScale);

  const std::string tuneHelp = run("tune --help").out;
  EXPECT_EQ(helpDefault(tuneHelp, "--method"), stereo::methodName(stereo.method));
  EXPECT_EQ(number(helpDefault(tuneHelp, "--max-separation")), stereo.maxSeparation);
  EXPECT_EQ(number(helpDefault(tuneHelp, "--taps")), float(stereo.searchTaps));
  EXPECT_EQ(number(helpDefault(tuneHelp, "--supersample")), float(tune.supersample));
  EXPECT_EQ(helpDefault(tuneHelp, "--hud"), app::hudModeName(tune.hud));

  const std::string benchHelp = run("bench --help").out;
  EXPECT_EQ(number(helpDefault(benchHelp, "--repeat")), float(bench.repeat));
  EXPECT_EQ(number(helpDefault(benchHelp, "--supersample")), float(bench.supersample));
  EXPECT_NE(benchHelp.find(stereo::kernelName(stereo.kernel)), std::string::npos);  // the kernel a run uses
  EXPECT_EQ(benchHelp.find("default: row tiles"), std::string::npos);

  for (const std::string& help : {renderHelp, convertHelp, tuneHelp, benchHelp, run("regress --help").out})
    EXPECT_EQ(help.find("issue #"), std::string::npos) << help;
}

TEST_F(Cli, VersionIsTheProjectVersion) {
  const ToolRun result = run("--version");
  EXPECT_EQ(result.status, 0);
  EXPECT_EQ(result.out, std::string("s3d ") + S3D_PROJECT_VERSION + "\n");
}

TEST_F(Cli, ATooLargeResolutionFailsInUnderASecondNamingTheEstimateAndTheLimit) {
  const fs::path output = folder_ / "out";
  const ToolRun result = run("render --resolution 16384x16384 --memory-limit 4GiB --output '" + output.string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_LT(result.seconds, 1.0);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  for (const char* part : {"s3d: error: 16384x16384", "needs an estimated ", " GiB of memory, more than the 4.0 GiB",
                           "--memory-limit", "lower --resolution or --supersample"})
    EXPECT_NE(result.err.find(part), std::string::npos) << part << " in " << result.err;
  EXPECT_FALSE(fs::exists(output));
}

TEST_F(Cli, TheEstimateInReportJsonIsAtLeastThePeakResidentMemory) {
  if (kSanitizedBuild) GTEST_SKIP() << "AddressSanitizer's shadow memory and redzones inflate the peak resident memory";
  const fs::path output = folder_ / "out";
  ASSERT_EQ(run("render --resolution 320x180 --outputs report.json --output '" + output.string() + "'").status, 0);
  const nlohmann::json memory = nlohmann::json::parse(readText(output / "report.json"))["memory"];
  EXPECT_GE(memory["estimatedBytes"].get<std::uint64_t>(), memory["peakResidentBytes"].get<std::uint64_t>()) << memory;
  EXPECT_GT(memory["peakResidentBytes"].get<std::uint64_t>(), 0u);
}

// --hybrid-cell and --hybrid-score-floor reach the hybrid's classification: the report names the cell given (the
// width alone would choose 1 at 320 columns) and masks fewer pixels under a higher floor.
TEST_F(Cli, TheHybridCellAndScoreFloorOptionsReachTheClassification) {
  auto hybridReport = [&](const std::string& options, const std::string& name) {
    const fs::path output = folder_ / name;
    EXPECT_EQ(run("render --method hybrid --hybrid-budget 0.5 --resolution 320x180 --disparity-budget off --outputs "
                  "report.json " + options + " --output '" + output.string() + "'")
                  .status,
              0);
    return nlohmann::json::parse(readText(output / "report.json"))["hybrid"];
  };
  const nlohmann::json defaults = hybridReport("", "defaults");
  const nlohmann::json cells = hybridReport("--hybrid-cell 2", "cells");
  const nlohmann::json floor = hybridReport("--hybrid-score-floor 4", "floor");
  EXPECT_EQ(defaults["cell"], 1);
  EXPECT_EQ(cells["cell"], 2);
  EXPECT_LT(floor["left"]["maskedPixels"].get<std::uint64_t>(), defaults["left"]["maskedPixels"].get<std::uint64_t>());
}

// The hybrid method's second renderer and masks are in the estimate too.
TEST_F(Cli, TheHybridEstimateInReportJsonIsAtLeastThePeakResidentMemory) {
  if (kSanitizedBuild) GTEST_SKIP() << "AddressSanitizer's shadow memory and redzones inflate the peak resident memory";
  const fs::path output = folder_ / "out";
  ASSERT_EQ(run("render --method hybrid --resolution 320x180 --outputs report.json --output '" + output.string() + "'")
                .status,
            0);
  const nlohmann::json memory = nlohmann::json::parse(readText(output / "report.json"))["memory"];
  EXPECT_GE(memory["estimatedBytes"].get<std::uint64_t>(), memory["peakResidentBytes"].get<std::uint64_t>()) << memory;
}

// A nonlinear map's per-layer reference (up to 7 renderings per eye held at once) is in the estimate too. At
// 960x540 the linear mapping's estimate (324 MiB) is below the nonlinear run's peak (353 MiB on lavapipe).
TEST_F(Cli, TheNonlinearMappingsEstimateInReportJsonIsAtLeastThePeakResidentMemory) {
  if (kSanitizedBuild) GTEST_SKIP() << "AddressSanitizer's shadow memory and redzones inflate the peak resident memory";
  const fs::path output = folder_ / "out";
  ASSERT_EQ(run("render --disparity-mapping nonlinear --resolution 960x540 --outputs report.json --output '" +
                output.string() + "'")
                .status,
            0);
  const nlohmann::json report = nlohmann::json::parse(readText(output / "report.json"));
  EXPECT_GT(report["disparityMapping"]["referenceLayers"].get<int>(), 1);
  const nlohmann::json& memory = report["memory"];
  EXPECT_GE(memory["estimatedBytes"].get<std::uint64_t>(), memory["peakResidentBytes"].get<std::uint64_t>()) << memory;
}

// Zero separation moves nothing: every method's eyes are the center view byte for byte, HUD included (the HUD
// fades by the weapon mask the eyes carry in alpha, as the center view's does).
TEST_F(Cli, ZeroSeparationEyesAreTheCenterViewForEveryMethodHudIncluded) {
  for (const char* method : {"seed", "search", "iterative", "forward", "hybrid"}) {
    const fs::path output = folder_ / method;
    const ToolRun result = run(std::string("render --method ") + method +
                               " --max-separation 0 --disparity-budget off --resolution 128x72 "
                               "--outputs center.png,left.png,right.png --output '" + output.string() + "'");
    ASSERT_EQ(result.status, 0) << method << ": " << result.err;
    const ImageRGBA8 center = io::readPng(output / "center.png");
    EXPECT_EQ(io::readPng(output / "left.png").pixels, center.pixels) << method;
    EXPECT_EQ(io::readPng(output / "right.png").pixels, center.pixels) << method;
  }
}

TEST_F(Cli, TheIterativeMethodFadesTheHudBehindTheWeaponAsTheSearchDoes) {
  std::array<std::uint64_t, 2> faded{};
  for (int i = 0; i < 2; ++i) {
    const fs::path output = folder_ / (i == 0 ? "search" : "iterative");
    ASSERT_EQ(run(std::string("render --method ") + (i == 0 ? "search" : "iterative") +
                  " --disparity-budget off --resolution 320x180 --outputs report.json --output '" + output.string() + "'")
                  .status,
              0);
    const nlohmann::json report = nlohmann::json::parse(readText(output / "report.json"));
    for (const nlohmann::json& element : report["hud"])
      if (element["name"] == "ammo") faded[std::size_t(i)] = element["fadedPixels"]["left"].get<std::uint64_t>();
  }
  // With the budget off (the parameters of the library's own HUD test) the weapon covers the ammo panel.
  ASSERT_GT(faded[0], 0u) << "the weapon no longer covers the ammo panel on courtyard frame 0";
  // The weapon's edges land a pixel apart between the methods, so the counts agree only roughly (within 20 %).
  EXPECT_NEAR(double(faded[1]), double(faded[0]), 0.2 * double(faded[0]));
}

TEST_F(Cli, LinksPlantedAtOutputNamesAreReplacedNeverWrittenThrough) {
  const fs::path output = folder_ / "out", victim = folder_ / "victim.txt";
  fs::create_directories(output);
  std::ofstream(victim) << "precious";
  for (const char* name : {"left.png", "report.json"}) fs::create_symlink(victim, output / name);
  const ToolRun result =
      run("render --resolution 32x18 --outputs left.png,report.json --output '" + output.string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(readText(victim), "precious");
  for (const char* name : {"left.png", "report.json"}) {
    EXPECT_FALSE(fs::is_symlink(output / name)) << name;
    EXPECT_TRUE(fs::is_regular_file(output / name)) << name;
  }
  for (const auto& entry : fs::directory_iterator(output))  // no staging folder or temporary file is left
    EXPECT_TRUE(entry.path().filename() == "left.png" || entry.path().filename() == "report.json") << entry.path();
}

TEST_F(Cli, AFolderAtAnOutputNameFailsBeforeRenderingAndChangesNothing) {
  const fs::path output = folder_ / "out";
  fs::create_directories(output / "right.png");
  std::ofstream(output / "left.png") << "old";
  const ToolRun result = run("render --resolution 32x18 --output '" + output.string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("right.png' is a folder"), std::string::npos) << result.err;
  EXPECT_EQ(readText(output / "left.png"), "old");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(output)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"left.png", "right.png"}));
}

TEST_F(Cli, AFolderRunWithResumeKeepsTheFramesItFinishedAndGoesOnFromThere) {
  const fs::path input = folder_ / "in", output = folder_ / "out";
  fs::create_directories(input);
  const ImageRGBA8 color(24, 8, 128);
  const io::PfmImage depth{24, 8, 1, std::vector<float>(24 * 8, 2.0f)};
  for (const char* key : {"a", "b"}) io::writePng(input / ("color_" + std::string(key) + ".png"), color);
  io::writePfm(input / "depth_a.pfm", depth);
  std::ofstream(input / "depth_b.pfm") << "Pf\n24 8\n-1\ntruncated";
  const std::string arguments = "convert --input-folder '" + input.string() +
                                "' --color-pattern 'color_*.png' --depth-pattern 'depth_*.pfm' --resume --output '" +
                                output.string() + "'";
  const ToolRun failed = run(arguments);
  EXPECT_EQ(failed.status, 1);
  EXPECT_NE(failed.err.find("frame 'b'"), std::string::npos) << failed.err;
  EXPECT_NE(failed.err.find("1 of 2 frames are in the output folder"), std::string::npos) << failed.err;
  nlohmann::json manifest = nlohmann::json::parse(readText(output / "report.json"));
  EXPECT_FALSE(manifest["complete"].get<bool>());
  ASSERT_EQ(manifest["frames"].size(), 1u);
  EXPECT_EQ(manifest["frames"][0]["frame"], "a");
  EXPECT_TRUE(fs::exists(output / "left_a.png"));
  EXPECT_FALSE(fs::exists(output / "left_b.png"));
  const auto firstWrite = fs::last_write_time(output / "left_a.png");

  io::writePfm(input / "depth_b.pfm", depth);  // fixed
  const ToolRun resumed = run(arguments);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("kept 1 converted earlier"), std::string::npos) << resumed.out;
  EXPECT_EQ(fs::last_write_time(output / "left_a.png"), firstWrite);  // frame a was not converted again
  manifest = nlohmann::json::parse(readText(output / "report.json"));
  EXPECT_TRUE(manifest["complete"].get<bool>());
  ASSERT_EQ(manifest["frames"].size(), 2u);
  EXPECT_EQ(manifest["frames"][1]["frame"], "b");
  EXPECT_TRUE(fs::exists(output / "tab_b.png"));

  // Other settings cannot resume: the kept frames would not match the new ones.
  const ToolRun changed = run(arguments + " --method seed");
  EXPECT_EQ(changed.status, 1);
  EXPECT_NE(changed.err.find("other settings"), std::string::npos) << changed.err;
}

TEST_F(Cli, RenderRefusesAnOutputThatIsATextureOfItsOwnScene) {
  // The scene's folder as the output folder, with the base color texture named like an output.
  const fs::path data = S3D_TEST_DATA_DIR;
  for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_normal.png"})
    fs::copy_file(data / name, folder_ / name);
  fs::copy_file(data / "textured_quad_base_color.png", folder_ / "center.png");
  std::string gltf = readText(folder_ / "textured_quad.gltf");
  gltf.replace(gltf.find("textured_quad_base_color.png"), std::string("textured_quad_base_color.png").size(), "center.png");
  std::ofstream(folder_ / "textured_quad.gltf", std::ios::binary) << gltf;
  const std::string before = readText(folder_ / "center.png");
  const ToolRun result = run("render --resolution 32x18 --scene '" + (folder_ / "textured_quad.gltf").string() +
                             "' --output '" + folder_.string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("center.png' would overwrite input"), std::string::npos) << result.err;
  EXPECT_EQ(readText(folder_ / "center.png"), before);
}

TEST_F(Cli, TheHudIsLeftOutOnRequestAndByDefaultOnAGltfScene) {
  auto hudElements = [&](const std::string& arguments) {
    const fs::path output = folder_ / "out";
    fs::remove_all(output);
    const ToolRun result = run("render --resolution 64x36 --outputs report.json --output '" + output.string() + "' " +
                               arguments);
    EXPECT_EQ(result.status, 0) << arguments << ": " << result.err;
    return nlohmann::json::parse(readText(output / "report.json"))["hud"].size();
  };
  EXPECT_EQ(hudElements(""), 3u);  // health, ammo, crosshair on a built-in scene
  EXPECT_EQ(hudElements("--hud none"), 0u);
  const std::string gltf = std::string(S3D_TEST_DATA_DIR) + "/textured_quad.gltf";
  EXPECT_EQ(hudElements("--scene '" + gltf + "'"), 0u);
  EXPECT_EQ(hudElements("--scene '" + gltf + "' --hud game"), 3u);
}

TEST_F(Cli, AFrameRateOfZeroIsRefusedNamingTheOption) {
  const ToolRun result = run("render --resolution 64x36 --frames-per-second 0 --output '" + (folder_ / "out").string() + "'");
  EXPECT_NE(result.status, 0);
  EXPECT_NE(result.err.find("--frames-per-second"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(folder_ / "out"));
}

// Every file a run writes is checked against every file it reads, --save-profile included, before anything is
// written: naming the scene must refuse the run and keep the scene byte for byte.
TEST_F(Cli, SaveProfileNamingTheSceneIsRefusedAndTheSceneKept) {
  const fs::path data = S3D_TEST_DATA_DIR;
  for (const char* name : {"textured_quad.gltf", "textured_quad.bin", "textured_quad_base_color.png",
                           "textured_quad_normal.png"})
    fs::copy_file(data / name, folder_ / name);
  const fs::path scene = folder_ / "textured_quad.gltf";
  const std::string before = readText(scene);
  const ToolRun result = run("render --resolution 32x18 --scene '" + scene.string() + "' --save-profile '" +
                             scene.string() + "' --output '" + (folder_ / "out").string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("textured_quad.gltf' (--scene); choose another --save-profile"), std::string::npos)
      << result.err;
  EXPECT_EQ(readText(scene), before);
  EXPECT_FALSE(fs::exists(folder_ / "out"));
}

TEST_F(Cli, SaveProfileNamingTheDisplayFileIsRefusedAndTheDisplayKept) {
  const fs::path display = folder_ / "studio.json";
  const std::string text = R"({"name": "studio", "screenWidthMeters": 2.5, "viewingDistanceMeters": 3.0})";
  std::ofstream(display) << text;
  const ToolRun result = run("render --resolution 32x18 --display '" + display.string() + "' --save-profile '" +
                             display.string() + "' --output '" + (folder_ / "out").string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("studio.json' (--display); choose another --save-profile"), std::string::npos) << result.err;
  EXPECT_EQ(readText(display), text);
}

// A run that fails writes no profile: --save-profile is written only after the outputs are committed.
TEST_F(Cli, AFailedRunWritesNoProfile) {
  const fs::path output = folder_ / "out", profile = folder_ / "profile.json";
  fs::create_directories(output / "right.png");  // a folder where an output goes: the run fails
  const ToolRun failed = run("render --resolution 32x18 --save-profile '" + profile.string() + "' --output '" +
                             output.string() + "'");
  EXPECT_EQ(failed.status, 1);
  EXPECT_FALSE(fs::exists(profile));
  const ToolRun succeeded = run("render --resolution 32x18 --outputs left.png --save-profile '" + profile.string() +
                                "' --output '" + output.string() + "'");
  ASSERT_EQ(succeeded.status, 0) << succeeded.err;
  EXPECT_TRUE(fs::is_regular_file(profile));
}

// --results-md rewrites a file in place: only a Markdown file that is empty or marked as an s3d results file.
TEST_F(Cli, ResultsMarkdownThatIsNotAMarkdownFileIsRefusedAndKept) {
  const fs::path image = folder_ / "picture.png";
  std::ofstream(image) << "not really a PNG";
  const ToolRun result = run("bench --results-md '" + image.string() + "' --output '" + (folder_ / "out").string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("--results-md '" + image.string() + "' is not a Markdown file (.md)"), std::string::npos)
      << result.err;
  EXPECT_EQ(readText(image), "not really a PNG");
}

TEST_F(Cli, ResultsMarkdownWithoutTheResultsMarkerIsRefusedAndKept) {
  const fs::path notes = folder_ / "notes.md";
  std::ofstream(notes) << "# My notes\n";
  const ToolRun result = run("bench --results-md '" + notes.string() + "' --output '" + (folder_ / "out").string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("is not an s3d results file"), std::string::npos) << result.err;
  EXPECT_EQ(readText(notes), "# My notes\n");
}

TEST_F(Cli, ResultsMarkdownThatIsAlsoABenchOutputIsRefused) {
  const fs::path output = folder_ / "out";
  fs::create_directories(output);
  std::ofstream(output / "bench.md");  // empty: a results file the bench may start
  const ToolRun result = run("bench --results-md '" + (output / "bench.md").string() + "' --output '" + output.string() + "'");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("would overwrite output"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("choose another --results-md"), std::string::npos) << result.err;
}

TEST_F(Cli, AnEmptyResultsMarkdownFileIsMarkedAndGetsTheTables) {
  const fs::path results = folder_ / "RESULTS.md";
  std::ofstream{results};
  const ToolRun result = run("bench --resolution 32x18 --scenes courtyard --methods seed --separations 2 --repeat 1 "
                             "--results-md '" + results.string() + "' --output '" + (folder_ / "out").string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const std::string text = readText(results);
  EXPECT_EQ(text.rfind(std::string(app::kResultsFileMarker) + "\n", 0), 0u) << text;
  EXPECT_NE(text.find("<!-- s3d bench: "), std::string::npos) << text;
}

}  // namespace
}  // namespace s3d
