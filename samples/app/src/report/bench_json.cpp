// bench.json: the report's rows, renderer timings, masked renders and targets.
#include <cmath>

#include "bench_internal.h"
#include "bench_text.h"

namespace s3d::app {
namespace {

using namespace bench_text;
using namespace bench_detail;

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

}  // namespace s3d::app
