#include "s3d/app/sequence_bench.h"

#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "s3d/app/render_job.h"
#include "s3d/app/report_json.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app {
namespace {

constexpr const char* kPreviousSuffix = "+previous";

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), pattern, value);
  return text;
}

}  // namespace

stereo::StereoParameters SequenceSetting::applyTo(stereo::StereoParameters parameters) const {
  parameters = method.applyTo(parameters);
  parameters.previousFrameFill = previousFrameFill;
  return parameters;
}

std::vector<SequenceSetting> parseSequenceSettings(const std::vector<std::string>& items) {
  std::vector<SequenceSetting> settings;
  for (const std::string& item : items) {
    const std::string suffix = kPreviousSuffix;
    const bool previous = item.size() > suffix.size() && item.compare(item.size() - suffix.size(), suffix.size(), suffix) == 0;
    const std::string base = previous ? item.substr(0, item.size() - suffix.size()) : item;
    for (const MethodSetting& method : parseMethodSettings({base})) {
      if (previous && method.method != stereo::StereoMethod::Forward)
        throw std::invalid_argument("method setting '" + item + "': the previous-frame fill (+previous) needs forward");
      SequenceSetting setting{method, previous};
      bool repeated = false;
      for (const SequenceSetting& s : settings) repeated = repeated || s.name() == setting.name();
      if (!repeated) settings.push_back(setting);
    }
  }
  if (settings.empty()) throw std::invalid_argument("no method settings given");
  return settings;
}

void validateSequenceBenchOptions(const SequenceBenchOptions& options) {
  if (options.width == 0 || options.height == 0 || options.width > kMaxImageSize || options.height > kMaxImageSize)
    throw std::invalid_argument("resolution outside 1.." + std::to_string(kMaxImageSize));
  if (options.supersample < 1 || options.supersample > 4) throw std::invalid_argument("supersample must be in [1, 4]");
  if (options.scenes.empty()) throw std::invalid_argument("no scenes given");
  for (const std::string& name : options.scenes)
    if (renderer::loadScene(name).cameraPath.empty())  // throws naming an unknown scene and the choices
      throw std::invalid_argument("scene '" + name + "' has no camera path");
  for (const SequenceSetting& setting : parseSequenceSettings(options.methods))
    stereo::validate(setting.applyTo(options.sequence.stereo));
  if (options.outputFolder.empty()) throw std::invalid_argument("the output folder is empty");
}

namespace {

// The sequence job one scene and setting run.
SequenceJobOptions jobFor(const SequenceBenchOptions& options, const std::string& scene, const SequenceSetting& setting) {
  SequenceJobOptions job = options.sequence;
  job.width = options.width;
  job.height = options.height;
  job.scene = scene;
  job.supersample = options.supersample;
  job.stereo = setting.applyTo(options.sequence.stereo);
  job.writeFrames = false;
  job.writeReport = false;
  return job;
}

}  // namespace

frame::MemoryEstimate sequenceBenchMemoryEstimate(const SequenceBenchOptions& options) {
  frame::MemoryEstimate largest;
  for (const SequenceSetting& setting : parseSequenceSettings(options.methods)) {
    frame::MemoryEstimate estimate = sequenceMemoryEstimate(jobFor(options, options.scenes.front(), setting));
    if (estimate.totalBytes() > largest.totalBytes()) largest = std::move(estimate);
  }
  return largest;
}

