#include "s3d/app/bench_job.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <tuple>
#include <utility>

#include "bench_text.h"
#include "s3d/app/interleaved_timing.h"
#include "s3d/app/render_job.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/disparity_map_pass.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/synthesis.h"
#include "renderer_timing.h"

namespace s3d::app {
namespace fs = std::filesystem;

namespace {

using namespace bench_text;

// The default sweeps of "search" and "iterative" in --methods.
constexpr int kDefaultSweepTaps[] = {4, 8, 16};
constexpr int kDefaultSweepIterations[] = {2, 4, 6, 8};
constexpr float kDefaultSweepBudgets[] = {0.0f, 0.02f, 0.05f, 0.1f, 0.2f, 0.5f, 0.6f, 1.0f};
constexpr int kMaxRepeat = 1000;

// The speed and error targets the bench judges.
constexpr double kHaloGainTargetDb = 2.0;         // the default method's halo PSNR over the seed's, each eye
constexpr double kTimeOverSeedTarget = 2.0;        // at no more than this multiple of the seed's GPU time
constexpr double kStereoToEyeTarget = 1.0 / 20.0;  // both eyes' stereo pass against one reference eye
constexpr double kTrafficLimitTarget = 1.5;       // measured time over (bytes / bandwidth)

std::string joinedNames(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}


// Error measures over the whole cropped area shown per eye after the PSNR columns: one line per stereo::ErrorStats
// field worth a column (a new field such as SSIM is one more line here and one in statsJson).
struct ErrorMeasure {
  const char* heading;
  double (*value)(const stereo::ErrorStats&);
  const char* pattern;
};
const ErrorMeasure kErrorMeasures[] = {
    {"SSIM", [](const stereo::ErrorStats& s) { return s.ssim; }, "%.4f"},
    {"mean abs. error", [](const stereo::ErrorStats& s) { return s.meanAbsoluteError; }, "%.2f"},
    {"error > 8 levels %", [](const stereo::ErrorStats& s) { return 100.0 * s.shareAbove8; }, "%.1f"},
};

// The PSNR regions of the main table, in column order.
struct ErrorRegion {
  const char* heading;
  stereo::ErrorStats EyeError::*stats;
};
const ErrorRegion kErrorRegions[] = {{"PSNR all", &EyeError::display},
                                     {"halo", &EyeError::halo},
                                     {"disocclusion", &EyeError::disocclusion},
                                     {"rest", &EyeError::rest}};
// Regions a scene may not have: a column only in the tables of scenes where they hold pixels.
const ErrorRegion kSceneRegions[] = {{"transparent", &EyeError::transparent}, {"foliage", &EyeError::foliage}};

MethodSetting parseOneSetting(const std::string& item, std::vector<MethodSetting>& settings) {
  auto numberAfter = [&](const std::string& prefix, int low, int high) -> std::optional<int> {
    if (item.rfind(prefix, 0) != 0 || item.size() == prefix.size() || item.size() > prefix.size() + 3)
      return std::nullopt;
    int value = 0;
    for (char c : item.substr(prefix.size())) {
      if (c < '0' || c > '9') return std::nullopt;
      value = value * 10 + (c - '0');
    }
    if (value < low || value > high) return std::nullopt;
    return value;
  };
  auto add = [&](MethodSetting setting) {
    if (std::find(settings.begin(), settings.end(), setting) == settings.end()) settings.push_back(setting);
    return setting;
  };
  if (const std::size_t slash = item.find('/'); slash != std::string::npos) {  // "search-4/tiles": a kernel
    stereo::StereoKernel kernel = stereo::StereoKernel::Auto;
    try {
      kernel = stereo::parseStereoKernel(item.substr(slash + 1));
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument("unknown kernel in method setting '" + item + "' (expected /pixel, /tiles or /auto)");
    }
    std::vector<MethodSetting> bases;
    parseOneSetting(item.substr(0, slash), bases);
    MethodSetting last;
    for (MethodSetting setting : bases) {
      setting.kernel = kernel;
      last = add(setting);
    }
    return last;
  }
  if (item == "hybrid") {
    for (float budget : kDefaultSweepBudgets) add({stereo::StereoMethod::Hybrid, 0, stereo::StereoKernel::Auto, budget});
    return settings.back();
  }
  if (item.rfind("hybrid-", 0) == 0) {  // a budget in [0, 1], e.g. hybrid-0.05
    const std::string text = item.substr(7);
    float budget = -1.0f;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), budget);
    if (error == std::errc() && end == text.data() + text.size() && budget >= 0.0f && budget <= 1.0f)
      return add({stereo::StereoMethod::Hybrid, 0, stereo::StereoKernel::Auto, budget});
  }
  if (item == "seed") return add({stereo::StereoMethod::Seed, 0});
  if (item == "forward") return add({stereo::StereoMethod::Forward, 0});
  if (item == "search") {
    for (int taps : kDefaultSweepTaps) add({stereo::StereoMethod::Search, taps});
    return settings.back();
  }
  if (item == "iterative") {
    for (int iterations : kDefaultSweepIterations) add({stereo::StereoMethod::Iterative, iterations});
    return settings.back();
  }
  if (std::optional<int> taps = numberAfter("search-", 1, S3D_STEREO_MAX_TAPS))
    return add({stereo::StereoMethod::Search, *taps});
  if (std::optional<int> iterations = numberAfter("iterative-", 1, S3D_ITERATIVE_MAX_ITERATIONS))
    return add({stereo::StereoMethod::Iterative, *iterations});
  throw std::invalid_argument("unknown method setting '" + item + "' (expected seed, forward, search, search-N with N in [1, " +
                              std::to_string(S3D_STEREO_MAX_TAPS) + "], iterative, iterative-K with K in [1, " +
                              std::to_string(S3D_ITERATIVE_MAX_ITERATIONS) +
                              "], each optionally followed by /pixel or /tiles, hybrid, or hybrid-B with B in [0, 1])");
}

MethodSetting parseSingleSetting(const std::string& item, const char* what) {
  std::vector<MethodSetting> settings;
  parseOneSetting(item, settings);
  if (settings.size() != 1)
    throw std::invalid_argument(std::string(what) + " must name one setting such as search-8 (got '" + item + "')");
  return settings.front();
}

// Everything validated, in the form the run needs.
// A scene's name in the tables: a built-in scene's name, or a scene file's name without folder and extension.
std::string sceneLabel(const std::string& scene) {
  return renderer::isSceneFile(scene) ? fs::path(scene).stem().string() : scene;
}

std::uint64_t triangleCount(const renderer::Scene& scene) {
  std::uint64_t triangles = 0;
  for (const renderer::Object& object : scene.objects) triangles += scene.meshes[object.mesh].indices.size() / 3;
  return triangles;
}

struct ValidatedBench {
  std::vector<std::string> scenes;
  std::vector<MethodSetting> settings;
  std::vector<float> separations;  // fractions of the width
  MethodSetting target;
};

void requireWellFormedMarkers(const std::string& document, const fs::path& file) {
  for (const char* kind : {"cpu", "gpu"})
    for (bool rendererOnly : {false, true}) {
      try {
        (void)replaceMarkedSection(document, resultsBeginMarker(kind, rendererOnly), resultsEndMarker(kind, rendererOnly),
                                   "");
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument("results file '" + file.string() + "': " + error.what());
      }
    }
}

std::string readTextFile(const fs::path& file);

