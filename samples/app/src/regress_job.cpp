#include "s3d/app/regress_job.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

#include "s3d/image_limits.h"
#include "s3d/input_file.h"
#include "s3d/io/image_io.h"
#include "s3d/json_document.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::app {
namespace {

namespace fs = std::filesystem;

// What each run renders into its folder.
constexpr std::array<const char*, 7> kRunOutputs{"left.png",       "right.png",       "left_reference.png",
                                                 "right_reference.png", "error_left.png", "error_right.png",
                                                 "report.json"};
using nlohmann::json;

// --- Suite validation: every error names the source, the place in the document and the problem ---

struct Where {
  const std::string& source;
  std::string path;  // "cases[2].stereo"
  [[noreturn]] void fail(const std::string& problem) const {
    throw std::invalid_argument(source + ": " + (path.empty() ? std::string("top level") : path) + ": " + problem);
  }
  Where operator/(const std::string& key) const { return {source, path.empty() ? key : path + "." + key}; }
  Where at(std::size_t index) const { return {source, path + "[" + std::to_string(index) + "]"}; }
};

std::string joinedNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

void requireKeys(const json& object, const Where& where, const std::vector<std::string>& known,
                 const std::vector<std::string>& required) {
  if (!object.is_object()) where.fail("expected an object");
  for (const auto& [key, value] : object.items())
    if (std::find(known.begin(), known.end(), key) == known.end())
      where.fail("unknown key '" + key + "' (known: " + joinedNames(known) + ")");
  for (const std::string& key : required)
    if (!object.contains(key)) where.fail("missing '" + key + "'");
}

double number(const json& value, const Where& where) {
  if (!value.is_number()) where.fail("expected a number");
  const double result = value.get<double>();
  if (!std::isfinite(result)) where.fail("expected a finite number");
  return result;
}

std::string text(const json& value, const Where& where) {
  if (!value.is_string()) where.fail("expected a string");
  return value.get<std::string>();
}

std::size_t count(const json& value, const Where& where) {
  // Parsed JSON gives non-negative integers as unsigned, documents built in code as signed: accept both.
  if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<std::int64_t>() < 0))
    where.fail("expected a whole number >= 0");
  return value.get<std::size_t>();
}

void parseTolerances(const json& object, const Where& where, RegressTolerances& tolerances) {
  requireKeys(object, where, {"psnrDropDb", "maeRise", "shareAbove8Rise", "baselineImageMinPsnrDb"}, {});
  auto read = [&](const char* key, double& target) {
    if (!object.contains(key)) return;
    target = number(object[key], where / key);
    if (target < 0.0) (where / key).fail("expected a number >= 0");
  };
  read("psnrDropDb", tolerances.psnrDropDb);
  read("maeRise", tolerances.maeRise);
  read("shareAbove8Rise", tolerances.shareAbove8Rise);
  read("baselineImageMinPsnrDb", tolerances.baselineImageMinPsnrDb);
}

// The keys of a comfort profile's "stereo" object (comfort_profile.h), so a case reads like a profile.
void parseStereo(const json& object, const Where& where, stereo::StereoParameters& parameters) {
  requireKeys(object, where,
              {"method", "maxSeparation", "zeroParallaxDistance", "edgeCrop", "searchTaps", "iterations", "hybridBudget",
               "hybridBase"},
              {});
  auto read = [&](const char* key, float& target) {
    if (object.contains(key)) target = float(number(object[key], where / key));
  };
  for (auto [key, method] : {std::pair{"method", &parameters.method}, std::pair{"hybridBase", &parameters.hybridBase}})
    if (object.contains(key)) {
      try {
        *method = stereo::parseStereoMethod(text(object[key], where / key));
      } catch (const std::invalid_argument& error) {
        (where / key).fail(error.what());
      }
    }
  read("maxSeparation", parameters.maxSeparation);
  read("zeroParallaxDistance", parameters.zeroParallaxDistance);
  read("edgeCrop", parameters.edgeCrop);
  read("hybridBudget", parameters.hybridBudget);
  if (object.contains("searchTaps"))
    parameters.searchTaps = int(std::min<std::size_t>(count(object["searchTaps"], where / "searchTaps"), 1u << 20));
  if (object.contains("iterations"))
    parameters.iterations = int(std::min<std::size_t>(count(object["iterations"], where / "iterations"), 1u << 20));
  try {
    stereo::validate(parameters);
  } catch (const std::invalid_argument& error) {
    where.fail(error.what());
  }
}

