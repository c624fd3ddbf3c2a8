// `s3d regress SUITE.json`: renders a suite of scenes, frames and stereo settings and checks them against the
// two-pass reference and stored baselines (s3d/app/regress_job.h); exits non-zero on a regression.
#include <unistd.h>

#include <iostream>

#include "cli_support.h"
#include "s3d/app/regress_job.h"

namespace s3d::cli {
namespace {

class RegressCommand final : public Command {
 public:
  explicit RegressCommand(CLI::App& app) {
    subcommand = app.add_subcommand(
        "regress",
        "Stereo regression test: render every case of SUITE.json (scene, frames, resolution, stereo parameters), "
        "compare the synthesized eyes with the two-pass reference (per-region statistics with tolerances) and with "
        "the stored baselines (statistics and images), write report.html (self-contained) and regress.json; exit "
        "status 1 when any run regresses");
    CLI::App& regress = *subcommand;
    regress.add_option("suite", suite_, "Suite file (JSON; see README)")->required();
    regress.add_option("--output", options_.outputFolder, "Report folder (created if missing)")->capture_default_str();
    regress.add_flag("--update-baselines", options_.updateBaselines,
                     "Write (or overwrite) every run's baseline instead of comparing with it");
    addMemoryLimitOption(regress, options_.memoryLimitBytes);
    addDeviceOptions(regress, contextOptions_);
  }

  int run() override {
    // The whole suite is validated before a Vulkan start-up.
    const app::RegressSuite suite = app::loadRegressSuite(suite_);
    app::requireRegressMemory(suite, options_);
    RunFiles files;
    files.outputs = app::regressOutputs(suite, options_);
    files.inputs = app::regressInputs(suite, options_);
    files.read(suite_, "suite");
    files.check();
    vk::Context context(contextOptions_);
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    const app::RegressResult result = app::runRegressSuite(
        context, suite, options_, [terminal](std::size_t done, std::size_t total, const std::string& name) {
          if (terminal) std::cerr << "\r[" << done << '/' << total << "] " << name << (done == total ? "\n" : "") << std::flush;
        });
    for (const app::RegressRun& run : result.runs) {
      std::cout << (run.baselineUpdated ? "updated " : run.passed() ? "pass    " : "FAIL    ") << run.name;
      if (!run.problem.empty()) std::cout << ": " << oneLine(run.problem);
      for (const app::RegressCheck& check : run.checks)
        if (!check.passed)
          std::cout << "\n    " << check.what << ": " << check.value << (check.atLeast ? " < " : " > ") << check.limit;
      std::cout << '\n';
    }
    std::cout << "s3d regress: " << result.runs.size() << " runs, " << result.failedRuns << " failed; report "
              << result.htmlReport.string() << '\n';
    const std::vector<std::string> messages = context.validationMessages();
    for (const std::string& message : messages) std::cerr << "s3d: validation: " << oneLine(message) << '\n';
    if (!messages.empty())
      return failValidation(messages.size());
    if (result.failedRuns > 0)
      return fail("regression: " + std::to_string(result.failedRuns) + " of " + std::to_string(result.runs.size()) +
                  " runs failed (see " + result.htmlReport.string() + ")");
    return 0;
  }

 private:
  std::string suite_;
  app::RegressOptions options_;
  vk::ContextOptions contextOptions_;
};

}  // namespace

std::unique_ptr<Command> addRegressCommand(CLI::App& app) { return std::make_unique<RegressCommand>(app); }

}  // namespace s3d::cli