// --results-md rewrites a file in place: only a Markdown file that is empty or already an s3d results file (its
// marker line, or a section a bench wrote), so a mistyped name never turns an image or a source file into tables.
void requireResultsFile(const fs::path& file) {
  const std::string named = "--results-md '" + file.string() + "'";
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (extension != ".md") throw std::invalid_argument(named + " is not a Markdown file (.md)");
  std::error_code error;
  if (!fs::is_regular_file(file, error)) throw std::invalid_argument(named + " does not exist or is not a file");
  const std::string document = readTextFile(file);
  if (!document.empty() && document.find(kResultsFileMarker) == std::string::npos &&
      document.find("<!-- s3d bench") == std::string::npos)
    throw std::invalid_argument(named + " is not an s3d results file: it has no '" + std::string(kResultsFileMarker) +
                                "' line (give an empty .md file to start one)");
  requireWellFormedMarkers(document, file);
}

std::string readTextFile(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw std::invalid_argument("cannot read results file '" + file.string() + "'");
  return std::string(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
}

ValidatedBench validateBench(const BenchOptions& options) {
  if (!options.rendererOnly && options.gbufferShading != renderer::RendererOptions::GBufferShading::Automatic)
    throw std::invalid_argument("--gbuffer-shading applies to --renderer timings only");
  if (options.supersample < 1 || options.supersample > 4 ||
      std::max(options.width, options.height) * options.supersample > kMaxImageSize)
    throw std::invalid_argument("supersample must be in [1, 4] and keep the render size within " +
                                std::to_string(kMaxImageSize) + " (got " + std::to_string(options.supersample) + ")");
  for (auto [value, name] : {std::pair{options.width, "width"}, std::pair{options.height, "height"}})
    if (value == 0 || value > kMaxImageSize)
      throw std::invalid_argument(std::string(name) + " must be in [1, " + std::to_string(kMaxImageSize) + "] (got " +
                                  std::to_string(value) + ")");
  if (options.repeat < 1 || options.repeat > kMaxRepeat)
    throw std::invalid_argument("repeat must be in [1, " + std::to_string(kMaxRepeat) + "] (got " +
                                std::to_string(options.repeat) + ")");
  if (options.bandwidthGBs && !(std::isfinite(*options.bandwidthGBs) && *options.bandwidthGBs > 0.0))
    throw std::invalid_argument("bandwidth must be a positive number of GB/s (got " +
                                format("%g", *options.bandwidthGBs) + ")");
  stereo::validate(options.stereo);

  ValidatedBench bench;
  for (const std::string& name : options.scenes.empty() ? renderer::builtInSceneNames() : options.scenes) {
    (void)renderer::loadScene(name);  // throws naming the scene (or file) and the choices
    if (std::find(bench.scenes.begin(), bench.scenes.end(), name) == bench.scenes.end()) bench.scenes.push_back(name);
  }
  if (!options.rendererOnly) {
    if (options.methods.empty()) throw std::invalid_argument("no method settings given");
    for (const std::string& item : options.methods) parseOneSetting(item, bench.settings);
    if (options.separationsPercent.empty()) throw std::invalid_argument("no separations given");
    const double limitPercent = 100.0 * double(stereo::kMaxSeparationLimit);
    for (double percent : options.separationsPercent) {
      if (!std::isfinite(percent) || percent <= 0.0 || percent > limitPercent)
        throw std::invalid_argument("separation " + format("%g", percent) + " % is outside (0, " +
                                    format("%g", limitPercent) + "] % of the screen width");
      const float separation = float(percent / 100.0);
      if (!(separation > 0.0f))
        throw std::invalid_argument("separation " + format("%g", percent) + " % is 0 as a float: give at least " +
                                    format("%g", 100.0 * double(std::numeric_limits<float>::min())) + " %");
      if (std::find(bench.separations.begin(), bench.separations.end(), separation) != bench.separations.end()) continue;
      stereo::StereoParameters parameters = options.stereo;
      parameters.maxSeparation = separation;
      parameters.edgeCrop = -1.0f;
      const gpu::StereoConstants constants = stereo::makeStereoConstants(parameters, options.width, options.height);
      if (constants.cropEnd <= constants.cropBegin)
        throw std::invalid_argument("separation " + format("%g", percent) + " % crops all " +
                                    std::to_string(options.width) + " columns: nothing left to compare");
      bench.separations.push_back(separation);
    }
  }
  bench.target = options.targetSetting.empty() ? defaultMethodSetting()
                                               : parseSingleSetting(options.targetSetting, "the target setting");

  if (options.outputFolder.empty()) throw std::invalid_argument("the output folder is empty");
  std::error_code error;
  const fs::file_status status = fs::status(options.outputFolder, error);
  if (fs::exists(status) && !fs::is_directory(status))
    throw std::invalid_argument("output folder '" + options.outputFolder.string() + "' exists and is not a folder");
  if (options.resultsMarkdown) requireResultsFile(*options.resultsMarkdown);
  return bench;
}

std::string commandLineOf(const BenchOptions& options, const ValidatedBench& bench, const MethodSetting& target) {
  std::string command = "s3d bench --resolution " + std::to_string(options.width) + "x" + std::to_string(options.height);
  if (!options.scenes.empty()) command += " --scenes " + joinedNames(bench.scenes, ",");
  if (options.rendererOnly) {
    command += " --renderer";
    if (options.gbufferShading != renderer::RendererOptions::GBufferShading::Automatic)
      command += std::string(" --gbuffer-shading ") + renderer::gbufferShadingName(options.gbufferShading);
  } else {
    std::vector<std::string> names;
    for (const MethodSetting& setting : bench.settings) names.push_back(setting.name());
    std::vector<std::string> separations;
    for (float separation : bench.separations) separations.push_back(percentText(separation));
    command += " --methods " + joinedNames(names, ",") + " --separations " + joinedNames(separations, ",");
    if (!options.targetSetting.empty()) command += " --target-setting " + target.name();
  }
  command += " --repeat " + std::to_string(options.repeat);
  if (options.supersample != 1) command += " --supersample " + std::to_string(options.supersample);
  if (options.bandwidthGBs) command += " --bandwidth-gbs " + format("%g", *options.bandwidthGBs);
  return command;
}

using detail::medianOf;
using detail::timeFrames;

struct EyeReferences {
  ImageRGBA8 leftColor, rightColor;
  DepthImage leftDepth, rightDepth;
  std::vector<std::uint8_t> leftTransparent, rightTransparent;  // the error regions the reference eye defines
  std::vector<std::uint8_t> leftFoliage, rightFoliage;
};

void runSweep(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench, BenchReport& report) {
  renderer::DeferredRenderer deferred(context, options.width, options.height, {options.supersample});
  // The hybrid settings' masked eye renders (a second renderer: the center view stays in `deferred`).
  const bool anyHybrid = std::any_of(bench.settings.begin(), bench.settings.end(),
                                     [](const MethodSetting& s) { return s.method == stereo::StereoMethod::Hybrid; });
  std::unique_ptr<renderer::DeferredRenderer> eyeRenderer;
  if (anyHybrid)
    eyeRenderer = std::make_unique<renderer::DeferredRenderer>(context, options.width, options.height,
                                                               renderer::RendererOptions{options.supersample});
  const std::size_t total = bench.scenes.size() * bench.separations.size() * bench.settings.size();
  std::size_t done = 0;
  auto progress = [&](const std::string& label) {
    if (options.progress) options.progress({done, total, label});
  };
  for (const std::string& sceneName : bench.scenes) {
    renderer::Scene scene = renderer::loadScene(sceneName);
    scene.camera = renderer::cameraForFrame(scene, 0);
    deferred.setScene(scene);
    if (eyeRenderer) eyeRenderer->setScene(scene);
    const renderer::ViewMatrices center =
        renderer::centerViewMatrices(scene, float(options.width) / float(options.height),
                                     {options.stereo.weaponDepthOffset, options.stereo.weaponDepthScale});
    (void)deferred.render(center);  // warm-up: lavapipe compiles pipelines at first use

    // The reference eyes depend on maxSeparation: rendered once per separation, before the center view that the
    // stereo settings run on. Untimed here: their time is measured below, interleaved with the center frame's.
    std::vector<EyeReferences> references;
    for (float separation : bench.separations) {
      progress(sceneName + " references sep " + percentText(separation) + "%");
      stereo::StereoParameters parameters = options.stereo;
      parameters.maxSeparation = separation;
      EyeReferences eyes;
      (void)deferred.render(referenceEyeView(scene, center, stereo::Eye::Left, parameters));
      eyes.leftColor = deferred.readDisplayColor();
      eyes.leftDepth = deferred.readLinearDepth();
      eyes.leftTransparent = deferred.readTransparentMask();
      eyes.leftFoliage = deferred.readCutoutMask();
      (void)deferred.render(referenceEyeView(scene, center, stereo::Eye::Right, parameters));
      eyes.rightColor = deferred.readDisplayColor();
      eyes.rightDepth = deferred.readLinearDepth();
      eyes.rightTransparent = deferred.readTransparentMask();
      eyes.rightFoliage = deferred.readCutoutMask();
      references.push_back(std::move(eyes));
    }
    (void)deferred.render(center);
    const DepthImage centerDepth = deferred.readLinearDepth();
    const stereo::DepthRangePass reduction(context);
    const stereo::DisparityMapPass mapping(context);
    const gpu::DisparityMapConstants map =
        stereo::nonlinearDisparityMap(stereo::reduceDepthRangeReference(centerDepth), options.stereo.zeroParallaxDistance);
    std::optional<double> depthReductionGpuMs, disparityMapGpuMs;
    // A CPU device has no clocks to bring back, and other load on the machine would keep its frame times from
    // settling: its warm-up is the minimum.
    WarmUp frameWarmUp;
    if (context.isCpuDevice()) frameWarmUp.maximum = frameWarmUp.minimum;

    for (std::size_t s = 0; s < bench.separations.size(); ++s) {
      stereo::StereoParameters parameters = options.stereo;
      parameters.maxSeparation = bench.separations[s];
      const EyeReferences& eyes = references[s];
      const renderer::ViewMatrices leftEye = referenceEyeView(scene, center, stereo::Eye::Left, parameters);
      parameters.edgeCrop = -1.0f;  // the crop follows the separation, as in `s3d render`
      // Each setting is timed in one warm stretch with the frames it is compared with: the reference eye and the
      // center frame in back-to-back pairs once untimed pairs run at a steady speed, then the setting, before any
      // error is computed. A GPU lowers its clocks through host-side work (metrics, readbacks, a scene upload)
      // and at a low duty cycle, and takes most of a second of frames to raise them: on an H200 an eye timed in
      // the first 500 ms of a scene read twice the center frame timed after it, and a hybrid setting late in a
      // scene's sweep read 1.8x its time.
      std::vector<InterleavedTiming> frames;
      std::vector<stereo::SynthesisResult> syntheses;
      std::vector<std::optional<HybridSynthesis>> hybrids;
      for (const MethodSetting& setting : bench.settings) {
        progress(sceneName + " " + setting.name() + " sep " + percentText(parameters.maxSeparation) + "%");
        frames.push_back(timeInterleaved(
            {[&] { return deferred.render(leftEye).totalGpuMs; }, [&] { return deferred.render(center).totalGpuMs; }},
            options.repeat, frameWarmUp));  // ends on the center frame: the setting's input
        if (s == 0 && frames.size() == 1) {
          // The disparity budget's depth reduction and the nonlinear depth-to-parallax mapping of the center
          // frame (one untimed run each, then `repeat` timed). The mapping rewrites linearDepth in place, so the
          // center view is rendered again after it.
          std::vector<double> reductionRuns, mappingRuns;
          for (int run = 0; run <= options.repeat; ++run)
            if (const std::optional<double> ms = stereo::reduceDepthRangeTimed(context, reduction, deferred.linearDepth()).gpuMs;
                ms && run > 0)
              reductionRuns.push_back(*ms);
          for (int run = 0; run <= options.repeat; ++run)
            if (const std::optional<double> ms = stereo::mapDepthTimed(context, mapping, deferred.linearDepth(), map);
                ms && run > 0)
              mappingRuns.push_back(*ms);
          depthReductionGpuMs = stereo::medianMs(reductionRuns);
          disparityMapGpuMs = stereo::medianMs(mappingRuns);
          (void)deferred.render(center);
        }
        if (setting.method == stereo::StereoMethod::Hybrid) {
          HybridSynthesis hybrid = synthesizeHybrid(context, deferred, *eyeRenderer,
                                                    scene, center, setting.applyTo(parameters), options.repeat);
          syntheses.push_back({std::move(hybrid.eyes), hybrid.timings.total, {}, hybrid.filledLeft, hybrid.filledRight});
          hybrids.push_back(std::move(hybrid));
        } else {
          syntheses.push_back(stereo::synthesizeTimed(context, deferred.displayColor(), deferred.linearDepth(),
                                                      setting.applyTo(parameters), options.repeat));
          hybrids.push_back(std::nullopt);
        }
        ++done;
      }
      const std::vector<std::uint8_t> halo = haloMaskFor(centerDepth, parameters);
      const std::vector<std::uint8_t> unseenLeft =
          disocclusionMaskFor(eyes.leftDepth, centerDepth, parameters, stereo::Eye::Left);
      const std::vector<std::uint8_t> unseenRight =
          disocclusionMaskFor(eyes.rightDepth, centerDepth, parameters, stereo::Eye::Right);
      for (std::size_t i = 0; i < bench.settings.size(); ++i) {
        const MethodSetting& setting = bench.settings[i];
        const stereo::StereoParameters methodParameters = setting.applyTo(parameters);
        const stereo::SynthesisResult& synthesis = syntheses[i];
        BenchRow row;
        row.scene = sceneLabel(sceneName);
        row.setting = setting;
        row.maxSeparation = parameters.maxSeparation;
        row.cropColumns =
            std::uint32_t(stereo::makeStereoConstants(methodParameters, options.width, options.height).cropBegin);
        row.stereoGpuMs = synthesis.gpuMs;
        row.stereoGpuMsRuns = synthesis.gpuMsRuns;
        row.referenceEyeGpuMs = frames[i].medians[0];
        row.centerFrameGpuMs = frames[i].medians[1];
        row.depthReductionGpuMs = depthReductionGpuMs;
        row.disparityMapGpuMs = disparityMapGpuMs;
        row.frameWarmUpMs = frames[i].warmUpMs;
        row.frameWarmUpSettled = frames[i].settled;
        row.left = compareEye(synthesis.eyes.left, eyes.leftColor, row.cropColumns,
                              stereo::RegionMasks{halo, unseenLeft, eyes.leftTransparent, eyes.leftFoliage});
        row.right = compareEye(synthesis.eyes.right, eyes.rightColor, row.cropColumns,
                               stereo::RegionMasks{halo, unseenRight, eyes.rightTransparent, eyes.rightFoliage});
        row.filledLeft = synthesis.filledLeft;
        row.filledRight = synthesis.filledRight;
        row.traffic = stereoPassTraffic(methodParameters, options.width, options.height, context.isCpuDevice());
        if (const std::optional<HybridSynthesis>& hybrid = hybrids[i]) {
          const double classified = double(std::max<std::uint64_t>(hybrid->classifiedPixels, 1));
          row.maskedShareLeft = double(hybrid->thresholds[0].maskedPixels) / classified;
          row.maskedShareRight = double(hybrid->thresholds[1].maskedPixels) / classified;
          row.hybridTimings = hybrid->timings;
        }
        report.rows.push_back(std::move(row));
      }
    }
  }
  progress("done");
}

void runRendererTimings(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench,
                        BenchReport& report) {
  renderer::RendererOptions rendererOptions{options.supersample};
  rendererOptions.gbufferShading = options.gbufferShading;
  renderer::DeferredRenderer deferred(context, options.width, options.height, rendererOptions);
  report.gbufferShading = renderer::gbufferShadingName(deferred.gbufferShading());
  // `s3d render`'s guard band (zero-parallax plane held at the nearest depth: the sky's parallax bounds it).
  const stereo::GuardBand band = stereo::guardBandFor(options.stereo.maxSeparation, 1.0, 1.0, options.width,
                                                      kMaxImageSize / options.supersample);
  renderer::DeferredRenderer wide(context, band.renderedWidth(options.width), options.height, rendererOptions);
  std::size_t done = 0;
  for (const std::string& sceneName : bench.scenes) {
    if (options.progress) options.progress({done, bench.scenes.size(), sceneName + " center frame"});
    renderer::Scene scene = renderer::loadScene(sceneName);
    scene.camera = renderer::cameraForFrame(scene, 0);
    deferred.setScene(scene);
    const renderer::ViewMatrices center =
        renderer::centerViewMatrices(scene, float(options.width) / float(options.height),
                                     {options.stereo.weaponDepthOffset, options.stereo.weaponDepthScale});
    (void)deferred.render(center);  // warm-up
    auto [frameMs, passes] = timeFrames(deferred, center, options.repeat);
    wide.setScene(scene);
    const renderer::ViewMatrices wideCenter =
        renderer::centerViewMatrices(scene, float(band.renderedWidth(options.width)) / float(options.height),
                                     {options.stereo.weaponDepthOffset, options.stereo.weaponDepthScale});
    (void)wide.render(wideCenter);  // warm-up
    // Back-to-back pairs: a shared CPU device's load drifts between two separate series.
    std::vector<std::optional<double>> wideRuns, ratios;
    for (int run = 0; run < options.repeat; ++run) {
      const std::optional<double> plainMs = deferred.render(center).totalGpuMs;
      wideRuns.push_back(wide.render(wideCenter).totalGpuMs);
      ratios.push_back(plainMs && wideRuns.back() && *plainMs > 0.0 ? std::optional(*wideRuns.back() / *plainMs)
                                                                     : std::nullopt);
    }
    report.rendererRows.push_back(
        {sceneLabel(sceneName), triangleCount(scene), frameMs, std::move(passes), band.columns, medianOf(wideRuns), medianOf(ratios),
         context.isCpuDevice() ? std::optional(detail::processCpuMsPerFrame(deferred, center, options.repeat)) : std::nullopt});
    if (done == 0) {  // the masked-render cost scaling, on the first scene
      if (options.progress) options.progress({done, bench.scenes.size(), sceneName + " masked frames"});
      (void)deferred.render(center);  // its depth picks the masks
      report.maskedRenderRows = detail::timeMaskedRenders(context, deferred, center, sceneName, options.repeat);
    }
    ++done;
  }
  if (options.progress) options.progress({done, bench.scenes.size(), "done"});
}

// ---- targets ----

struct TargetCase {
  std::string scope;          // "courtyard sep 2%"
  std::optional<bool> pass;   // empty: not measurable (a time is missing)
  std::string numbers;
};

struct TargetResult {
  std::string name;
  std::string note;  // why it was skipped, or how it is judged
  std::vector<TargetCase> cases;
};

const BenchRow* findRow(const BenchReport& report, const std::string& scene, float separation,
                        const MethodSetting& setting) {
  for (const BenchRow& row : report.rows)
    if (row.scene == scene && row.maxSeparation == separation && row.setting == setting) return &row;
  return nullptr;
}

std::string scopeOf(const BenchRow& row) { return row.scene + " sep " + percentText(row.maxSeparation) + "%"; }

std::vector<TargetResult> evaluateTargets(const BenchReport& report) {
  const MethodSetting seed{stereo::StereoMethod::Seed, 0};
  const std::string target = report.targetSetting.name();
  std::vector<TargetResult> results;

  TargetResult dominance{"`" + target + "` dominates `seed`: halo PSNR at least " + format("%g", kHaloGainTargetDb) +
                             " dB higher in each eye, at no more than " + format("%g", kTimeOverSeedTarget) +
                             "x its GPU time",
                         "", {}};
  if (report.targetSetting == seed)
    dominance.note = "not applicable: the judged setting is the seed itself (pass --target-setting to judge another)";
  TargetResult budget{"`" + target + "` stereo pass (both eyes) costs at most 1/20 of one reference eye", "", {}};
  if (report.width != 1920 || report.height != 1080)
    budget.note = "measured at " + std::to_string(report.width) + "x" + std::to_string(report.height) +
                  "; the target is stated at 1920x1080";
  TargetResult traffic{"`" + target + "` within " + format("%g", kTrafficLimitTarget) +
                           "x of the memory-traffic limit (bytes counted from the shaders over the bandwidth)",
                       "", {}};
  if (!report.bandwidthGBs)
    traffic.note = "skipped: no --bandwidth-gbs given for " + report.deviceName;
  else
    traffic.note = "bandwidth " + format("%g", *report.bandwidthGBs) + " GB/s (given)";

  for (const BenchRow& row : report.rows) {
    if (!(row.setting == report.targetSetting)) continue;
    const std::optional<double> eyeRatio = ratio(row.stereoGpuMs, row.referenceEyeGpuMs);
    budget.cases.push_back({scopeOf(row), eyeRatio ? std::optional<bool>(*eyeRatio <= kStereoToEyeTarget) : std::nullopt,
                            "stereo " + msText(row.stereoGpuMs) + " ms / eye " + msText(row.referenceEyeGpuMs) +
                                " ms = " + ratioText(eyeRatio)});
    if (report.bandwidthGBs) {
      const double limitMs = double(row.traffic.total()) / (*report.bandwidthGBs * 1e9) * 1e3;
      const std::optional<double> overLimit = ratio(row.stereoGpuMs, limitMs);
      traffic.cases.push_back(
          {scopeOf(row), overLimit ? std::optional<bool>(*overLimit <= kTrafficLimitTarget) : std::nullopt,
           format("%.1f", double(row.traffic.total()) / 1e6) + " MB in " + msText(row.stereoGpuMs) + " ms, limit " +
               msText(limitMs) + " ms: " + (overLimit ? format("%.2f", *overLimit) + "x" : "n/a")});
    }
    const BenchRow* seedRow = findRow(report, row.scene, row.maxSeparation, seed);
    if (report.targetSetting == seed) continue;
    if (!seedRow) {
      dominance.cases.push_back({scopeOf(row), std::nullopt, "seed not in the sweep"});
      continue;
    }
    const double gainLeft = row.left.halo.psnrDb - seedRow->left.halo.psnrDb;
    const double gainRight = row.right.halo.psnrDb - seedRow->right.halo.psnrDb;
    const std::optional<double> timeRatio = ratio(row.stereoGpuMs, seedRow->stereoGpuMs);
    const bool gainMet = std::min(gainLeft, gainRight) >= kHaloGainTargetDb;
    std::optional<bool> pass;
    if (!gainMet)
      pass = false;
    else if (timeRatio)
      pass = *timeRatio <= kTimeOverSeedTarget;
    dominance.cases.push_back({scopeOf(row), pass,
                               "halo gain " + format("%+.2f", gainLeft) + " / " + format("%+.2f", gainRight) +
                                   " dB, time " + (timeRatio ? format("%.2f", *timeRatio) + "x" : "n/a")});
  }
  if (dominance.cases.empty() && dominance.note.empty()) dominance.note = "not measured: `" + target + "` not in the sweep";
  if (budget.cases.empty() && budget.note.empty()) budget.note = "not measured: `" + target + "` not in the sweep";
  results.push_back(std::move(dominance));
  results.push_back(std::move(budget));
  results.push_back(std::move(traffic));
  return results;
}

std::string verdict(const TargetResult& target) {
  std::size_t passed = 0, judged = 0;
  for (const TargetCase& c : target.cases)
    if (c.pass) {
      ++judged;
      passed += *c.pass ? 1 : 0;
    }
  if (judged == 0) return "not judged";
  const std::string count = std::to_string(passed) + " of " + std::to_string(judged) + " cases";
  return (passed == judged ? "**pass** (" : "**fail** (") + count + " pass)";
}

std::string passText(const std::optional<bool>& pass) { return pass ? (*pass ? "pass" : "fail") : "n/a"; }

std::string settingDetail(const MethodSetting& setting) {
  const std::string kernel = setting.kernel == stereo::StereoKernel::PerPixel   ? ", per pixel"
                             : setting.kernel == stereo::StereoKernel::RowTiles ? ", row tiles"
                                                                                : "";
  switch (setting.method) {
    case stereo::StereoMethod::Seed: return "Listing 4.5 (3 taps)" + kernel;
    case stereo::StereoMethod::Search: return std::to_string(setting.parameter) + " taps" + kernel;
    case stereo::StereoMethod::Iterative: return std::to_string(setting.parameter) + " iterations" + kernel;
    case stereo::StereoMethod::Forward: return "z-buffered scatter";
    case stereo::StereoMethod::Hybrid: return "budget " + format("%g", double(setting.budget));
  }
  return "";
}

std::string sweepMarkdown(const BenchReport& report) {
  std::ostringstream md;
  md << "### `s3d bench` on " << report.deviceName << " (" << report.deviceKind << "), " << report.width << "x"
     << report.height << "\n\n";
  md << "Command: `" << report.commandLine << "` (wall time " << format("%.1f", report.wallSeconds) << " s).\n";
  md << "Every time is the median of " << report.repeat
     << " GPU timestamp measurements of warm runs; per scene and separation the center view and both reference eyes\n"
        "are rendered once and every setting runs on that center view. Stereo: both eyes in one dispatch; eye: one\n"
        "two-pass reference eye (the left), timed in back-to-back pairs with the center frame right before each\n"
        "setting. PSNR left / right in dB against the two-pass reference over the cropped\n"
        "area (maxSeparation columns each side) and its regions: halo (within maxSeparation of a center-view depth\n"
        "edge), disocclusion (reference pixels the center view never saw), transparent and foliage (reference pixels\n"
        "covered by transparent surfaces, or whose surface is an alpha cut-out; only for scenes that have them), rest\n"
        "(none of them); the last columns are over the whole cropped area (SSIM: 11x11 Gaussian window on luma,\n"
        "Wang et al. 2004).\n";

  if (!report.rows.empty()) {
    auto [shortest, longest] = std::minmax_element(report.rows.begin(), report.rows.end(), [](const BenchRow& a, const BenchRow& b) {
      return a.frameWarmUpMs < b.frameWarmUpMs;
    });
    const bool cpuDevice = report.deviceKind == "cpu";
    md << "The eye and the center frame were timed after " << format("%.0f", shortest->frameWarmUpMs) << "-"
       << format("%.0f", longest->frameWarmUpMs) << " ms of untimed pairs before each setting"
       << (cpuDevice ? " (a CPU device: the minimum).\n"
                     : " (until they ran at a steady speed: a GPU lowers its clocks\nwhile the host computes metrics).");
    std::vector<std::string> unsettled;
    if (!cpuDevice)
      for (const BenchRow& row : report.rows)
        if (!row.frameWarmUpSettled)
          unsettled.push_back(row.scene + " sep " + percentText(row.maxSeparation) + "% " + row.setting.name());
    if (!unsettled.empty())
      md << " **Not settled** (still changing speed when the warm-up's limit ended it): " << joinedNames(unsettled, ", ")
         << ".";
    if (!cpuDevice) md << "\n";
  }

  std::vector<std::string> scenes;
  for (const BenchRow& row : report.rows)
    if (std::find(scenes.begin(), scenes.end(), row.scene) == scenes.end()) scenes.push_back(row.scene);
  for (const std::string& scene : scenes) {
    const BenchRow* first = nullptr;
    for (const BenchRow& row : report.rows)
      if (row.scene == scene && !first) first = &row;
    md << "\n#### " << scene << " (center frame " << msText(first->centerFrameGpuMs) << " ms, depth reduction "
       << msText(first->depthReductionGpuMs) << " ms, nonlinear depth mapping " << msText(first->disparityMapGpuMs)
       << " ms)\n\n";
    std::vector<ErrorRegion> regions(std::begin(kErrorRegions), std::end(kErrorRegions));
    for (const ErrorRegion& region : kSceneRegions)
      if (std::any_of(report.rows.begin(), report.rows.end(), [&](const BenchRow& row) {
            return row.scene == scene && (row.left.*region.stats).pixelCount + (row.right.*region.stats).pixelCount > 0;
          }))
        regions.insert(regions.end() - 1, region);  // before rest
    md << "| method | setting | sep % | stereo ms | stereo / center | stereo / eye |";
    for (const ErrorRegion& region : regions) md << ' ' << region.heading << " |";
    for (const ErrorMeasure& measure : kErrorMeasures) md << ' ' << measure.heading << " |";
    md << "\n|---|---|---|---|---|---|";
    for (std::size_t i = 0; i < regions.size() + std::size(kErrorMeasures); ++i) md << "---|";
    md << '\n';
    for (const BenchRow& row : report.rows) {
      if (row.scene != scene) continue;
      md << "| " << stereo::methodName(row.setting.method) << " | " << settingDetail(row.setting) << " | "
         << percentText(row.maxSeparation) << " | " << msText(row.stereoGpuMs) << " | "
         << ratioText(ratio(row.stereoGpuMs, row.centerFrameGpuMs)) << " | "
         << ratioText(ratio(row.stereoGpuMs, row.referenceEyeGpuMs)) << " |";
      for (const ErrorRegion& region : regions)
        md << ' ' << dbPair((row.left.*region.stats).psnrDb, (row.right.*region.stats).psnrDb) << " |";
      for (const ErrorMeasure& measure : kErrorMeasures)
        md << ' ' << format(measure.pattern, measure.value(row.left.display)) << " / "
           << format(measure.pattern, measure.value(row.right.display)) << " |";
      md << '\n';
    }
  }

  // Every setting against the seed over all scenes and separations: what the dominance target asks, for all.
  const MethodSetting seed{stereo::StereoMethod::Seed, 0};
  md << "\n#### Settings against the seed (halo PSNR gain of the worse eye, over scenes and separations)\n\n"
        "| setting | smallest gain (dB) | mean gain (dB) | largest time / seed | dominates the seed in |\n"
        "|---|---|---|---|---|\n";
  std::vector<MethodSetting> settings;
  for (const BenchRow& row : report.rows)
    if (std::find(settings.begin(), settings.end(), row.setting) == settings.end()) settings.push_back(row.setting);
  for (const MethodSetting& setting : settings) {
    if (setting == seed) continue;
    double smallest = INFINITY, sum = 0.0, largestTime = 0.0;
    std::size_t count = 0, dominating = 0;
    bool timesKnown = true;
    for (const BenchRow& row : report.rows) {
      const BenchRow* seedRow = row.setting == setting ? findRow(report, row.scene, row.maxSeparation, seed) : nullptr;
      if (!seedRow) continue;
      const double gain = std::min(row.left.halo.psnrDb - seedRow->left.halo.psnrDb,
                                   row.right.halo.psnrDb - seedRow->right.halo.psnrDb);
      const std::optional<double> time = ratio(row.stereoGpuMs, seedRow->stereoGpuMs);
      smallest = std::min(smallest, gain);
      sum += gain;
      ++count;
      if (time) largestTime = std::max(largestTime, *time);
      timesKnown = timesKnown && time.has_value();
      if (gain >= kHaloGainTargetDb && time && *time <= kTimeOverSeedTarget) ++dominating;
    }
    if (count == 0) continue;
    md << "| " << setting.name() << " | " << format("%+.2f", smallest) << " | " << format("%+.2f", sum / double(count))
       << " | " << (timesKnown ? format("%.2f", largestTime) + "x" : std::string("n/a")) << " | " << dominating << " of "
       << count << " |\n";
  }

  md << "\n#### Targets, judged on `" << report.targetSetting.name() << "`\n\n";
  for (const TargetResult& target : evaluateTargets(report)) {
    md << "- " << target.name << ": " << verdict(target);
    if (!target.note.empty()) md << "; " << target.note;
    md << '\n';
    for (const TargetCase& c : target.cases) md << "  - " << c.scope << ": " << passText(c.pass) << ", " << c.numbers << '\n';
  }

  md << hybridBenchMarkdown(report);

  md << "\n#### Memory traffic of the stereo pass (counted from stereo/shaders/)\n\n"
        "Per pixel kernel, per interior pixel and eye: the depth imageLoads (4 B each; seed/search: one per tap,\n"
        "iterative: 8 start taps + 2 x iterations), two color imageLoads (4 B, the horizontal filter) and one\n"
        "imageStore (4 B); a cropped pixel stores both eyes only. Row tiles: each tile loads its run of a row plus the\n"
        "margin each side once (a depth and a color texel, 8 B a column) into shared memory; neighbouring tiles'\n"
        "margins overlap, so DRAM sees between the compulsory bytes (overlap served by the L2 cache) and the counted\n"
        "ones; seed/search fetches of near surfaces beyond the margin are data-dependent and not counted. Compulsory:\n"
        "color and depth read once, both eyes written once (16 B per pixel).\n\n";
  md << "| setting | kernel | sep % | read MB | written MB | B / pixel | compulsory MB |";
  if (report.bandwidthGBs) md << " limit ms | compulsory limit ms | stereo ms (median of scenes) | stereo / limit |";
  md << "\n|---|---|---|---|---|---|---|";
  if (report.bandwidthGBs) md << "---|---|---|---|";
  md << '\n';
  std::vector<std::pair<MethodSetting, float>> seen;
  for (const BenchRow& row : report.rows) {
    if (row.setting.method == stereo::StereoMethod::Hybrid) continue;  // renders pixels: not a pass's traffic
    const std::pair key{row.setting, row.maxSeparation};
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    const double pixels = double(report.width) * double(report.height);
    md << "| " << row.setting.name() << " | " << (row.traffic.rowTiles ? "row tiles" : "per pixel") << " | "
       << percentText(row.maxSeparation) << " | " << format("%.1f", double(row.traffic.bytesRead) / 1e6) << " | "
       << format("%.1f", double(row.traffic.bytesWritten) / 1e6) << " | "
       << format("%.1f", double(row.traffic.total()) / pixels) << " | "
       << format("%.1f", double(row.traffic.compulsoryBytes) / 1e6) << " |";
    if (report.bandwidthGBs) {
      std::vector<double> times;
      for (const BenchRow& other : report.rows)
        if (other.setting == row.setting && other.maxSeparation == row.maxSeparation && other.stereoGpuMs)
          times.push_back(*other.stereoGpuMs);
      const std::optional<double> median = stereo::medianMs(times);
      const double bytesPerMs = *report.bandwidthGBs * 1e6;
      const double limitMs = double(row.traffic.total()) / bytesPerMs;
      md << ' ' << msText(limitMs) << " | " << msText(double(row.traffic.compulsoryBytes) / bytesPerMs) << " | "
         << msText(median) << " | " << (median ? format("%.2f", *median / limitMs) + "x" : "n/a") << " |";
    }
    md << '\n';
  }
  return md.str();
}

std::string rendererMarkdown(const BenchReport& report) {
  std::ostringstream md;
  md << "### `s3d bench --renderer` on " << report.deviceName << " (" << report.deviceKind << "), " << report.width
     << "x" << report.height << "\n\n";
  md << "Command: `" << report.commandLine << "` (wall time " << format("%.1f", report.wallSeconds) << " s).\n";
  md << "Center frame GPU time per scene and per pass (ms), each the median of " << report.repeat
     << " warm frames; a pass the scene does not need does not run (-). G-buffer shading: "
     << report.gbufferShading << ".\n\n";
  std::vector<std::string> passNames;
  for (const RendererRow& row : report.rendererRows)
    for (const renderer::PassTiming& pass : row.passes)
      if (std::find(passNames.begin(), passNames.end(), pass.name) == passNames.end()) passNames.push_back(pass.name);
  const std::uint32_t band = report.rendererRows.empty() ? 0 : report.rendererRows.front().guardBandColumns;
  md << "Guard band: the center frame " << band << " columns wider on each side (`s3d render`'s default at "
     << "this separation); ratio: the median of " << report.repeat << " back-to-back pairs of wide / plain frame.\n\n";
  const bool cpuTimes = std::any_of(report.rendererRows.begin(), report.rendererRows.end(),
                                    [](const RendererRow& row) { return row.cpuTimePerFrameMs.has_value(); });
  if (cpuTimes)
    md << "CPU time: the process's user + system time per center frame over " << report.repeat
       << " more frames (the device's work summed over its threads), which other load on the machine disturbs "
          "less than the timestamps.\n\n";
  md << "| scene | triangles | frame |" << (cpuTimes ? " CPU time |" : "") << " guard band frame | ratio |";
  for (const std::string& name : passNames) md << ' ' << name << " |";
  md << "\n|---|---|---|" << (cpuTimes ? "---|" : "") << "---|---|";
  for (std::size_t i = 0; i < passNames.size(); ++i) md << "---|";
  md << '\n';
  for (const RendererRow& row : report.rendererRows) {
    md << "| " << row.scene << " | " << row.triangles << " | " << msText(row.frameGpuMs) << " | ";
    if (cpuTimes) md << msText(row.cpuTimePerFrameMs) << " | ";
    md << msText(row.guardBandFrameGpuMs) << " | " << ratioText(row.guardBandRatio) << " |";
    for (const std::string& name : passNames) {
      auto pass = std::find_if(row.passes.begin(), row.passes.end(),
                               [&](const renderer::PassTiming& p) { return p.name == name; });
      md << ' ' << (pass == row.passes.end() ? std::string("-") : msText(pass->gpuMs)) << " |";
    }
    md << '\n';
  }
  if (!report.maskedRenderRows.empty()) md << '\n' << detail::maskedRenderMarkdown(report.maskedRenderRows, report.repeat);
  return md.str();
}

nlohmann::json rowJson(const BenchRow& row) {
  return {{"scene", row.scene},
          {"setting", row.setting.name()},
          {"method", stereo::methodName(row.setting.method)},
          {"searchTaps", row.setting.method == stereo::StereoMethod::Search ? nlohmann::json(row.setting.parameter)
                                                                             : nlohmann::json()},
          {"iterations", row.setting.method == stereo::StereoMethod::Iterative ? nlohmann::json(row.setting.parameter)
                                                                                : nlohmann::json()},
          {"maxSeparation", finiteOrNull(tidy(row.maxSeparation))},
          {"cropColumns", row.cropColumns},
          {"gpuTimeMs",
           {{"stereoPass", optionalMs(row.stereoGpuMs)},
            {"stereoPassRuns", row.stereoGpuMsRuns},
            {"centerFrame", optionalMs(row.centerFrameGpuMs)},
            {"depthReduction", optionalMs(row.depthReductionGpuMs)},
            {"disparityMapping", optionalMs(row.disparityMapGpuMs)},
            {"referenceEye", optionalMs(row.referenceEyeGpuMs)}}},
          {"frameWarmUp", {{"hostMs", finiteOrNull(std::round(row.frameWarmUpMs))}, {"settled", row.frameWarmUpSettled}}},
          {"ratios",
           {{"stereoPassToCenterFrame", optionalMs(ratio(row.stereoGpuMs, row.centerFrameGpuMs))},
            {"stereoPassToReferenceEye", optionalMs(ratio(row.stereoGpuMs, row.referenceEyeGpuMs))}}},
          {"error", {{"left", errorJson(row.left)}, {"right", errorJson(row.right)}}},
          {"filledPixels", {{"left", row.filledLeft}, {"right", row.filledRight}}},
          {"hybrid", row.setting.method != stereo::StereoMethod::Hybrid
                         ? nlohmann::json()
                         : nlohmann::json{{"budget", finiteOrNull(tidy(row.setting.budget))},
                                          {"maskedShare", {{"left", row.maskedShareLeft ? finiteOrNull(*row.maskedShareLeft) : nlohmann::json()},
                                                           {"right", row.maskedShareRight ? finiteOrNull(*row.maskedShareRight) : nlohmann::json()}}},
                                          {"gpuTimeMs", row.hybridTimings ? toJson(*row.hybridTimings) : nlohmann::json()}}},
          {"kernel", row.traffic.rowTiles ? "tiles" : "pixel"},
          {"traffic",
           {{"bytesRead", row.traffic.bytesRead},
            {"bytesWritten", row.traffic.bytesWritten},
            {"compulsoryBytes", row.traffic.compulsoryBytes}}}};
}

}  // namespace