SequenceBenchReport runSequenceBench(vk::Context& context, const SequenceBenchOptions& options) {
  validateSequenceBenchOptions(options);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<SequenceSetting> settings = parseSequenceSettings(options.methods);
  SequenceBenchReport report;
  report.deviceName = context.deviceName();
  report.width = options.width;
  report.height = options.height;
  std::string scenes, methods;
  for (const std::string& s : options.scenes) scenes += (scenes.empty() ? "" : ",") + s;
  for (const SequenceSetting& s : settings) methods += (methods.empty() ? "" : ",") + s.name();
  report.commandLine = "s3d bench --sequence --resolution " + std::to_string(options.width) + "x" +
                       std::to_string(options.height) + " --scenes " + scenes + " --methods " + methods;
  BenchProgress progress{0, options.scenes.size() * settings.size(), ""};
  for (const std::string& scene : options.scenes)
    for (const SequenceSetting& setting : settings) {
      progress.label = scene + " " + setting.name();
      if (options.progress) options.progress(progress);
      const SequenceReport sequence = runSequenceJob(context, jobFor(options, scene, setting));
      SequenceBenchRow row;
      row.scene = scene;
      row.setting = setting.name();
      row.frames = sequence.frames.size();
      row.flicker = meanFlicker(sequence);
      std::vector<double> gpuMs;
      std::uint64_t compared = 0, newlyVisible = 0;
      for (const SequenceFrame& frame : sequence.frames) {
        row.psnrLeftDb += frame.psnrLeftDb / double(sequence.frames.size());
        row.psnrRightDb += frame.psnrRightDb / double(sequence.frames.size());
        if (frame.stereoPassGpuMs) gpuMs.push_back(*frame.stereoPassGpuMs);
        if (frame.flicker)
          for (const stereo::FlickerStats& eye : *frame.flicker) {
            compared += eye.all.pixelCount + eye.newlyVisiblePixels;
            newlyVisible += eye.newlyVisiblePixels;
          }
      }
      row.newlyVisibleShare = compared ? double(newlyVisible) / double(compared) : 0.0;
      row.stereoGpuMs = stereo::medianMs(gpuMs);
      if (!sequence.frames.empty()) row.guardBandColumns = sequence.frames.front().guardBandColumns;
      report.rows.push_back(row);
      ++progress.done;
    }
  progress.label = "done";
  if (options.progress) options.progress(progress);
  report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.filesWritten = {"sequence_bench.json", "sequence_bench.md"};
  io::writeTextFile(options.outputFolder / "sequence_bench.json", toJson(report).dump(2) + "\n");
  io::writeTextFile(options.outputFolder / "sequence_bench.md", sequenceBenchMarkdown(report));
  return report;
}

nlohmann::json toJson(const SequenceBenchReport& report) {
  nlohmann::json rows = nlohmann::json::array();
  auto region = [](const stereo::FlickerRegion& r) {
    return nlohmann::json{{"meanLevels", finiteOrNull(r.meanLevels)}, {"pixelCount", r.pixelCount}};
  };
  auto eye = [&](const stereo::FlickerStats& f) {
    return nlohmann::json{{"all", region(f.all)}, {"halo", region(f.halo)}, {"disocclusion", region(f.disocclusion)}};
  };
  for (const SequenceBenchRow& row : report.rows)
    rows.push_back({{"scene", row.scene},
                    {"setting", row.setting},
                    {"frames", row.frames},
                    {"flicker", {{"left", eye(row.flicker[0])}, {"right", eye(row.flicker[1])}}},
                    {"newlyVisibleShare", finiteOrNull(row.newlyVisibleShare)},
                    {"psnrDb", {{"left", finiteOrNull(row.psnrLeftDb)}, {"right", finiteOrNull(row.psnrRightDb)}}},
                    {"stereoGpuMs", optionalMs(row.stereoGpuMs)},
                    {"guardBandColumns", row.guardBandColumns}});
  return {{"device", report.deviceName}, {"width", report.width}, {"height", report.height},
          {"command", report.commandLine}, {"rows", rows}, {"wallSeconds", report.wallSeconds}};
}

std::string sequenceBenchMarkdown(const SequenceBenchReport& report) {
  std::ostringstream md;
  md << "### `s3d bench --sequence` on " << report.deviceName << ", " << report.width << "x" << report.height << "\n\n"
     << "Command: `" << report.commandLine << "`. Flicker: mean over frames of |e_t(x) - e_t-1(x')| in 8-bit levels "
     << "(e = synthesized - reference, x' where the camera's motion puts x's surface in the previous frame; pixels "
     << "the motion disoccluded left out), over every compared pixel, the halo and the disocclusion region. PSNR: "
     << "mean over frames of the whole compared frame. Stereo ms: median over frames (GPU timestamps).\n\n"
     << "| scene | setting | frames | flicker L: all / halo / disocclusion | flicker R: all / halo / disocclusion "
        "| mean PSNR L / R (dB) | stereo ms |\n|---|---|---|---|---|---|---|\n";
  auto levels = [](const stereo::FlickerStats& f) {
    return format("%.2f", f.all.meanLevels) + " / " + format("%.2f", f.halo.meanLevels) + " / " +
           format("%.2f", f.disocclusion.meanLevels);
  };
  for (const SequenceBenchRow& row : report.rows)
    md << "| " << row.scene << " | " << row.setting << " | " << row.frames << " | " << levels(row.flicker[0]) << " | "
       << levels(row.flicker[1]) << " | " << format("%.2f", row.psnrLeftDb) << " / " << format("%.2f", row.psnrRightDb)
       << " | " << (row.stereoGpuMs ? format("%.2f", *row.stereoGpuMs) : std::string("-")) << " |\n";
  md << "\n";
  return md.str();
}

}  // namespace s3d::app
