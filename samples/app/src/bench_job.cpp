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
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "bench_internal.h"
#include "bench_text.h"
#include "s3d/app/render_job.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app {
namespace fs = std::filesystem;

namespace bench_detail {

using namespace bench_text;

std::string joinedNames(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

// A scene's name in the tables: a built-in scene's name, or a scene file's name without folder and extension.
std::string sceneLabel(const std::string& scene) {
  return renderer::isSceneFile(scene) ? fs::path(scene).stem().string() : scene;
}

}  // namespace bench_detail

namespace {

using namespace bench_text;
using namespace bench_detail;

// The default sweeps of "search" and "iterative" in --methods.
constexpr int kDefaultSweepTaps[] = {4, 8, 16};
constexpr int kDefaultSweepIterations[] = {2, 4, 6, 8};
constexpr float kDefaultSweepBudgets[] = {0.0f, 0.02f, 0.05f, 0.1f, 0.2f, 0.5f, 0.6f, 1.0f};
constexpr int kMaxRepeat = 1000;

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
    if (options.hybridSurfaces != frame::HybridSurfaces::Automatic)
      command += std::string(" --hybrid-surfaces ") + frame::hybridSurfacesName(options.hybridSurfaces);
    if (options.hybridEyesInTurn) command += " --hybrid-eyes-in-turn";
    if (options.stereo.hybridCell != stereo::StereoParameters{}.hybridCell)
      command += " --hybrid-cell " + std::to_string(options.stereo.hybridCell);
    if (options.stereo.hybridScoreFloor != stereo::StereoParameters{}.hybridScoreFloor)
      command += " --hybrid-score-floor " + format("%g", double(options.stereo.hybridScoreFloor));
  }
  command += " --repeat " + std::to_string(options.repeat);
  if (options.supersample != 1) command += " --supersample " + std::to_string(options.supersample);
  if (options.bandwidthGBs) command += " --bandwidth-gbs " + format("%g", *options.bandwidthGBs);
  return command;
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

void validateBenchOptions(const BenchOptions& options) { (void)validateBench(options); }

frame::MemoryEstimate benchMemoryEstimate(const BenchOptions& options) {
  double separation = 0.0;
  if (!options.rendererOnly)
    for (double percent : options.separationsPercent) separation = std::max(separation, percent / 100.0);
  const std::uint32_t band = separation > 0.0 ? std::uint32_t(std::ceil(separation * options.width)) + 1 : 0;
  bool hybrid = false;
  if (!options.rendererOnly)
    for (const MethodSetting& setting : parseMethodSettings(options.methods))
      hybrid = hybrid || setting.method == stereo::StereoMethod::Hybrid;
  return frame::renderMemoryEstimate(options.width, options.height, options.width + 2 * band, options.supersample, hybrid);
}

BenchReport runBench(vk::Context& context, const BenchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const ValidatedBench bench = validateBench(options);
  frame::requireMemory(context, benchMemoryEstimate(options), options.memoryLimitBytes);
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
