// benchMarkdown: the sweep's tables (per scene, settings against the seed, targets, memory traffic) or the
// renderer timings' table.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bench_internal.h"
#include "bench_text.h"
#include "renderer_timing.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app {
namespace {

using namespace bench_text;
using namespace bench_detail;


// Error measures over the whole cropped area shown per eye after the PSNR columns: one line per stereo::ErrorStats
// field worth a column (a new field such as SSIM is one more line here and one in statsJson).
struct ErrorMeasure {
  const char* heading;
  double (*value)(const stereo::ErrorStats&);
  const char* pattern;
};
const ErrorMeasure kErrorMeasures[] = {
    {"SSIM", [](const stereo::ErrorStats& s) { return s.ssim; }, "%.4f"},
    {"mean abs. error", [](const stereo::ErrorStats& s) { return s.meanAbsoluteError; }, "%.2f"},
    {"error > 8 levels %", [](const stereo::ErrorStats& s) { return 100.0 * s.shareAbove8; }, "%.1f"},
};

// The PSNR regions of the main table, in column order.
struct ErrorRegion {
  const char* heading;
  stereo::ErrorStats stereo::EyeError::*stats;
};
const ErrorRegion kErrorRegions[] = {{"PSNR all", &stereo::EyeError::display},
                                     {"halo", &stereo::EyeError::halo},
                                     {"disocclusion", &stereo::EyeError::disocclusion},
                                     {"rest", &stereo::EyeError::rest}};
// Regions a scene may not have: a column only in the tables of scenes where they hold pixels.
const ErrorRegion kSceneRegions[] = {{"transparent", &stereo::EyeError::transparent}, {"foliage", &stereo::EyeError::foliage}};

std::string settingDetail(const MethodSetting& setting) {
  const std::string kernel = setting.kernel == stereo::StereoKernel::PerPixel   ? ", per pixel"
                             : setting.kernel == stereo::StereoKernel::RowTiles ? ", row tiles"
                                                                                : "";
  switch (setting.method) {
    case stereo::StereoMethod::Seed: return "Listing 4.5 (3 taps)" + kernel;
    case stereo::StereoMethod::Search: return std::to_string(setting.parameter) + " taps" + kernel;
    case stereo::StereoMethod::Iterative: return std::to_string(setting.parameter) + " iterations" + kernel;
    case stereo::StereoMethod::Forward: return "z-buffered scatter";
    case stereo::StereoMethod::Hybrid: return "budget " + format("%g", double(setting.budget));
  }
  return "";
}

// The heading, the command and how every number was measured; the warm-up the timed frames had.
void writeSweepIntroduction(std::ostream& md, const BenchReport& report) {
  md << "### `s3d bench` on " << report.deviceName << " (" << report.deviceKind << "), " << report.width << "x"
     << report.height << "\n\n";
  md << "Command: `" << report.commandLine << "` (wall time " << format("%.1f", report.wallSeconds) << " s).\n";
  md << "Every time is the median of " << report.repeat
     << " GPU timestamp measurements of warm runs; per scene and separation the center view and both reference eyes\n"
        "are rendered once and every setting runs on that center view. Stereo: both eyes in one dispatch; eye: one\n"
        "two-pass reference eye (the left), timed in back-to-back pairs with the center frame right before each\n"
        "setting. PSNR left / right in dB against the two-pass reference over the cropped\n"
        "area (maxSeparation columns each side) and its regions: halo (within maxSeparation of a center-view depth\n"
        "edge), disocclusion (reference pixels the center view never saw), transparent and foliage (reference pixels\n"
        "covered by transparent surfaces, or whose surface is an alpha cut-out; only for scenes that have them), rest\n"
        "(none of them); the last columns are over the whole cropped area (SSIM: 11x11 Gaussian window on luma,\n"
        "Wang et al. 2004).\n";

  if (!report.rows.empty()) {
    auto [shortest, longest] = std::minmax_element(report.rows.begin(), report.rows.end(), [](const BenchRow& a, const BenchRow& b) {
      return a.frameWarmUpMs < b.frameWarmUpMs;
    });
    const bool cpuDevice = report.deviceKind == "cpu";
    md << "The eye and the center frame were timed after " << format("%.0f", shortest->frameWarmUpMs) << "-"
       << format("%.0f", longest->frameWarmUpMs) << " ms of untimed pairs before each setting"
       << (cpuDevice ? " (a CPU device: the minimum).\n"
                     : " (until they ran at a steady speed: a GPU lowers its clocks\nwhile the host computes metrics).");
    std::vector<std::string> unsettled;
    if (!cpuDevice)
      for (const BenchRow& row : report.rows)
        if (!row.frameWarmUpSettled)
          unsettled.push_back(row.scene + " sep " + percentText(row.maxSeparation) + "% " + row.setting.name());
    if (!unsettled.empty())
      md << " **Not settled** (still changing speed when the warm-up's limit ended it): " << joinedNames(unsettled, ", ")
         << ".";
    if (!cpuDevice) md << "\n";
  }
}

// Per scene: every setting's times and its error per region, both eyes.
void writeSceneTables(std::ostream& md, const BenchReport& report) {
  std::vector<std::string> scenes;
  for (const BenchRow& row : report.rows)
    if (std::find(scenes.begin(), scenes.end(), row.scene) == scenes.end()) scenes.push_back(row.scene);
  for (const std::string& scene : scenes) {
    const BenchRow* first = nullptr;
    for (const BenchRow& row : report.rows)
      if (row.scene == scene && !first) first = &row;
    md << "\n#### " << scene << " (center frame " << msText(first->centerFrameGpuMs) << " ms, depth reduction "
       << msText(first->depthReductionGpuMs) << " ms, nonlinear depth mapping " << msText(first->disparityMapGpuMs)
       << " ms)\n\n";
    std::vector<ErrorRegion> regions(std::begin(kErrorRegions), std::end(kErrorRegions));
    for (const ErrorRegion& region : kSceneRegions)
      if (std::any_of(report.rows.begin(), report.rows.end(), [&](const BenchRow& row) {
            return row.scene == scene && (row.left.*region.stats).pixelCount + (row.right.*region.stats).pixelCount > 0;
          }))
        regions.insert(regions.end() - 1, region);  // before rest
    md << "| method | setting | sep % | stereo ms | stereo / center | stereo / eye |";
    for (const ErrorRegion& region : regions) md << ' ' << region.heading << " |";
    for (const ErrorMeasure& measure : kErrorMeasures) md << ' ' << measure.heading << " |";
    md << "\n|---|---|---|---|---|---|";
    for (std::size_t i = 0; i < regions.size() + std::size(kErrorMeasures); ++i) md << "---|";
    md << '\n';
    for (const BenchRow& row : report.rows) {
      if (row.scene != scene) continue;
      md << "| " << stereo::methodName(row.setting.method) << " | " << settingDetail(row.setting) << " | "
         << percentText(row.maxSeparation) << " | " << msText(row.stereoGpuMs) << " | "
         << ratioText(ratio(row.stereoGpuMs, row.centerFrameGpuMs)) << " | "
         << ratioText(ratio(row.stereoGpuMs, row.referenceEyeGpuMs)) << " |";
      for (const ErrorRegion& region : regions)
        md << ' ' << dbPair((row.left.*region.stats).psnrDb, (row.right.*region.stats).psnrDb) << " |";
      for (const ErrorMeasure& measure : kErrorMeasures)
        md << ' ' << format(measure.pattern, measure.value(row.left.display)) << " / "
           << format(measure.pattern, measure.value(row.right.display)) << " |";
      md << '\n';
    }
  }
}

// Every setting against the seed over all scenes and separations: what the dominance target asks, for all.
void writeSeedComparison(std::ostream& md, const BenchReport& report) {
  const MethodSetting seed{stereo::StereoMethod::Seed, 0};
  md << "\n#### Settings against the seed (halo PSNR gain of the worse eye, over scenes and separations)\n\n"
        "| setting | smallest gain (dB) | mean gain (dB) | largest time / seed | dominates the seed in |\n"
        "|---|---|---|---|---|\n";
  std::vector<MethodSetting> settings;
  for (const BenchRow& row : report.rows)
    if (std::find(settings.begin(), settings.end(), row.setting) == settings.end()) settings.push_back(row.setting);
  for (const MethodSetting& setting : settings) {
    if (setting == seed) continue;
    double smallest = INFINITY, sum = 0.0, largestTime = 0.0;
    std::size_t count = 0, dominating = 0;
    bool timesKnown = true;
    for (const BenchRow& row : report.rows) {
      const BenchRow* seedRow = row.setting == setting ? findRow(report, row.scene, row.maxSeparation, seed) : nullptr;
      if (!seedRow) continue;
      const double gain = std::min(row.left.halo.psnrDb - seedRow->left.halo.psnrDb,
                                   row.right.halo.psnrDb - seedRow->right.halo.psnrDb);
      const std::optional<double> time = ratio(row.stereoGpuMs, seedRow->stereoGpuMs);
      smallest = std::min(smallest, gain);
      sum += gain;
      ++count;
      if (time) largestTime = std::max(largestTime, *time);
      timesKnown = timesKnown && time.has_value();
      if (gain >= kHaloGainTargetDb && time && *time <= kTimeOverSeedTarget) ++dominating;
    }
    if (count == 0) continue;
    md << "| " << setting.name() << " | " << format("%+.2f", smallest) << " | " << format("%+.2f", sum / double(count))
       << " | " << (timesKnown ? format("%.2f", largestTime) + "x" : std::string("n/a")) << " | " << dominating << " of "
       << count << " |\n";
  }
}

// The targets judged on the target setting, each with its cases.
void writeTargets(std::ostream& md, const BenchReport& report) {
  md << "\n#### Targets, judged on `" << report.targetSetting.name() << "`\n\n";
  for (const TargetResult& target : evaluateTargets(report)) {
    md << "- " << target.name << ": " << verdict(target);
    if (!target.note.empty()) md << "; " << target.note;
    md << '\n';
    for (const TargetCase& c : target.cases) md << "  - " << c.scope << ": " << passText(c.pass) << ", " << c.numbers << '\n';
  }
}

// The stereo pass's memory traffic per setting and separation, against the bandwidth's limit when given.
void writeTrafficTable(std::ostream& md, const BenchReport& report) {
  md << "\n#### Memory traffic of the stereo pass (counted from stereo/shaders/)\n\n"
        "Per pixel kernel, per interior pixel and eye: the depth imageLoads (4 B each; seed/search: one per tap,\n"
        "iterative: 8 start taps + 2 x iterations), two color imageLoads (4 B, the horizontal filter) and one\n"
        "imageStore (4 B); a cropped pixel stores both eyes only. Row tiles: each tile loads its run of a row plus the\n"
        "margin each side once (a depth and a color texel, 8 B a column) into shared memory; neighbouring tiles'\n"
        "margins overlap, so DRAM sees between the compulsory bytes (overlap served by the L2 cache) and the counted\n"
        "ones; seed/search fetches of near surfaces beyond the margin are data-dependent and not counted. Compulsory:\n"
        "color and depth read once, both eyes written once (16 B per pixel).\n\n";
  md << "| setting | kernel | sep % | read MB | written MB | B / pixel | compulsory MB |";
  if (report.bandwidthGBs) md << " limit ms | compulsory limit ms | stereo ms (median of scenes) | stereo / limit |";
  md << "\n|---|---|---|---|---|---|---|";
  if (report.bandwidthGBs) md << "---|---|---|---|";
  md << '\n';
  std::vector<std::pair<MethodSetting, float>> seen;
  for (const BenchRow& row : report.rows) {
    if (row.setting.method == stereo::StereoMethod::Hybrid) continue;  // renders pixels: not a pass's traffic
    const std::pair key{row.setting, row.maxSeparation};
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    const double pixels = double(report.width) * double(report.height);
    md << "| " << row.setting.name() << " | " << (row.traffic.rowTiles ? "row tiles" : "per pixel") << " | "
       << percentText(row.maxSeparation) << " | " << format("%.1f", double(row.traffic.bytesRead) / 1e6) << " | "
       << format("%.1f", double(row.traffic.bytesWritten) / 1e6) << " | "
       << format("%.1f", double(row.traffic.total()) / pixels) << " | "
       << format("%.1f", double(row.traffic.compulsoryBytes) / 1e6) << " |";
    if (report.bandwidthGBs) {
      std::vector<double> times;
      for (const BenchRow& other : report.rows)
        if (other.setting == row.setting && other.maxSeparation == row.maxSeparation && other.stereoGpuMs)
          times.push_back(*other.stereoGpuMs);
      const std::optional<double> median = stereo::medianMs(times);
      const double bytesPerMs = *report.bandwidthGBs * 1e6;
      const double limitMs = double(row.traffic.total()) / bytesPerMs;
      md << ' ' << msText(limitMs) << " | " << msText(double(row.traffic.compulsoryBytes) / bytesPerMs) << " | "
         << msText(median) << " | " << (median ? format("%.2f", *median / limitMs) + "x" : "n/a") << " |";
    }
    md << '\n';
  }
}

std::string sweepMarkdown(const BenchReport& report) {
  std::ostringstream md;
  writeSweepIntroduction(md, report);
  writeSceneTables(md, report);
  writeSeedComparison(md, report);
  writeTargets(md, report);
  md << hybridBenchMarkdown(report);
  writeTrafficTable(md, report);
  return md.str();
}

std::string rendererMarkdown(const BenchReport& report) {
  std::ostringstream md;
  md << "### `s3d bench --renderer` on " << report.deviceName << " (" << report.deviceKind << "), " << report.width
     << "x" << report.height << "\n\n";
  md << "Command: `" << report.commandLine << "` (wall time " << format("%.1f", report.wallSeconds) << " s).\n";
  md << "Center frame GPU time per scene and per pass (ms), each the median of " << report.repeat
     << " warm frames; a pass the scene does not need does not run (-). G-buffer shading: "
     << report.gbufferShading << ".\n\n";
  std::vector<std::string> passNames;
  for (const RendererRow& row : report.rendererRows)
    for (const renderer::PassTiming& pass : row.passes)
      if (std::find(passNames.begin(), passNames.end(), pass.name) == passNames.end()) passNames.push_back(pass.name);
  const std::uint32_t band = report.rendererRows.empty() ? 0 : report.rendererRows.front().guardBandColumns;
  md << "Guard band: the center frame " << band << " columns wider on each side (`s3d render`'s default at "
     << "this separation); ratio: the median of " << report.repeat << " back-to-back pairs of wide / plain frame.\n\n";
  const bool cpuTimes = std::any_of(report.rendererRows.begin(), report.rendererRows.end(),
                                    [](const RendererRow& row) { return row.cpuTimePerFrameMs.has_value(); });
  if (cpuTimes)
    md << "CPU time: the process's user + system time per center frame over " << report.repeat
       << " more frames (the device's work summed over its threads), which other load on the machine disturbs "
          "less than the timestamps.\n\n";
  md << "| scene | triangles | frame |" << (cpuTimes ? " CPU time |" : "") << " guard band frame | ratio |";
  for (const std::string& name : passNames) md << ' ' << name << " |";
  md << "\n|---|---|---|" << (cpuTimes ? "---|" : "") << "---|---|";
  for (std::size_t i = 0; i < passNames.size(); ++i) md << "---|";
  md << '\n';
  for (const RendererRow& row : report.rendererRows) {
    md << "| " << row.scene << " | " << row.triangles << " | " << msText(row.frameGpuMs) << " | ";
    if (cpuTimes) md << msText(row.cpuTimePerFrameMs) << " | ";
    md << msText(row.guardBandFrameGpuMs) << " | " << ratioText(row.guardBandRatio) << " |";
    for (const std::string& name : passNames) {
      auto pass = std::find_if(row.passes.begin(), row.passes.end(),
                               [&](const renderer::PassTiming& p) { return p.name == name; });
      md << ' ' << (pass == row.passes.end() ? std::string("-") : msText(pass->gpuMs)) << " |";
    }
    md << '\n';
  }
  if (!report.maskedRenderRows.empty()) md << '\n' << detail::maskedRenderMarkdown(report.maskedRenderRows, report.repeat);
  return md.str();
}

}  // namespace

std::string benchMarkdown(const BenchReport& report) {
  return report.rendererOnly ? rendererMarkdown(report) : sweepMarkdown(report);
}

}  // namespace s3d::app
