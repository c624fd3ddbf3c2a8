#pragma once
// Pieces every `s3d` command shares: error/number formatting, option validators, the stereo and device options,
// and the Command interface each command file implements (main.cpp runs the one that was parsed).
#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "s3d/io/output_transaction.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::cli {

// One `s3d` command: a CLI11 subcommand plus the code that runs it once parsed.
class Command {
 public:
  virtual ~Command() = default;
  CLI::App* subcommand = nullptr;
  virtual int run() = 0;  // the exit status; throws on errors (main prints them as one line)
};

std::unique_ptr<Command> addRenderCommand(CLI::App& app);
std::unique_ptr<Command> addConvertCommand(CLI::App& app);
std::unique_ptr<Command> addBenchCommand(CLI::App& app);
std::unique_ptr<Command> addRegressCommand(CLI::App& app);
std::unique_ptr<Command> addTuneCommand(CLI::App& app);

std::string oneLine(std::string text);
// Prints "s3d: error: <message>" as one line on stderr and returns the failing exit status (1).
int fail(const std::string& message);
void warn(const std::string& message);  // "s3d: warning: <message>"
std::string joined(const std::vector<std::string>& names, const char* separator);

// Every file a command writes and reads, gathered before it writes anything and checked together in one place
// (io::requireOutputsAreNotInputs): no output may replace an input or another output.
struct RunFiles {
  std::vector<io::RunFile> outputs, inputs;
  void write(const std::filesystem::path& file, const std::string& option) { outputs.push_back({file, option}); }
  // Files of the output folder (option "--output"); a name may hold one '*' for any text.
  void writeInFolder(const std::filesystem::path& folder, const std::vector<std::string>& names);
  void read(const std::filesystem::path& file, const std::string& option) { inputs.push_back({file, option}); }
  // A scene file and every file it references (renderer::sceneFileInputs); nothing for a built-in scene.
  void readScene(const std::string& scene, const std::string& option);
  // --display NAME_OR_FILE: the file, unless it is a built-in display's name.
  void readDisplay(const std::string& display);
  void check() const { io::requireOutputsAreNotInputs(outputs, inputs); }
};

// What runStaged gives back: the job's report (empty when it threw: `error` says why) and how many messages the
// validation layer reported (each already printed; a non-zero count fails the run: failValidation).
template <typename Report>
struct StagedRun {
  std::optional<Report> report;
  std::string error;
  std::size_t validationMessages = 0;
};

// Runs `job` with every output it writes into `folder` staged (io::OutputTransaction): the files are moved into
// place only when the job returned and the validation layer reported nothing, so a failed run leaves the folder
// as it was. The layer's messages are printed as "s3d: validation: ..." lines.
template <typename Job>
StagedRun<std::invoke_result_t<Job>> runStaged(vk::Context& context, const std::filesystem::path& folder, Job&& job) {
  StagedRun<std::invoke_result_t<Job>> run;
  io::OutputTransaction outputs(folder);  // all files or none
  try {
    run.report = job();
  } catch (const std::exception& error) {
    run.error = error.what();
  }
  const std::vector<std::string> messages = context.validationMessages();
  for (const std::string& message : messages) std::cerr << "s3d: validation: " << oneLine(message) << '\n';
  run.validationMessages = messages.size();
  if (run.report && messages.empty()) outputs.commit();
  return run;
}

// "the Vulkan validation layer reported N message(s)" through fail().
int failValidation(std::size_t messages);
std::optional<double> parseNumber(const std::string& text);
std::string formatMs(const std::optional<double>& ms);

// A finite float in [low, high] (open at an end when lowOpen / highOpen), judged as the float it is stored in
// (1e-300 is 0 there); CLI11 puts the option's name before the message.
CLI::Validator floatRange(double low, double high, bool lowOpen, const std::string& what, bool highOpen = false);
// "WxH" with both parts in [1, maxSize].
bool parseResolution(const std::string& text, std::uint32_t maxSize, std::uint32_t& width, std::uint32_t& height);
CLI::Validator resolutionValidator(std::uint32_t maxSize);

// --frame N: a whole number >= 0 (CLI11 would wrap "-1" around to 18446744073709551615).
CLI::Validator frameNumberValidator();

// Throws std::invalid_argument "<option> <reason>" for the first of `options` given on `command`: an option that
// does nothing in the mode the command line chose is an error naming the mode, never silently ignored.
void rejectGiven(const CLI::App& command, const std::vector<std::string>& options, const std::string& reason);

// --hybrid-cell and --hybrid-score-floor into `parameters`; `whose` starts their help ("--method hybrid: the
// classification's").
void addHybridClassificationOptions(CLI::App& command, stereo::StereoParameters& parameters, const std::string& whose);

// --max-separation, --zero-parallax-distance, --edge-crop, --method, --taps, --iterations, --hybrid-budget,
// --hybrid-cell, --hybrid-score-floor and --hybrid-base on `command`, their defaults read from
// stereo::StereoParameters (the help prints what a run uses); call finish() after parsing to turn the method name
// into StereoParameters::method and validate. With offerAuto, --method also takes "auto" (finish() then sets
// `automatic` and leaves parameters.method).
struct StereoOptions {
  stereo::StereoParameters parameters;
  std::string method = stereo::methodName(stereo::StereoParameters{}.method);
  std::string hybridBase = stereo::methodName(stereo::StereoParameters{}.hybridBase);
  bool automatic = false;
  void add(CLI::App& command, const std::string& depthUnits, bool offerAuto = false);
  void finish();
  // --taps without the search method or --iterations without the iterative one (a hybrid's: its base), and
  // --hybrid-budget / --hybrid-base without the hybrid method, are errors naming the method (`parameters`: what
  // the run uses, after a profile or --method auto).
  static void requireMethodOptionsApply(const CLI::App& command, const stereo::StereoParameters& parameters);
  // With the disparity budget on, the budget chooses maxSeparation and the zero-parallax distance every frame:
  // giving either is an error that says so and how to set them (--disparity-budget off).
  static void rejectSeparationUnderBudget(const CLI::App& command, const std::string& budgetRule);
};

// --memory-limit SIZE (e.g. 4GiB): the most memory a run may plan for, below the machine's available memory.
void addMemoryLimitOption(CLI::App& command, std::optional<std::uint64_t>& limit);

// --device and --validation.
void addDeviceOptions(CLI::App& command, vk::ContextOptions& options);

void listDevices();

}  // namespace s3d::cli