std::string MethodSetting::name() const {
  const std::string suffix = kernel == stereo::StereoKernel::Auto ? "" : std::string("/") + stereo::kernelName(kernel);
  switch (method) {
    case stereo::StereoMethod::Seed: return "seed" + suffix;
    case stereo::StereoMethod::Search: return "search-" + std::to_string(parameter) + suffix;
    case stereo::StereoMethod::Iterative: return "iterative-" + std::to_string(parameter) + suffix;
    case stereo::StereoMethod::Forward: return "forward";
    case stereo::StereoMethod::Hybrid: return "hybrid-" + format("%g", double(budget));
  }
  return "unknown";
}

stereo::StereoParameters MethodSetting::applyTo(stereo::StereoParameters parameters) const {
  parameters.method = method;
  parameters.kernel = kernel;
  if (method == stereo::StereoMethod::Search) parameters.searchTaps = parameter;
  if (method == stereo::StereoMethod::Iterative) parameters.iterations = parameter;
  if (method == stereo::StereoMethod::Hybrid) parameters.hybridBudget = budget;
  return parameters;
}

std::vector<MethodSetting> parseMethodSettings(const std::vector<std::string>& items) {
  std::vector<MethodSetting> settings;
  for (const std::string& item : items) parseOneSetting(item, settings);
  return settings;
}

