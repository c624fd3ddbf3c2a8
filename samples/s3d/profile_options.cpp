#include "profile_options.h"

#include <algorithm>
#include <stdexcept>

#include "s3d/number_text.h"

namespace s3d::cli {

void ProfileOptions::add(CLI::App& command) {
  command.add_option("--profile", load,
                     "Comfort profile (JSON) with the stereo and comfort parameters; options given on the command "
                     "line override its values");
  command.add_option("--save-profile", save,
                     "Write the effective comfort profile (the --profile file, or the defaults, with the command "
                     "line's options applied) to this JSON file once the run succeeded; never a file the run reads");
  command.add_flag("--allow-negative-parallax", allowNegativeParallax,
                   "Allow negative parallax (in front of the screen); by default the weapon push and the "
                   "zero-parallax distance keep everything at or behind the screen plane");
  command
      .add_option("--display", display,
                  "Display profile of the comfort report: tv55 (55-inch at 2.5 m), monitor27 (27-inch at 0.7 m), "
                  "hmd (90-degree field of view focused at 1.3 m) or a JSON display profile FILE.json")
      ->check([](const std::string& text) -> std::string {
        const std::vector<std::string> names = comfort::builtInDisplayProfileNames();
        const bool isFile = text.size() > 5 && text.compare(text.size() - 5, 5, ".json") == 0;
        if (isFile || std::find(names.begin(), names.end(), text) != names.end()) return {};
        return "expected " + joined(names, ", ") + " or a .json display profile (got '" + text + "')";
      })
      ->capture_default_str();
  command
      .add_option("--disparity-mapping", disparityMapping,
                  "How depth becomes parallax: linear (the seed's m (1 - zpp / depth)) or nonlinear (a per-frame "
                  "monotonic curve over the frame's depth histogram: populated depths get more of the parallax "
                  "range, empty gaps less; the nearest and farthest depth and the screen plane stay put). Needs "
                  "the frame's depth reduction, which runs with it even when --disparity-budget is off")
      ->check(CLI::IsMember({"linear", "nonlinear"}))
      ->capture_default_str();
}

void addDisparityBudgetOption(CLI::App& command, std::string& rule) {
  command
      .add_option("--disparity-budget", rule,
                  "off: maxSeparation and the zero-parallax distance as given; 1deg: chosen per frame from the "
                  "frame's depth range (a GPU reduction) so every pixel's disparity stays within 1 degree on the "
                  "--display, filling 90 % of that budget")
      ->check(CLI::IsMember({"off", "1deg"}))
      ->capture_default_str();
}

comfort::ComfortProfile ProfileOptions::resolve(const CLI::App& command, const StereoOptions& stereo) const {
  comfort::ComfortProfile profile = load.empty() ? comfort::ComfortProfile{} : comfort::loadComfortProfile(load);
  auto given = [&](const char* name) { return command.count(name) > 0; };
  const stereo::StereoParameters& cli = stereo.parameters;
  stereo::StereoParameters& p = profile.stereo;
  if (given("--max-separation")) p.maxSeparation = cli.maxSeparation;
  if (given("--zero-parallax-distance")) p.zeroParallaxDistance = cli.zeroParallaxDistance;
  if (given("--edge-crop")) p.edgeCrop = cli.edgeCrop;
  if (given("--method")) p.method = cli.method;
  if (given("--taps")) p.searchTaps = cli.searchTaps;
  if (given("--iterations")) p.iterations = cli.iterations;
  if (given("--hybrid-budget")) p.hybridBudget = cli.hybridBudget;
  if (given("--hybrid-base")) p.hybridBase = cli.hybridBase;
  if (given("--hybrid-cell")) p.hybridCell = cli.hybridCell;
  if (given("--hybrid-score-floor")) p.hybridScoreFloor = cli.hybridScoreFloor;
  if (given("--weapon-depth-offset")) p.weaponDepthOffset = cli.weaponDepthOffset;
  if (given("--weapon-depth-scale")) p.weaponDepthScale = cli.weaponDepthScale;
  if (given("--display")) profile.display = comfort::resolveDisplayProfile(display);
  if (given("--allow-negative-parallax")) profile.allowNegativeParallax = allowNegativeParallax;
  if (given("--disparity-mapping")) p.disparityMapping = stereo::parseDisparityMapping(disparityMapping);
  if (p.disparityMapping == stereo::DisparityMapping::Nonlinear && p.method == stereo::StereoMethod::Hybrid)
    throw std::invalid_argument(mappingSource(command) + " does not work with " +
                                (given("--method") ? std::string("--method hybrid")
                                                   : "the profile's method hybrid (" + load.string() + ")") +
                                ": the hybrid method renders its masked pixels from one pair of eye cameras, and a "
                                "nonlinear map has none (one per segment of its curve)");
  requireProfileSeparationUnderBudget(profile);
  comfort::validate(profile);  // the overrides may combine into something the profile's rules refuse
  return profile;
}

void ProfileOptions::requireProfileSeparationUnderBudget(const comfort::ComfortProfile& profile) const {
  if (load.empty() || budgetRule() == comfort::DisparityBudgetRule::Off) return;
  const stereo::StereoParameters defaults;
  const auto check = [&](float value, float fallback, const char* key) {
    if (value != fallback)
      throw std::invalid_argument("the profile '" + load.string() + "' sets stereo." + key + " " + numberText(value) +
                                  ", which --disparity-budget " + disparityBudget + " chooses every frame from the "
                                  "frame's depth range; add --disparity-budget off to use it");
  };
  check(profile.stereo.maxSeparation, defaults.maxSeparation, "maxSeparation");
  check(profile.stereo.zeroParallaxDistance, defaults.zeroParallaxDistance, "zeroParallaxDistance");
}

std::string ProfileOptions::mappingSource(const CLI::App& command) const {
  if (command.count("--disparity-mapping") > 0) return "--disparity-mapping " + disparityMapping;
  return "the profile's disparityMapping nonlinear (" + load.string() + ")";
}

void ProfileOptions::addFiles(const CLI::App& command, RunFiles& files) const {
  if (!save.empty()) files.write(save, "--save-profile");
  if (!load.empty()) files.read(load, "--profile");
  if (command.count("--display") > 0) files.readDisplay(display);
}

void ProfileOptions::saveAfterSuccess() const {
  if (!save.empty()) comfort::saveComfortProfile(save, resolved);
}

comfort::DisplayProfile ProfileOptions::resolveDisplay(const CLI::App& command) const {
  if (command.count("--display") > 0) return comfort::resolveDisplayProfile(display);
  return load.empty() ? comfort::ComfortProfile{}.display : comfort::loadComfortProfile(load).display;
}

}  // namespace s3d::cli
