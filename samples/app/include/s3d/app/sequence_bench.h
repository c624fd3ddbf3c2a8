#pragma once
// `s3d bench --sequence`: every stereo method setting over the camera paths of the chosen scenes, with the comfort
// controls running as in `s3d render --sequence` (sequence_job.h): per setting the mean temporal flicker per eye
// and region, the mean PSNR and the stereo pass's GPU time. Writes sequence_bench.json and sequence_bench.md.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/app/bench_job.h"
#include "s3d/app/sequence_job.h"
#include "s3d/vk/context.h"

namespace s3d::app {

// A method setting (bench_job.h's forms) or "forward+previous": the forward method with the previous-frame fill.
struct SequenceSetting {
  MethodSetting method;
  bool previousFrameFill = false;
  std::string name() const { return method.name() + (previousFrameFill ? "+previous" : ""); }
  stereo::StereoParameters applyTo(stereo::StereoParameters parameters) const;
};
// Throws std::invalid_argument naming the bad item (a "+previous" suffix on another method than forward too).
std::vector<SequenceSetting> parseSequenceSettings(const std::vector<std::string>& items);

inline const std::vector<std::string> kDefaultSequenceScenes = {"cover", "courtyard"};
inline const std::vector<std::string> kDefaultSequenceMethods = {"seed", "search-4", "iterative-6", "forward",
                                                                 "forward+previous"};

struct SequenceBenchOptions {
  std::uint32_t width = 320;
  std::uint32_t height = 180;
  std::vector<std::string> scenes = kDefaultSequenceScenes;  // each must have a camera path
  std::vector<std::string> methods = kDefaultSequenceMethods;
  std::uint32_t supersample = 1;
  // Stereo parameters and comfort controls of every run (method and previousFrameFill come from the setting).
  SequenceJobOptions sequence;
  std::filesystem::path outputFolder = "bench";
  std::function<void(const BenchProgress&)> progress;
};

struct SequenceBenchRow {
  std::string scene;
  std::string setting;
  std::size_t frames = 0;
  std::array<stereo::FlickerStats, 2> flicker{};  // mean over frames 1.. (meanFlicker)
  double newlyVisibleShare = 0.0;  // of the compared pixels, mean over eyes and frames: left out of the flicker
  double psnrLeftDb = 0.0, psnrRightDb = 0.0;  // mean over frames
  std::optional<double> stereoGpuMs;  // median over frames of the stereo pass (the fill included)
  std::uint32_t guardBandColumns = 0;  // of the first frame
};

struct SequenceBenchReport {
  std::string deviceName;
  std::uint32_t width = 0, height = 0;
  std::string commandLine;
  std::vector<SequenceBenchRow> rows;  // scene, then setting, in option order
  double wallSeconds = 0.0;
  std::vector<std::string> filesWritten;
};

// Every check before a GPU resource or file is made: size, scenes (known, with a camera path), settings.
void validateSequenceBenchOptions(const SequenceBenchOptions& options);
// The largest of its runs' estimates (sequence_job.h's sequenceMemoryEstimate): checked before the Vulkan start-up
// and by each run once the device is known.
frame::MemoryEstimate sequenceBenchMemoryEstimate(const SequenceBenchOptions& options);
SequenceBenchReport runSequenceBench(vk::Context& context, const SequenceBenchOptions& options);
nlohmann::json toJson(const SequenceBenchReport& report);
std::string sequenceBenchMarkdown(const SequenceBenchReport& report);

}  // namespace s3d::app