MethodSetting defaultMethodSetting() {
  const stereo::StereoParameters defaults;
  switch (defaults.method) {
    case stereo::StereoMethod::Seed: return {stereo::StereoMethod::Seed, 0};
    case stereo::StereoMethod::Search: return {stereo::StereoMethod::Search, defaults.searchTaps};
    case stereo::StereoMethod::Iterative: return {stereo::StereoMethod::Iterative, defaults.iterations};
    case stereo::StereoMethod::Forward: return {stereo::StereoMethod::Forward, 0};
    case stereo::StereoMethod::Hybrid: return {stereo::StereoMethod::Hybrid, 0, stereo::StereoKernel::Auto, defaults.hybridBudget};
  }
  return {};
}

StereoTraffic stereoPassTraffic(const stereo::StereoParameters& methodParameters, std::uint32_t width,
                                std::uint32_t height, bool cpuDevice) {
  const stereo::StereoParameters parameters = stereo::displacementParameters(methodParameters);  // a hybrid's base
  constexpr std::uint64_t kTexelBytes = 4;  // RGBA8 color, R32F depth, RGBA8 eyes
  int depthLoadsPerEye = 0;
  int margin = 0;
  gpu::StereoConstants crop{};
  if (parameters.method == stereo::StereoMethod::Forward) {
    // stereo_forward_*.comp per pixel and eye: splat 4 depth loads and about one atomic; resolve the key, 2 depth
    // and 2 color loads (holes more); atomics write the 4-byte z-buffers, the resolve empties the other pair
    // (for the next frame) and writes the eyes.
    stereo::makeForwardConstants(parameters, width, height);  // throws for parameters the pass refuses
    const std::uint64_t pixels = std::uint64_t(width) * height;
    StereoTraffic traffic;
    traffic.bytesRead = 2 * pixels * (4 + 1 + 1 + 2 + 2) * kTexelBytes;
    traffic.bytesWritten = 2 * pixels * 3 * kTexelBytes;
    traffic.compulsoryBytes = pixels * 4 * kTexelBytes;
    return traffic;
  }
  if (parameters.method == stereo::StereoMethod::Iterative) {
    const gpu::IterativeConstants c = stereo::makeIterativeConstants(parameters, parameters.iterations, width, height);
    depthLoadsPerEye = c.startTapCount + 2 * c.iterations;  // stereo_iterative.comp: taps, then two starts x K
    margin = stereo::rowTileMargin(c);
    crop.cropBegin = c.cropBegin;
    crop.cropEnd = c.cropEnd;
  } else {
    crop = stereo::makeStereoConstants(parameters, width, height);
    depthLoadsPerEye = crop.tapCount;  // stereo_gather.glsl: minDepthOverTaps
    margin = stereo::rowTileMargin(crop);
  }
  const std::uint64_t interior = std::uint64_t(crop.cropEnd - crop.cropBegin) * height;
  const std::uint64_t pixels = std::uint64_t(width) * height;
  const std::uint64_t colorLoadsPerEye = 2;  // sampleRow's two texels
  StereoTraffic traffic;
  traffic.rowTiles = stereo::usesRowTiles(parameters.kernel, margin, cpuDevice);
  if (traffic.rowTiles) {
    // stereo_row_tile.glsl: each tile with interior columns [begin, end) loads [begin - margin, end + margin)
    // (clipped to the image, margin at most the shared arrays') once, a depth and a color texel per column.
    std::uint64_t loadedColumns = 0;
    for (int tile = 0; tile < int(width); tile += S3D_STEREO_ROW_TILE) {
      const int begin = std::max(tile, crop.cropBegin);
      const int end = std::min({tile + S3D_STEREO_ROW_TILE, crop.cropEnd, int(width)});
      if (begin < end)
        loadedColumns += std::uint64_t(std::min(end + margin, int(width)) - std::max(begin - margin, 0));
    }
    traffic.bytesRead = loadedColumns * height * 2 * kTexelBytes;
  } else {
    traffic.bytesRead = 2 * interior * (std::uint64_t(depthLoadsPerEye) + colorLoadsPerEye) * kTexelBytes;
  }
  traffic.bytesWritten = 2 * pixels * kTexelBytes;  // both eyes, cropped columns too (black)
  traffic.compulsoryBytes = pixels * 4 * kTexelBytes;
  return traffic;
}

