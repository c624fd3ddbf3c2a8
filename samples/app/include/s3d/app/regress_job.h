#pragma once
// `s3d regress SUITE.json`: stereo regression tests for a studio's CI. Renders every case of a suite (scene,
// frames, resolution, stereo parameters) through runRenderJob, checks the synthesized eyes against the two-pass
// reference (per-region statistics with tolerances) and against stored baselines (the baseline's statistics and
// its eye images), and writes a self-contained HTML report (images inlined as base64 PNG).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/render_job.h"
#include "s3d/comfort/comfort_profile.h"
#include "s3d/io/output_transaction.h"
#include "s3d/vk/context.h"

namespace s3d::app {

struct RegressTolerances {
  double psnrDropDb = 0.5;        // a region's PSNR against the reference may fall this far below its baseline
  double maeRise = 0.5;           // its mean absolute error (8-bit levels) may rise this much
  double shareAbove8Rise = 0.005;  // its share of pixels off by more than 8 levels may rise this much
  double baselineImageMinPsnrDb = 40.0;  // each synthesized eye against the baseline's eye (drivers round differently)
};

// Regions of stereo::EyeError by their suite name: "all" (display), "halo", "rest", "disocclusion".
inline const std::vector<std::string> kRegressRegions = {"all", "halo", "rest", "disocclusion"};

struct RegressCase {
  std::string name;  // [A-Za-z0-9_.-]+, unique in the suite; names the baseline files
  std::string scene;
  std::vector<std::size_t> frames{0};
  std::uint32_t width = 0, height = 0;
  std::uint32_t supersample = 1;
  // "profile": a comfort profile file (relative to the suite) or an inline profile object; then "stereo" keys
  // override its stereo parameters. Without a profile: the ComfortProfile defaults.
  comfort::ComfortProfile profile;
  std::map<std::string, double> minPsnrDb;  // absolute floors against the reference, by region (both eyes)
  RegressTolerances tolerances;
};

struct RegressSuite {
  std::filesystem::path baselineFolder;  // "baselines" of the suite, relative to the suite file
  std::vector<RegressCase> cases;
};

// Parses and validates a suite document. Every problem throws std::invalid_argument as
// "<source>: <where>: <problem>": unknown keys (with the known ones), missing fields, wrong types, bad values
// (scene, frame, resolution, stereo parameters, region names, duplicate case names).
RegressSuite parseRegressSuite(const nlohmann::json& document, const std::filesystem::path& suiteFolder,
                               const std::string& source);
// Reads the file (JSON syntax errors name it) and parses it.
RegressSuite loadRegressSuite(const std::filesystem::path& file);

struct RegressCheck {
  std::string what;  // e.g. "left halo PSNR vs baseline"
  double value = 0.0;
  double limit = 0.0;
  bool atLeast = true;  // passes when value >= limit (else value <= limit)
  bool passed = false;
};

struct RegressRun {
  std::string name;  // "<case>_f<frame>"
  std::string caseName;
  std::size_t frame = 0;
  RenderReport report;
  std::vector<RegressCheck> checks;
  std::string problem;  // a failure that is not a number: missing baseline, render error
  bool baselineUpdated = false;
  bool passed() const;
};

struct RegressOptions {
  std::filesystem::path outputFolder = "regress_out";  // report.html, regress.json and one folder per run
  bool updateBaselines = false;  // (re)write every run's baseline instead of comparing with it
  std::optional<std::uint64_t> memoryLimitBytes;  // --memory-limit; the machine's available memory in any case
};

// Before a Vulkan start-up: every run's memory estimate against the available memory and memoryLimitBytes.
// Throws std::invalid_argument naming the case, the estimate and the limit.
void requireRegressMemory(const RegressSuite& suite, const RegressOptions& options);

// The files a suite run writes (the report folder's, and the baselines with updateBaselines) and reads (each
// case's scene file, and the baselines it compares with), for io::requireOutputsAreNotInputs.
std::vector<io::RunFile> regressOutputs(const RegressSuite& suite, const RegressOptions& options);
std::vector<io::RunFile> regressInputs(const RegressSuite& suite, const RegressOptions& options);

struct RegressResult {
  std::vector<RegressRun> runs;
  std::size_t failedRuns = 0;
  std::filesystem::path htmlReport;
};

// Runs every case and frame, writes the per-run images, report.html and regress.json into options.outputFolder,
// and (with updateBaselines) the baselines: <baselines>/<run>.json (statistics) and <run>.png (left | right).
// progress(done, total, run) is called after each run.
RegressResult runRegressSuite(vk::Context& context, const RegressSuite& suite, const RegressOptions& options,
                              const std::function<void(std::size_t, std::size_t, const std::string&)>& progress = {});

// Standard base64 (RFC 4648, with padding): the HTML report's inlined images.
std::string base64(std::string_view bytes);

}  // namespace s3d::app
