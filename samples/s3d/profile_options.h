#pragma once
// Comfort profiles on the command line: --profile FILE loads one, --save-profile FILE writes the effective
// one, and every stereo/comfort option given explicitly on the command line overrides the profile's value.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>

#include "cli_support.h"
#include "s3d/comfort/comfort_profile.h"
#include "s3d/comfort/disparity_budget.h"

namespace s3d::cli {

struct ProfileOptions {
  std::filesystem::path load;
  std::filesystem::path save;
  bool allowNegativeParallax = false;
  std::string display = comfort::ComfortProfile{}.display.name;  // the profile's default display
  // `s3d` turns the budget on (the library's jobs default to off, so a host decides for itself).
  std::string disparityBudget = comfort::disparityBudgetRuleName(comfort::DisparityBudgetRule::OneDegree);
  std::string disparityMapping = stereo::disparityMappingName(stereo::DisparityMapping::Linear);

  // --profile, --save-profile, --allow-negative-parallax, --display and --disparity-mapping on `command`.
  void add(CLI::App& command);
  // After parsing (and stereo.finish()): the loaded profile, or the defaults, with every option that was
  // given on `command` (the StereoOptions', --weapon-depth-*, --display, --allow-negative-parallax,
  // --disparity-mapping) applied.
  comfort::ComfortProfile resolve(const CLI::App& command, const StereoOptions& stereo) const;
  // The display alone, as resolve() would give it: --display, else the --profile's, else the default profile's
  // (for modes where the profile's stereo parameters do not apply, e.g. `s3d render --views`).
  comfort::DisplayProfile resolveDisplay(const CLI::App& command) const;
  // Where a nonlinear mapping came from, for errors: "--disparity-mapping nonlinear" or the --profile file's key.
  std::string mappingSource(const CLI::App& command) const;
  // With the budget on, a --profile whose stereo.maxSeparation or zeroParallaxDistance differs from the default is
  // refused as the same command-line options are (the budget would silently replace it).
  void requireProfileSeparationUnderBudget(const comfort::ComfortProfile& profile) const;
  // --save-profile as an output, --profile and a --display FILE.json as inputs.
  void addFiles(const CLI::App& command, RunFiles& files) const;
  comfort::ComfortProfile resolved;  // what the run uses, set by the command: what --save-profile writes
  // Writes `resolved` to --save-profile (when given); called only once the run succeeded, its outputs committed.
  void saveAfterSuccess() const;
  // --disparity-budget, where the command offers it (addDisparityBudgetOption).
  comfort::DisparityBudgetRule budgetRule() const { return comfort::parseDisparityBudgetRule(disparityBudget); }
};

// --disparity-budget off|1deg (default: what `rule` holds).
void addDisparityBudgetOption(CLI::App& command, std::string& rule);

}  // namespace s3d::cli