void validateBenchOptions(const BenchOptions& options) { (void)validateBench(options); }

MemoryEstimate benchMemoryEstimate(const BenchOptions& options) {
  double separation = 0.0;
  if (!options.rendererOnly)
    for (double percent : options.separationsPercent) separation = std::max(separation, percent / 100.0);
  const std::uint32_t band = separation > 0.0 ? std::uint32_t(std::ceil(separation * options.width)) + 1 : 0;
  bool hybrid = false;
  if (!options.rendererOnly)
    for (const MethodSetting& setting : parseMethodSettings(options.methods))
      hybrid = hybrid || setting.method == stereo::StereoMethod::Hybrid;
  return renderMemoryEstimate(options.width, options.height, options.width + 2 * band, options.supersample, hybrid);
}

BenchReport runBench(vk::Context& context, const BenchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const ValidatedBench bench = validateBench(options);
  requireMemory(context, benchMemoryEstimate(options), options.memoryLimitBytes);
  BenchReport report;
  report.deviceName = context.deviceName();
  report.deviceKind = context.isCpuDevice() ? "cpu" : "gpu";
  report.width = options.width;
  report.height = options.height;
  report.repeat = options.repeat;
  report.rendererOnly = options.rendererOnly;
  report.targetSetting = bench.target;
  report.bandwidthGBs = options.bandwidthGBs;
  report.commandLine = commandLineOf(options, bench, bench.target);
  if (options.rendererOnly)
    runRendererTimings(context, options, bench, report);
  else
    runSweep(context, options, bench, report);
  report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Outputs, each written atomically; the results file last, so it only changes after a complete run.
  const fs::path& folder = options.outputFolder;
  const std::string markdown = benchMarkdown(report);
  auto write = [&](const std::string& name, const std::string& text) {
    io::writeTextFile(folder / name, text);
    report.filesWritten.push_back(name);
  };
  if (!options.rendererOnly) write("bench_speed_vs_error.svg", benchSpeedErrorSvg(report));
  if (!options.rendererOnly) write("bench_time_over_eye.svg", benchTimeOverEyeSvg(report));
  write("bench.md", "# s3d bench\n\n" + markdown);
  // bench.json lists itself and the results file, written after it.
  report.filesWritten.push_back("bench.json");
  if (options.resultsMarkdown) report.filesWritten.push_back(options.resultsMarkdown->string());
  io::writeTextFile(folder / "bench.json", toJson(report).dump(2) + "\n");
  if (options.resultsMarkdown) {
    std::string document = readTextFile(*options.resultsMarkdown);
    if (document.empty()) document = std::string(kResultsFileMarker) + "\n";  // marks the file as ours
    io::writeTextFile(*options.resultsMarkdown,
                      replaceMarkedSection(document, resultsBeginMarker(report.deviceKind, report.rendererOnly),
                                           resultsEndMarker(report.deviceKind, report.rendererOnly), markdown));
  }
  return report;
}

