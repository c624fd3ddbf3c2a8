#pragma once
// What the files of `s3d bench` share (bench_job.cpp: validation and the run; bench_sweep.cpp: the stereo sweep;
// bench_renderer_sweep.cpp: --renderer; bench_targets.cpp; bench_markdown.cpp; bench_json.cpp). Not installed.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "s3d/app/bench_job.h"
#include "s3d/vk/context.h"

namespace s3d::app::bench_detail {

// The speed and error targets the bench judges.
constexpr double kHaloGainTargetDb = 2.0;         // the default method's halo PSNR over the seed's, each eye
constexpr double kTimeOverSeedTarget = 2.0;        // at no more than this multiple of the seed's GPU time
constexpr double kStereoToEyeTarget = 1.0 / 20.0;  // both eyes' stereo pass against one reference eye
constexpr double kTrafficLimitTarget = 1.5;       // measured time over (bytes / bandwidth)

std::string joinedNames(const std::vector<std::string>& names, const char* separator);

// A scene's name in the tables: a built-in scene's name, or a scene file's name without folder and extension.
std::string sceneLabel(const std::string& scene);

// Everything validated, in the form the run needs.
struct ValidatedBench {
  std::vector<std::string> scenes;
  std::vector<MethodSetting> settings;
  std::vector<float> separations;  // fractions of the width
  MethodSetting target;
};

// The stereo sweep (bench_sweep.cpp): every scene x separation x setting, one BenchRow each.
void runSweep(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench, BenchReport& report);
// --renderer (bench_renderer_sweep.cpp): center frame and pass times per scene, masked renders on the first.
void runRendererTimings(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench,
                        BenchReport& report);

// ---- targets (bench_targets.cpp) ----

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
                        const MethodSetting& setting);
std::vector<TargetResult> evaluateTargets(const BenchReport& report);
// "**pass** (N of M cases pass)", "**fail** (...)" or "not judged".
std::string verdict(const TargetResult& target);
std::string passText(const std::optional<bool>& pass);

}  // namespace s3d::app::bench_detail