bool isCaseName(const std::string& name) {
  return !name.empty() && name.size() <= 100 && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  }) && name.front() != '.';
}

// The render job of one frame of a case: validated while the suite is parsed, run by runRegressSuite.
RenderJobOptions renderOptionsFor(const RegressCase& entry, std::size_t frame) {
  RenderJobOptions options;
  options.width = entry.width;
  options.height = entry.height;
  options.scene = entry.scene;
  options.frame = frame;
  options.supersample = entry.supersample;
  options.stereo = entry.profile.stereo;
  options.display = entry.profile.display;
  options.crosshair = entry.profile.crosshair;
  options.allowNegativeParallax = entry.profile.allowNegativeParallax;
  return options;
}

RegressCase parseCase(const json& object, const Where& where, const RegressTolerances& suiteTolerances,
                      const fs::path& suiteFolder) {
  requireKeys(object, where,
              {"name", "scene", "frames", "resolution", "supersample", "profile", "stereo", "minPsnrDb", "tolerances"},
              {"name", "scene", "resolution"});
  RegressCase entry;
  entry.name = text(object["name"], where / "name");
  if (!isCaseName(entry.name)) (where / "name").fail("'" + entry.name + "' must be letters, digits, '_', '-' or '.'");
  entry.scene = text(object["scene"], where / "scene");
  const std::string resolution = text(object["resolution"], where / "resolution");
  const std::size_t x = resolution.find('x');
  try {
    std::size_t used = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    const unsigned long width = std::stoul(resolution.substr(0, x), &used);
    if (used != x) throw std::invalid_argument("width");
    const unsigned long height = std::stoul(resolution.substr(x + 1), &used);
    if (used != resolution.size() - x - 1) throw std::invalid_argument("height");
    entry.width = std::uint32_t(std::min<unsigned long>(width, kMaxImageSize + 1));
    entry.height = std::uint32_t(std::min<unsigned long>(height, kMaxImageSize + 1));
  } catch (const std::exception&) {
    (where / "resolution").fail("expected WxH, e.g. \"64x36\" (got '" + resolution + "')");
  }
  if (object.contains("frames")) {
    const json& frames = object["frames"];
    if (!frames.is_array() || frames.empty()) (where / "frames").fail("expected a non-empty array of frame numbers");
    entry.frames.clear();
    for (std::size_t i = 0; i < frames.size(); ++i) entry.frames.push_back(count(frames[i], (where / "frames").at(i)));
  }
  if (object.contains("supersample"))
    entry.supersample = std::uint32_t(std::min<std::size_t>(count(object["supersample"], where / "supersample"), 1u << 20));
  if (object.contains("profile")) {
    const json& profile = object["profile"];
    try {
      if (profile.is_string())
        entry.profile = comfort::loadComfortProfile(suiteFolder / profile.get<std::string>());
      else if (profile.is_object())
        entry.profile = comfort::comfortProfileFromJson(profile);
      else
        (where / "profile").fail("expected a profile file name or an inline profile object");
    } catch (const std::invalid_argument& error) {
      if (std::string(error.what()).starts_with(where.source)) throw;  // our own message, already placed
      (where / "profile").fail(error.what());
    } catch (const std::runtime_error& error) {
      (where / "profile").fail(error.what());
    }
  }
  if (object.contains("stereo")) parseStereo(object["stereo"], where / "stereo", entry.profile.stereo);
  try {
    comfort::validate(entry.profile);
  } catch (const std::invalid_argument& error) {
    where.fail(error.what());
  }
  if (object.contains("minPsnrDb")) {
    requireKeys(object["minPsnrDb"], where / "minPsnrDb", kRegressRegions, {});
    for (const auto& [region, value] : object["minPsnrDb"].items())
      entry.minPsnrDb[region] = number(value, where / "minPsnrDb" / region);
  }
  entry.tolerances = suiteTolerances;
  if (object.contains("tolerances")) parseTolerances(object["tolerances"], where / "tolerances", entry.tolerances);
  // Scene, frame, size and crop: the render job's own validation, before anything runs.
  for (std::size_t frame : entry.frames) {
    try {
      validateRenderJobOptions(renderOptionsFor(entry, frame));
    } catch (const std::logic_error& error) {  // invalid_argument, and out_of_range for a frame beyond the path
      where.fail(error.what());
    }
  }
  return entry;
}

// --- Running ---

std::string readBytes(const fs::path& file) { return readInputFile(file, "image", kMaxImagePixels * 8); }

