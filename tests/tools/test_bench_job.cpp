// `s3d bench` as a library: a tiny sweep end to end (rows, markdown, SVG, JSON, the marked section of a
// results file), the renderer timings, and option checks that happen before anything is written.
#include <gtest/gtest.h>

#include <unistd.h>  // getpid: keeps parallel test runs in separate folders

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/bench_job.h"
#include "s3d/io/image_io.h"
#include "vulkan_test.h"

namespace s3d::app {
namespace {
namespace fs = std::filesystem;

fs::path scratchPath(const std::string& name) {
  return fs::temp_directory_path() / ("s3d_bench_job_" + std::to_string(::getpid()) + "_" + name);
}

std::string readText(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// A results file with text around both devices' sections, so the test sees exactly what changes.
const std::string kResultsPrefix = "# Results\n\nHand-written text before.\n\n<!-- s3d bench: cpu begin -->\nold cpu table\n";
const std::string kResultsMiddle = "<!-- s3d bench: cpu end -->\n\nBetween.\n\n<!-- s3d bench: gpu begin -->\nold gpu table\n";
const std::string kResultsSuffix = "<!-- s3d bench: gpu end -->\n\nHand-written text after.\n";

BenchOptions tinySweepOptions(const fs::path& folder) {
  BenchOptions options;
  options.width = 96;
  options.height = 64;
  options.scenes = {"courtyard"};
  options.methods = {"seed", "iterative-2"};
  options.separationsPercent = {2.0};
  options.repeat = 1;
  options.outputFolder = folder;
  return options;
}

// The tiny sweep runs once per test binary (the suite stays fast); its files go at exit.
struct TinySweep {
  fs::path folder;
  fs::path results;
  std::string resultsBefore;
  BenchReport report;
  ~TinySweep() {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
    fs::remove(results, ignored);
  }
};

const TinySweep& tinySweep(vk::Context& context) {
  static const std::unique_ptr<TinySweep> sweep = [&] {
    auto result = std::make_unique<TinySweep>();
    result->folder = scratchPath("sweep");
    result->results = scratchPath("RESULTS.md");
    std::error_code ignored;
    fs::remove_all(result->folder, ignored);
    result->resultsBefore = kResultsPrefix + kResultsMiddle + kResultsSuffix;
    io::writeTextFile(result->results, result->resultsBefore);
    BenchOptions options = tinySweepOptions(result->folder);
    options.resultsMarkdown = result->results;
    result->report = runBench(context, options);
    return result;
  }();
  return *sweep;
}

class BenchJobTest : public test::VulkanTest {};

TEST_F(BenchJobTest, TinySweepHasOneRowPerSettingWithFiniteErrorAndPositiveTimes) {
  const BenchReport& report = tinySweep(context()).report;
  ASSERT_EQ(report.rows.size(), 2u);
  EXPECT_EQ(report.rows[0].setting.name(), "seed");
  EXPECT_EQ(report.rows[1].setting.name(), "iterative-2");
  const bool timestamps = context().timestampPeriodNs() > 0.0;
  for (const BenchRow& row : report.rows) {
    EXPECT_EQ(row.scene, "courtyard");
    EXPECT_FLOAT_EQ(row.maxSeparation, 0.02f);
    for (const stereo::EyeError* eye : {&row.left, &row.right})
      for (const stereo::ErrorStats* stats : {&eye->display, &eye->halo, &eye->rest, &eye->disocclusion})
        EXPECT_TRUE(std::isfinite(stats->psnrDb)) << row.setting.name();
    EXPECT_GT(row.left.display.pixelCount, 0u);
    if (!timestamps) continue;
    ASSERT_TRUE(row.stereoGpuMs && row.centerFrameGpuMs && row.referenceEyeGpuMs) << row.setting.name();
    EXPECT_GT(*row.stereoGpuMs, 0.0);
    EXPECT_GT(*row.centerFrameGpuMs, 0.0);
    EXPECT_GT(*row.referenceEyeGpuMs, 0.0);
    EXPECT_EQ(row.stereoGpuMsRuns.size(), 1u);  // repeat 1
  }
}

TEST_F(BenchJobTest, MarkdownHasARowPerSettingAndTheTargets) {
  const TinySweep& sweep = tinySweep(context());
  const std::string markdown = readText(sweep.folder / "bench.md");
  EXPECT_EQ(markdown, "# s3d bench\n\n" + benchMarkdown(sweep.report));
  EXPECT_NE(markdown.find("| seed | Listing 4.5 (3 taps) | 2 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| iterative | 2 iterations | 2 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("#### Targets"), std::string::npos);
  EXPECT_NE(markdown.find(sweep.report.deviceName), std::string::npos);  // the reader picks the bandwidth by it
}

// Tags balance (every opened element is closed in order) and the document is one <svg> element.
void expectWellFormedXml(const std::string& svg) {
  std::vector<std::string> open;
  std::size_t at = 0;
  while ((at = svg.find('<', at)) != std::string::npos) {
    const std::size_t end = svg.find('>', at);
    ASSERT_NE(end, std::string::npos) << "unterminated tag at " << at;
    const std::string tag = svg.substr(at + 1, end - at - 1);
    ASSERT_FALSE(tag.empty());
    if (tag.front() == '/') {
      ASSERT_FALSE(open.empty()) << "closing </" << tag << "> without an open element";
      EXPECT_EQ(open.back(), tag.substr(1)) << "at " << at;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find(' ')));
      if (at > 0) {
        EXPECT_NE(open.size(), 1u) << "a second top-level element at " << at;
      }
    }
    at = end + 1;
  }
  EXPECT_TRUE(open.empty()) << "unclosed <" << (open.empty() ? "" : open.back()) << ">";
}

TEST_F(BenchJobTest, SpeedAgainstErrorSvgIsWellFormedWithOneCirclePerRow) {
  const TinySweep& sweep = tinySweep(context());
  const std::string svg = readText(sweep.folder / "bench_speed_vs_error.svg");
  ASSERT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  expectWellFormedXml(svg);
  if (context().timestampPeriodNs() > 0.0) {
    EXPECT_EQ(occurrences(svg, "<circle"), sweep.report.rows.size());
  }
  EXPECT_NE(svg.find(">seed<"), std::string::npos);  // points are labelled with their setting
  EXPECT_NE(svg.find(">iterative-2<"), std::string::npos);
}

TEST_F(BenchJobTest, JsonHoldsEveryRowAndListsTheFiles) {
  const TinySweep& sweep = tinySweep(context());
  const nlohmann::json json = nlohmann::json::parse(readText(sweep.folder / "bench.json"));
  ASSERT_EQ(json.at("rows").size(), 2u);
  EXPECT_EQ(json.at("rows")[1].at("setting"), "iterative-2");
  EXPECT_EQ(json.at("rows")[1].at("iterations"), 2);
  EXPECT_TRUE(json.at("rows")[0].at("error").at("left").at("halo").at("psnrDb").is_number());
  EXPECT_EQ(json.at("deviceKind"), sweep.report.deviceKind);
  EXPECT_EQ(json.at("files"), nlohmann::json({"bench_speed_vs_error.svg", "bench_time_over_eye.svg", "bench.md", "bench.json",
                                               sweep.results.string()}));
}

TEST_F(BenchJobTest, ResultsFileChangesOnlyInsideItsDeviceSection) {
  const TinySweep& sweep = tinySweep(context());
  const std::string after = readText(sweep.results);
  const std::string section = benchMarkdown(sweep.report);
  const std::string cpuSection = "<!-- s3d bench: cpu begin -->\n";
  const std::string gpuSection = "<!-- s3d bench: gpu begin -->\n";
  const std::string expected =
      sweep.report.deviceKind == "cpu"
          ? "# Results\n\nHand-written text before.\n\n" + cpuSection + section + kResultsMiddle + kResultsSuffix
          : kResultsPrefix + kResultsMiddle.substr(0, kResultsMiddle.find(gpuSection)) + gpuSection + section + kResultsSuffix;
  EXPECT_EQ(after, expected);  // byte for byte: the rest of the file is untouched
}

TEST_F(BenchJobTest, RendererModeTimesEveryPassOfEachScene) {
  const fs::path folder = scratchPath("renderer");
  BenchOptions options;
  options.width = 64;
  options.height = 48;
  options.scenes = {"courtyard"};
  options.rendererOnly = true;
  options.repeat = 1;
  options.outputFolder = folder;
  const BenchReport report = runBench(context(), options);
  ASSERT_EQ(report.rendererRows.size(), 1u);
  EXPECT_TRUE(report.rows.empty());
  const RendererRow& row = report.rendererRows.front();
  EXPECT_EQ(row.scene, "courtyard");
  EXPECT_GT(row.triangles, 1000u);  // the courtyard's walls, pillars, fence and weapon
  ASSERT_FALSE(row.passes.empty());
  if (context().timestampPeriodNs() > 0.0) {
    ASSERT_TRUE(row.frameGpuMs);
    EXPECT_GT(*row.frameGpuMs, 0.0);
    ASSERT_TRUE(row.guardBandFrameGpuMs);
    EXPECT_GT(*row.guardBandFrameGpuMs, 0.0);
  }
  EXPECT_EQ(row.guardBandColumns, 3u);  // s3d render's band at the default 2 %: ceil(1.28) + 1
  // A CPU device's work also as process CPU time per frame (some milliseconds at least, even at 64x48).
  EXPECT_EQ(row.cpuTimePerFrameMs.has_value(), context().isCpuDevice());
  if (row.cpuTimePerFrameMs) {
    EXPECT_GT(*row.cpuTimePerFrameMs, 0.0);
  }
  const std::string markdown = readText(folder / "bench.md");
  EXPECT_NE(markdown.find("| courtyard | "), std::string::npos) << markdown;
  EXPECT_NE(markdown.find(row.passes.front().name), std::string::npos);
  EXPECT_FALSE(fs::exists(folder / "bench_speed_vs_error.svg"));  // no error to plot
  EXPECT_FALSE(fs::exists(folder / "bench_time_over_eye.svg"));
  std::error_code ignored;
  fs::remove_all(folder, ignored);
}

TEST_F(BenchJobTest, ASceneFileIsBenchedUnderItsNameWithItsFoliageRegion) {
  // tests/data/textured_quad.gltf with its material made a cut-out (alphaMode MASK): every drawn texel of the
  // quad is foliage, so both eyes have pixels there, and that scene's table gets the column.
  const fs::path folder = scratchPath("scene_file");
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  fs::create_directories(folder / "scene");
  for (const char* name : {"textured_quad.bin", "textured_quad_base_color.png", "textured_quad_normal.png"})
    fs::copy_file(fs::path(S3D_TEST_DATA_DIR) / name, folder / "scene" / name);
  std::string gltf = readText(fs::path(S3D_TEST_DATA_DIR) / "textured_quad.gltf");
  const std::string material = "\"name\": \"quadrants\",";
  gltf.replace(gltf.find(material), material.size(), material + " \"alphaMode\": \"MASK\",");
  io::writeTextFile(folder / "scene" / "textured_quad.gltf", gltf);
  BenchOptions options = tinySweepOptions(folder / "out");
  options.scenes = {(folder / "scene" / "textured_quad.gltf").string()};
  options.methods = {"seed"};
  const BenchReport report = runBench(context(), options);
  ASSERT_EQ(report.rows.size(), 1u);
  EXPECT_EQ(report.rows[0].scene, "textured_quad");
  EXPECT_GT(report.rows[0].left.foliage.pixelCount, 0u);
  EXPECT_GT(report.rows[0].right.foliage.pixelCount, 0u);
  EXPECT_NE(readText(folder / "out" / "bench.md").find(" foliage |"), std::string::npos);
  EXPECT_EQ(readText(tinySweep(context()).folder / "bench.md").find(" foliage |"), std::string::npos)
      << "the courtyard has no cut-outs";
  fs::remove_all(folder, ignored);
}

// Each bad option throws std::invalid_argument naming the problem, before any file or folder exists.
void expectRejectedBeforeWriting(vk::Context& context, BenchOptions options, const std::string& expectedInMessage) {
  ASSERT_FALSE(fs::exists(options.outputFolder));
  try {
    (void)runBench(context, options);
    ADD_FAILURE() << "accepted options that should fail with '" << expectedInMessage << "'";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(expectedInMessage), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(options.outputFolder));
}

TEST_F(BenchJobTest, UnknownSceneIsRejectedBeforeAnyFileIsWritten) {
  BenchOptions options = tinySweepOptions(scratchPath("bad_scene"));
  options.scenes = {"courtyard", "atlantis"};
  expectRejectedBeforeWriting(context(), options, "atlantis");
}

TEST_F(BenchJobTest, UnknownMethodSettingIsRejectedBeforeAnyFileIsWritten) {
  BenchOptions options = tinySweepOptions(scratchPath("bad_method"));
  options.methods = {"seed", "raymarch-3"};
  expectRejectedBeforeWriting(context(), options, "unknown method setting 'raymarch-3'");
  options.methods = {"search-17"};  // beyond S3D_STEREO_MAX_TAPS
  expectRejectedBeforeWriting(context(), options, "unknown method setting 'search-17'");
}

TEST_F(BenchJobTest, SeparationZeroOrBeyondTheLimitIsRejectedBeforeAnyFileIsWritten) {
  BenchOptions options = tinySweepOptions(scratchPath("bad_separation"));
  options.separationsPercent = {2.0, 0.0};
  expectRejectedBeforeWriting(context(), options, "separation 0 % is outside (0, 25] %");
  options.separationsPercent = {25.5};
  expectRejectedBeforeWriting(context(), options, "separation 25.5 % is outside (0, 25] %");
  options.separationsPercent = {NAN};
  expectRejectedBeforeWriting(context(), options, "is outside (0, 25] %");
}

TEST_F(BenchJobTest, ResultsFileWithABrokenSectionIsRejectedAndLeftAlone) {
  const fs::path results = scratchPath("broken_RESULTS.md");
  const std::string text = "intro\n<!-- s3d bench: gpu end -->\nno begin marker\n";
  io::writeTextFile(results, text);
  BenchOptions options = tinySweepOptions(scratchPath("bad_results"));
  options.resultsMarkdown = results;
  expectRejectedBeforeWriting(context(), options, "s3d bench: gpu begin");
  EXPECT_EQ(readText(results), text);
  options.resultsMarkdown = scratchPath("missing_RESULTS.md");
  expectRejectedBeforeWriting(context(), options, "does not exist");
  std::error_code ignored;
  fs::remove(results, ignored);
}

TEST(BenchOptions, SearchAndIterativeAloneExpandToTheirDefaultSweepsWithoutRepeats) {
  std::vector<std::string> names;
  for (const MethodSetting& setting : parseMethodSettings({"seed", "search", "iterative", "search-8", "seed"}))
    names.push_back(setting.name());
  EXPECT_EQ(names, (std::vector<std::string>{"seed", "search-4", "search-8", "search-16", "iterative-2", "iterative-4",
                                              "iterative-6", "iterative-8"}));
}

TEST(BenchMarkedSection, ReplacesOnlyTheTextBetweenItsMarkers) {
  const std::string document = "a\n<!-- B -->\nold\n<!-- E -->\nz\n";
  EXPECT_EQ(replaceMarkedSection(document, "<!-- B -->", "<!-- E -->", "new\n"), "a\n<!-- B -->\nnew\n<!-- E -->\nz\n");
}

TEST(BenchMarkedSection, AppendsTheSectionWhenTheFileHasNone) {
  EXPECT_EQ(replaceMarkedSection("text", "<!-- B -->", "<!-- E -->", "new\n"), "text\n\n<!-- B -->\nnew\n<!-- E -->\n");
}

TEST(BenchMarkedSection, RejectsRepeatedOrMisorderedMarkers) {
  EXPECT_THROW(replaceMarkedSection("<!-- B --><!-- B --><!-- E -->", "<!-- B -->", "<!-- E -->", ""),
               std::invalid_argument);
  EXPECT_THROW(replaceMarkedSection("<!-- E -->\n<!-- B -->", "<!-- B -->", "<!-- E -->", ""), std::invalid_argument);
}

TEST(BenchProgressBar, ShowsFilledCellsCountAndLabel) {
  EXPECT_EQ(formatProgressBar({12, 24, "courtyard search-8 sep 2%"}), "[#####.....] 12/24 courtyard search-8 sep 2%");
  EXPECT_EQ(formatProgressBar({0, 48, "x"}), "[..........] 0/48 x");
  EXPECT_EQ(formatProgressBar({48, 48, "done"}), "[##########] 48/48 done");
}

// Counted from stereo_gather.glsl: per interior pixel and eye 3 depth taps + 2 color texels read, 1 texel written.
TEST(BenchTraffic, SeedReadsItsTapsAndTwoColorTexelsPerInteriorPixelAndEye) {
  stereo::StereoParameters parameters;  // maxSeparation 0.02: 2 columns cropped on each side of 100
  parameters.method = stereo::StereoMethod::Seed;
  parameters.kernel = stereo::StereoKernel::PerPixel;
  const stereo::StereoTraffic traffic = stereoPassTraffic(parameters, 100, 10);
  EXPECT_FALSE(traffic.rowTiles);
  const std::uint64_t interior = 96 * 10;
  EXPECT_EQ(traffic.bytesRead, 2 * interior * (3 + 2) * 4);
  EXPECT_EQ(traffic.bytesWritten, 2u * 100 * 10 * 4);
  EXPECT_EQ(traffic.compulsoryBytes, 16u * 100 * 10);
}

// Counted from stereo_row_tile.glsl: each 256-column tile loads its interior columns plus the margin each side
// (clipped to the image) once, a depth and a color texel (8 B) per column; the eyes are written as before.
TEST(BenchTraffic, RowTilesReadEachTilesRunAndMarginOnce) {
  stereo::StereoParameters parameters;  // seed, maxSeparation 0.02 of 600: 12 px, margin 14, 12 columns cropped
  EXPECT_FALSE(stereoPassTraffic(parameters, 600, 10).rowTiles);  // Auto: per pixel
  parameters.kernel = stereo::StereoKernel::RowTiles;
  const stereo::StereoTraffic traffic = stereoPassTraffic(parameters, 600, 10);
  EXPECT_TRUE(traffic.rowTiles);  // the margin fits
  // Tiles [0, 256), [256, 512), [512, 600) with interiors [12, 256), [256, 512), [512, 588).
  const std::uint64_t columns = (270 - 0) + (526 - 242) + (600 - 498);
  EXPECT_EQ(traffic.bytesRead, columns * 10 * 8);
  EXPECT_EQ(traffic.bytesWritten, 2u * 600 * 10 * 4);
}

TEST(BenchOptions, AKernelSuffixForcesTheKernelOfEverySettingItNames) {
  std::vector<std::string> names;
  for (const MethodSetting& setting : parseMethodSettings({"seed/pixel", "search/tiles", "seed", "iterative-2/pixel"}))
    names.push_back(setting.name());
  EXPECT_EQ(names, (std::vector<std::string>{"seed/pixel", "search-4/tiles", "search-8/tiles", "search-16/tiles", "seed",
                                              "iterative-2/pixel"}));
  EXPECT_EQ(parseMethodSettings({"search-4/pixel"}).front().applyTo({}).kernel, stereo::StereoKernel::PerPixel);
  EXPECT_THROW(parseMethodSettings({"seed/blocks"}), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::app