nlohmann::json toJson(const BenchReport& report) {
  nlohmann::json rows = nlohmann::json::array();
  for (const BenchRow& row : report.rows) rows.push_back(rowJson(row));
  nlohmann::json rendererRows = nlohmann::json::array();
  for (const RendererRow& row : report.rendererRows) {
    nlohmann::json passes = nlohmann::json::array();
    for (const renderer::PassTiming& pass : row.passes)
      passes.push_back({{"name", pass.name}, {"gpuMs", finiteOrNull(pass.gpuMs)}});
    rendererRows.push_back({{"scene", row.scene}, {"triangles", row.triangles}, {"frameGpuMs", optionalMs(row.frameGpuMs)}, {"passes", passes},
                            {"guardBandColumns", row.guardBandColumns},
                            {"guardBandFrameGpuMs", optionalMs(row.guardBandFrameGpuMs)},
                            {"guardBandRatio", optionalMs(row.guardBandRatio)},
                            {"cpuTimePerFrameMs", optionalMs(row.cpuTimePerFrameMs)}});
  }
  nlohmann::json maskedRows = nlohmann::json::array();
  for (const MaskedRenderRow& row : report.maskedRenderRows) {
    nlohmann::json passes = nlohmann::json::array();
    for (const renderer::PassTiming& pass : row.passes)
      passes.push_back({{"name", pass.name}, {"gpuMs", finiteOrNull(pass.gpuMs)}});
    maskedRows.push_back({{"scene", row.scene}, {"requestedShare", finiteOrNull(row.requestedShare)},
                          {"shadedShare", finiteOrNull(row.shadedShare)}, {"frameGpuMs", optionalMs(row.frameGpuMs)},
                          {"passes", passes}});
  }
  nlohmann::json targets = nlohmann::json::array();
  if (!report.rendererOnly)
    for (const TargetResult& target : evaluateTargets(report)) {
      nlohmann::json cases = nlohmann::json::array();
      for (const TargetCase& c : target.cases)
        cases.push_back({{"scope", c.scope}, {"pass", c.pass ? nlohmann::json(*c.pass) : nlohmann::json()},
                         {"numbers", c.numbers}});
      targets.push_back({{"target", target.name}, {"note", target.note}, {"cases", cases}});
    }
  return {{"device", report.deviceName},
          {"deviceKind", report.deviceKind},
          {"width", report.width},
          {"height", report.height},
          {"repeat", report.repeat},
          {"command", report.commandLine},
          {"wallSeconds", finiteOrNull(report.wallSeconds)},
          {"targetSetting", report.targetSetting.name()},
          {"bandwidthGBs", report.bandwidthGBs ? finiteOrNull(*report.bandwidthGBs) : nlohmann::json()},
          {"rows", rows},
          {"renderer", rendererRows},
          {"maskedRenderer", maskedRows},
          {"targets", targets},
          {"files", report.filesWritten}};
}

