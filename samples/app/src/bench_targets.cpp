// The speed and error targets `s3d bench` judges: the default setting against the seed, the stereo pass against
// one reference eye, and the pass against its memory-traffic limit.
#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include "bench_internal.h"
#include "bench_text.h"

namespace s3d::app::bench_detail {

using namespace bench_text;

const BenchRow* findRow(const BenchReport& report, const std::string& scene, float separation,
                        const MethodSetting& setting) {
  for (const BenchRow& row : report.rows)
    if (row.scene == scene && row.maxSeparation == separation && row.setting == setting) return &row;
  return nullptr;
}

namespace {

std::string scopeOf(const BenchRow& row) { return row.scene + " sep " + percentText(row.maxSeparation) + "%"; }

}  // namespace

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

}  // namespace s3d::app::bench_detail