const stereo::ErrorStats& region(const stereo::EyeError& error, const std::string& name) {
  if (name == "halo") return error.halo;
  if (name == "rest") return error.rest;
  if (name == "disocclusion") return error.disocclusion;
  return error.display;
}

const json* baselineRegion(const json& eye, const std::string& name) {
  if (name == "all") return &eye;
  if (!eye.contains(name)) return nullptr;
  return &eye[name];
}

std::optional<double> optionalNumber(const json* object, const char* key) {
  if (!object || !object->is_object() || !object->contains(key) || !(*object)[key].is_number()) return std::nullopt;
  return (*object)[key].get<double>();
}

void addCheck(RegressRun& run, std::string what, double value, double limit, bool atLeast) {
  const bool passed = std::isfinite(value) && (atLeast ? value >= limit : value <= limit);
  run.checks.push_back({std::move(what), value, limit, atLeast, passed});
}

std::pair<ImageRGBA8, ImageRGBA8> splitSideBySide(const ImageRGBA8& pair) {
  const std::uint32_t width = pair.width / 2;
  ImageRGBA8 left(width, pair.height), right(width, pair.height);
  for (std::uint32_t y = 0; y < pair.height; ++y)
    for (std::uint32_t x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c) {
        left.at(x, y)[c] = pair.at(x, y)[c];
        right.at(x, y)[c] = pair.at(x + width, y)[c];
      }
  return {std::move(left), std::move(right)};
}

json baselineDocument(const RegressCase& entry, const RegressRun& run) {
  const stereo::StereoParameters& p = run.report.stereo;
  return {{"case", entry.name},
          {"scene", entry.scene},
          {"supersample", entry.supersample},
          {"profile", comfort::toJson(entry.profile)},
          {"frame", run.frame},
          {"width", entry.width},
          {"height", entry.height},
          {"stereo",
           {{"method", stereo::methodName(p.method)},
            {"maxSeparation", tidy(p.maxSeparation)},
            {"zeroParallaxDistance", tidy(p.zeroParallaxDistance)},
            {"edgeCrop", tidy(p.edgeCrop)},
            {"searchTaps", p.searchTaps},
            {"iterations", p.iterations}}},
          {"error", {{"left", errorJson(run.report.left)}, {"right", errorJson(run.report.right)}}}};
}

// Compares one run with its stored baseline (statistics and eye images); writes baseline_error_*.png.
void compareWithBaseline(RegressRun& run, const RegressCase& entry, const fs::path& baselineFolder,
                         const fs::path& runFolder, const ImageRGBA8& left, const ImageRGBA8& right) {
  const fs::path statsFile = baselineFolder / (run.name + ".json");
  const fs::path imageFile = baselineFolder / (run.name + ".png");
  if (!fs::is_regular_file(statsFile) || !fs::is_regular_file(imageFile)) {
    run.problem = "no baseline " + statsFile.filename().string() + " / " + imageFile.filename().string() + " in '" +
                  baselineFolder.string() + "' (run with --update-baselines)";
    return;
  }
  json baseline;
  try {
    baseline = readJsonDocument(statsFile, "baseline");
  } catch (const InputFileError& error) {
    run.problem = error.what();
    return;
  }
  const RegressTolerances& tolerance = entry.tolerances;
  for (const char* eyeName : {"left", "right"}) {
    const stereo::EyeError& current = std::string(eyeName) == "left" ? run.report.left : run.report.right;
    const json* eye = baseline.contains("error") && baseline["error"].contains(eyeName) ? &baseline["error"][eyeName] : nullptr;
    if (!eye) {
      run.problem = "baseline '" + statsFile.string() + "' has no error." + eyeName;
      return;
    }
    for (const std::string& name : kRegressRegions) {
      const stereo::ErrorStats& stats = region(current, name);
      if (stats.pixelCount == 0) continue;  // nothing of this region in the frame
      const json* stored = baselineRegion(*eye, name);
      const std::string prefix = std::string(eyeName) + " " + name + " ";
      if (auto psnr = optionalNumber(stored, "psnrDb"))
        addCheck(run, prefix + "PSNR (dB) vs baseline", stats.psnrDb, *psnr - tolerance.psnrDropDb, true);
      if (auto mae = optionalNumber(stored, "meanAbsoluteError"))
        addCheck(run, prefix + "mean abs. error vs baseline", stats.meanAbsoluteError, *mae + tolerance.maeRise, false);
      if (auto share = optionalNumber(stored, "shareAbove8"))
        addCheck(run, prefix + "share > 8 levels vs baseline", stats.shareAbove8, *share + tolerance.shareAbove8Rise, false);
    }
  }
  ImageRGBA8 stored;
  try {
    stored = io::readPng(imageFile);
  } catch (const std::exception& error) {
    run.problem = error.what();
    return;
  }
  if (stored.width != 2 * left.width || stored.height != left.height) {
    run.problem = "baseline image '" + imageFile.string() + "' is " + std::to_string(stored.width) + "x" +
                  std::to_string(stored.height) + ", expected " + std::to_string(2 * left.width) + "x" +
                  std::to_string(left.height) + " (left | right)";
    return;
  }
  const auto [storedLeft, storedRight] = splitSideBySide(stored);
  const std::uint32_t crop = run.report.cropColumns;
  addCheck(run, "left eye vs baseline image PSNR (dB)", stereo::compareDisplayImages(left, storedLeft, crop).psnrDb,
           tolerance.baselineImageMinPsnrDb, true);
  addCheck(run, "right eye vs baseline image PSNR (dB)", stereo::compareDisplayImages(right, storedRight, crop).psnrDb,
           tolerance.baselineImageMinPsnrDb, true);
  io::writePng(runFolder / "baseline_error_left.png", stereo::makeErrorHeatMap(left, storedLeft, crop));
  io::writePng(runFolder / "baseline_error_right.png", stereo::makeErrorHeatMap(right, storedRight, crop));
}