std::string benchMarkdown(const BenchReport& report) {
  return report.rendererOnly ? rendererMarkdown(report) : sweepMarkdown(report);
}


std::string resultsBeginMarker(const std::string& deviceKind, bool rendererOnly) {
  return std::string("<!-- s3d bench") + (rendererOnly ? " renderer" : "") + ": " + deviceKind + " begin -->";
}

std::string resultsEndMarker(const std::string& deviceKind, bool rendererOnly) {
  return std::string("<!-- s3d bench") + (rendererOnly ? " renderer" : "") + ": " + deviceKind + " end -->";
}

std::string replaceMarkedSection(const std::string& document, const std::string& beginMarker,
                                 const std::string& endMarker, const std::string& section) {
  auto countOf = [&](const std::string& marker) {
    std::size_t count = 0;
    for (std::size_t at = document.find(marker); at != std::string::npos; at = document.find(marker, at + 1)) ++count;
    return count;
  };
  const std::size_t begins = countOf(beginMarker), ends = countOf(endMarker);
  if (begins == 0 && ends == 0) {  // first run: the section goes at the end
    std::string appended = document;
    if (!appended.empty() && appended.back() != '\n') appended += '\n';
    if (!appended.empty()) appended += '\n';
    return appended + beginMarker + "\n" + section + endMarker + "\n";
  }
  if (begins != 1 || ends != 1)
    throw std::invalid_argument("expected the markers '" + beginMarker + "' and '" + endMarker +
                                "' once each (found " + std::to_string(begins) + " and " + std::to_string(ends) + ")");
  const std::size_t begin = document.find(beginMarker) + beginMarker.size();
  const std::size_t end = document.find(endMarker);
  if (end < begin) throw std::invalid_argument("marker '" + endMarker + "' comes before '" + beginMarker + "'");
  return document.substr(0, begin) + "\n" + section + document.substr(end);
}

std::string formatProgressBar(const BenchProgress& progress) {
  constexpr std::size_t kCells = 10;
  const std::size_t filled = progress.total == 0 ? 0 : std::min(kCells, progress.done * kCells / progress.total);
  return "[" + std::string(filled, '#') + std::string(kCells - filled, '.') + "] " + std::to_string(progress.done) +
         "/" + std::to_string(progress.total) + " " + progress.label;
}

}  // namespace s3d::app