// --- HTML ---

std::string escaped(const std::string& value) {
  std::string out;
  for (char c : value) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string formatted(double value, int decimals = 2) {
  if (!std::isfinite(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

std::string imageTag(const fs::path& file, const std::string& caption) {
  if (!fs::is_regular_file(file)) return {};
  return "<figure><img src=\"data:image/png;base64," + base64(readBytes(file)) + "\" alt=\"" + escaped(caption) +
         "\"><figcaption>" + escaped(caption) + "</figcaption></figure>";
}

std::string htmlReport(const std::vector<RegressRun>& runs, const fs::path& outputFolder, std::size_t failed) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>s3d regress</title><style>"
          "body{font-family:sans-serif;margin:1em}table{border-collapse:collapse}td,th{border:1px solid #999;"
          "padding:2px 6px;text-align:right}td.l{text-align:left}.pass{background:#cfc}.fail{background:#fcc}"
          "figure{display:inline-block;margin:4px}img{image-rendering:pixelated;width:256px}"
          "figcaption{font-size:80%}</style></head><body>\n";
  html << "<h1>s3d regress: " << (failed ? std::to_string(failed) + " of " + std::to_string(runs.size()) + " runs FAILED"
                                         : "all " + std::to_string(runs.size()) + " runs passed")
       << "</h1>\n";
  html << "<p>Synthesized eyes against the two-pass reference (PSNR in dB; border columns excluded) and against the "
          "stored baselines.</p>\n<table><tr><th>run</th><th>scene</th><th>method</th><th>left all</th><th>left halo</th>"
          "<th>left rest</th><th>right all</th><th>right halo</th><th>right rest</th><th>checks</th><th>result</th>"
          "</tr>\n";
  for (const RegressRun& run : runs) {
    std::size_t failedChecks = 0;
    for (const RegressCheck& check : run.checks) failedChecks += check.passed ? 0 : 1;
    html << "<tr class=\"" << (run.passed() ? "pass" : "fail") << "\"><td class=\"l\"><a href=\"#" << escaped(run.name)
         << "\">" << escaped(run.name) << "</a></td><td class=\"l\">" << escaped(run.report.scene) << "</td><td class=\"l\">"
         << stereo::methodName(run.report.stereo.method) << "</td>";
    for (const stereo::EyeError* eye : {&run.report.left, &run.report.right})
      html << "<td>" << formatted(eye->display.psnrDb) << "</td><td>" << formatted(eye->halo.psnrDb) << "</td><td>"
           << formatted(eye->rest.psnrDb) << "</td>";
    html << "<td>" << (run.checks.size() - failedChecks) << "/" << run.checks.size() << "</td><td class=\"l\">"
         << (run.baselineUpdated ? "baseline updated" : run.passed() ? "pass" : "FAIL") << "</td></tr>\n";
  }
  html << "</table>\n";
  for (const RegressRun& run : runs) {
    const fs::path folder = outputFolder / run.name;
    html << "<h2 id=\"" << escaped(run.name) << "\">" << escaped(run.name) << ": "
         << (run.baselineUpdated ? "baseline updated" : run.passed() ? "pass" : "FAIL") << "</h2>\n";
    if (!run.problem.empty()) html << "<p class=\"fail\">" << escaped(run.problem) << "</p>\n";
    if (!run.checks.empty()) {
      html << "<table><tr><th>check</th><th>value</th><th>limit</th><th>result</th></tr>\n";
      for (const RegressCheck& check : run.checks)
        html << "<tr class=\"" << (check.passed ? "pass" : "fail") << "\"><td class=\"l\">" << escaped(check.what)
             << "</td><td>" << formatted(check.value, 4) << "</td><td>" << (check.atLeast ? "&ge; " : "&le; ")
             << formatted(check.limit, 4) << "</td><td class=\"l\">" << (check.passed ? "pass" : "FAIL") << "</td></tr>\n";
      html << "</table>\n";
    }
    html << "<div>" << imageTag(folder / "left.png", "synthesized left") << imageTag(folder / "right.png", "synthesized right")
         << imageTag(folder / "left_reference.png", "reference left") << imageTag(folder / "right_reference.png", "reference right")
         << "</div>\n<div>" << imageTag(folder / "error_left.png", "error vs reference, left")
         << imageTag(folder / "error_right.png", "error vs reference, right")
         << imageTag(folder / "baseline_error_left.png", "error vs baseline, left")
         << imageTag(folder / "baseline_error_right.png", "error vs baseline, right") << "</div>\n";
  }
  html << "<p>Heat maps: largest R/G/B difference per pixel, black 0 through blue, red and yellow to white at 32 levels; "
          "the cropped border columns stay black.</p>\n</body></html>\n";
  return html.str();
}

json checkJson(const RegressCheck& check) {
  return {{"check", check.what}, {"value", finiteOrNull(check.value)}, {"limit", finiteOrNull(check.limit)},
          {"atLeast", check.atLeast}, {"passed", check.passed}};
}

}  // namespace

bool RegressRun::passed() const {
  return problem.empty() && std::all_of(checks.begin(), checks.end(), [](const RegressCheck& c) { return c.passed; });
}

RegressSuite parseRegressSuite(const json& document, const fs::path& suiteFolder, const std::string& source) {
  const Where top{source, ""};
  requireKeys(document, top, {"baselines", "tolerances", "cases"}, {"cases"});
  RegressSuite suite;
  suite.baselineFolder = suiteFolder / (document.contains("baselines") ? text(document["baselines"], top / "baselines")
                                                                       : std::string("baselines"));
  RegressTolerances tolerances;
  if (document.contains("tolerances")) parseTolerances(document["tolerances"], top / "tolerances", tolerances);
  const json& cases = document["cases"];
  if (!cases.is_array() || cases.empty()) (top / "cases").fail("expected a non-empty array of cases");
  std::set<std::string> names;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    suite.cases.push_back(parseCase(cases[i], (top / "cases").at(i), tolerances, suiteFolder));
    if (!names.insert(suite.cases.back().name).second)
      ((top / "cases").at(i) / "name").fail("duplicate case name '" + suite.cases.back().name + "'");
  }
  return suite;
}

RegressSuite loadRegressSuite(const fs::path& file) {
  json document;
  try {
    document = readJsonDocument(file, "suite file");
  } catch (const InputFileError& error) {
    throw std::invalid_argument(error.what());
  }
  return parseRegressSuite(document, file.parent_path(), file.string());
}

void requireRegressMemory(const RegressSuite& suite, const RegressOptions& options) {
  for (const RegressCase& entry : suite.cases)
    for (std::size_t frame : entry.frames) {
      RenderJobOptions render = renderOptionsFor(entry, frame);
      render.memoryLimitBytes = options.memoryLimitBytes;
      try {
        validateRenderJobOptions(render);
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument("case '" + entry.name + "': " + error.what());
      }
    }
}

std::vector<io::RunFile> regressOutputs(const RegressSuite& suite, const RegressOptions& options) {
  std::vector<io::RunFile> files{{options.outputFolder / "regress.json", "--output"},
                                 {options.outputFolder / "report.html", "--output"}};
  for (const RegressCase& entry : suite.cases)
    for (std::size_t frame : entry.frames) {
      const std::string run = entry.name + "_f" + std::to_string(frame);
      for (const char* name : kRunOutputs) files.push_back({options.outputFolder / run / name, "--output"});
      for (const char* name : {"baseline_error_left.png", "baseline_error_right.png"})
        files.push_back({options.outputFolder / run / name, "--output"});
      if (options.updateBaselines)
        for (const char* extension : {".json", ".png"})
          files.push_back({suite.baselineFolder / (run + extension), "--update-baselines"});
    }
  return files;
}

std::vector<io::RunFile> regressInputs(const RegressSuite& suite, const RegressOptions& options) {
  std::vector<io::RunFile> files;
  for (const RegressCase& entry : suite.cases) {
    if (renderer::isSceneFile(entry.scene))
      for (const fs::path& file : renderer::sceneFileInputs(entry.scene)) files.push_back({file, "the suite's scene"});
    if (!options.updateBaselines)
      for (std::size_t frame : entry.frames)
        for (const char* extension : {".json", ".png"})
          files.push_back({suite.baselineFolder / (entry.name + "_f" + std::to_string(frame) + extension), "baseline"});
  }
  return files;
}

RegressResult runRegressSuite(vk::Context& context, const RegressSuite& suite, const RegressOptions& options,
                              const std::function<void(std::size_t, std::size_t, const std::string&)>& progress) {
  std::size_t total = 0;
  for (const RegressCase& entry : suite.cases) total += entry.frames.size();
  RegressResult result;
  for (const RegressCase& entry : suite.cases) {
    for (std::size_t frame : entry.frames) {
      RegressRun run;
      run.caseName = entry.name;
      run.frame = frame;
      run.name = entry.name + "_f" + std::to_string(frame);
      const fs::path runFolder = options.outputFolder / run.name;
      RenderJobOptions render = renderOptionsFor(entry, frame);
      render.memoryLimitBytes = options.memoryLimitBytes;
      render.outputFolder = runFolder;
      render.outputs = {kRunOutputs.begin(), kRunOutputs.end()};
      run.report = runRenderJob(context, render);
      const ImageRGBA8 left = io::readPng(runFolder / "left.png");
      const ImageRGBA8 right = io::readPng(runFolder / "right.png");
      // Against the reference: the suite's absolute floors.
      for (const auto& [name, floor] : entry.minPsnrDb)
        for (const auto& [eyeName, eye] : {std::pair{"left", &run.report.left}, std::pair{"right", &run.report.right}})
          if (region(*eye, name).pixelCount > 0)
            addCheck(run, std::string(eyeName) + " " + name + " PSNR (dB) vs reference", region(*eye, name).psnrDb, floor, true);
      if (options.updateBaselines) {
        io::writeTextFile(suite.baselineFolder / (run.name + ".json"), baselineDocument(entry, run).dump(2) + "\n");
        io::writePng(suite.baselineFolder / (run.name + ".png"), stereo::makeSideBySide(left, right, stereo::PackingMode::Full));
        run.baselineUpdated = true;
      } else {
        compareWithBaseline(run, entry, suite.baselineFolder, runFolder, left, right);
      }
      if (!run.passed()) ++result.failedRuns;
      result.runs.push_back(std::move(run));
      if (progress) progress(result.runs.size(), total, result.runs.back().name);
    }
  }
  json runs = json::array();
  for (const RegressRun& run : result.runs) {
    json checks = json::array();
    for (const RegressCheck& check : run.checks) checks.push_back(checkJson(check));
    runs.push_back({{"run", run.name}, {"case", run.caseName}, {"frame", run.frame}, {"passed", run.passed()},
                    {"baselineUpdated", run.baselineUpdated}, {"problem", run.problem}, {"checks", checks},
                    {"error", {{"left", errorJson(run.report.left)}, {"right", errorJson(run.report.right)}}}});
  }
  io::writeTextFile(options.outputFolder / "regress.json",
                    json{{"failedRuns", result.failedRuns}, {"runs", runs}}.dump(2) + "\n");
  result.htmlReport = options.outputFolder / "report.html";
  io::writeTextFile(result.htmlReport, htmlReport(result.runs, options.outputFolder, result.failedRuns));
  return result;
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t triple = std::uint32_t(std::uint8_t(bytes[i])) << 16 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 |
                                 std::uint8_t(bytes[i + 2]);
    for (int shift = 18; shift >= 0; shift -= 6) out.push_back(kAlphabet[(triple >> shift) & 63u]);
  }
  if (i < bytes.size()) {
    std::uint32_t triple = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) triple |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out.push_back(kAlphabet[(triple >> 18) & 63u]);
    out.push_back(kAlphabet[(triple >> 12) & 63u]);
    out.push_back(i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63u] : '=');
    out.push_back('=');
  }
  return out;
}

}  // namespace s3d::app
