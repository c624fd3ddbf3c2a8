// `s3d bench`'s hybrid section: per scene and separation the budget against the masked share, the GPU time of
// each part (both eyes) and the error, and the hybrid method's targets on its default budget.
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "bench_text.h"
#include "s3d/app/bench_job.h"

namespace s3d::app {
namespace {

using namespace bench_text;

// The hybrid method's targets, on the default budget at this separation, in both eyes.
constexpr float kHybridTargetSeparation = 0.02f;
constexpr double kHybridWholeTargetDb = 35.0;
constexpr double kHybridHaloTargetDb = 32.0;
constexpr double kHybridTimeOverEyeTarget = 0.5;  // both eyes against one reference eye

std::string shareText(const std::optional<double>& share) { return share ? format("%.1f", 100.0 * *share) : "n/a"; }

}  // namespace

std::string hybridBenchMarkdown(const BenchReport& report) {
  std::vector<const BenchRow*> rows;
  for (const BenchRow& row : report.rows)
    if (row.setting.method == stereo::StereoMethod::Hybrid) rows.push_back(&row);
  if (rows.empty()) return "";
  std::ostringstream md;
  md << "\n#### Hybrid: budget against error and time (both eyes)\n\n"
        "Masked: the share of each eye's compared pixels rendered from the eye camera (left / right). Surfaces: how\n"
        "the masked pixels' surfaces were found, ray cast (with ambient occlusion the region around them takes the\n"
        "base's depth, or with --hybrid-surfaces raycast-region is cast too), rasterized (G-buffer and occlusion\n"
        "depth), or the left eye rasterized beside the right eye's rays (raster + ray cast). Times: the base\n"
        "displacement, the classification (classify, threshold, masks), each timed alone; the front: both as the\n"
        "frame runs them, with the work no mask decides beside them (the base's depth, and with one renderer per\n"
        "eye the ray-cast eyes' triangle setup and screen bins), from first start to last end; both eyes' surfaces\n"
        "(with the base's depth timed alone), both eyes' other renderer passes (mask tiles, occlusion, lighting and\n"
        "resolve of the masked pixels; the shadow maps are the center frame's), the eye renders together (surfaces\n"
        "less the base's depth, and shading: their sum one eye after the other, the span from first start to last\n"
        "end where the eyes render at once, marked *) and both composites; total: the front, the eye renders and\n"
        "the composites; / eye: the total over one reference eye.\n"
        "PSNR and SSIM left / right against the two-pass reference.\n\n"
        "| scene | sep % | budget | masked % | surfaces | displace ms | classify ms | front ms | surfaces ms | "
        "shading ms | eye renders ms | composite ms | total ms | / eye | PSNR all | halo | disocclusion | SSIM |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchRow* row : rows) {
    const frame::HybridTimings& t = row->hybridTimings ? *row->hybridTimings : frame::HybridTimings{};
    md << "| " << row->scene << " | " << percentText(row->maxSeparation) << " | " << format("%g", row->setting.budget)
       << " | " << shareText(row->maskedShareLeft) << " / " << shareText(row->maskedShareRight) << " | "
       << (t.mixedSurfaces ? "raster + ray cast" : t.raycastSurfaces ? "ray cast" : "raster") << " | " << msText(t.displacement) << " | " << msText(t.classification) << " | " << msText(t.frontSpan) << " | "
       << msText(t.eyeGeometry) << " | "
       << msText(t.maskedShading) << " | " << msText(t.eyeRenders) << (t.concurrentEyes ? "*" : "") << " | "
       << msText(t.composite) << " | " << msText(row->stereoGpuMs) << " | "
       << ratioText(ratio(row->stereoGpuMs, row->referenceEyeGpuMs)) << " | "
       << dbPair(row->left.display.psnrDb, row->right.display.psnrDb) << " | "
       << dbPair(row->left.halo.psnrDb, row->right.halo.psnrDb) << " | "
       << dbPair(row->left.disocclusion.psnrDb, row->right.disocclusion.psnrDb) << " | "
       << format("%.4f", row->left.display.ssim) << " / " << format("%.4f", row->right.display.ssim) << " |\n";
  }

  // Per pass: the classification's three, then each renderer pass of the eye renders, both eyes summed (an eye
  // with nothing masked is not rendered; the shadow maps are the center frame's, so none runs here).
  std::vector<std::string> eyePasses;
  for (const BenchRow* row : rows)
    if (row->hybridTimings)
      for (const auto* passes : {&row->hybridTimings->leftEyePasses, &row->hybridTimings->rightEyePasses})
        for (const renderer::PassTiming& pass : *passes)
          if (std::find(eyePasses.begin(), eyePasses.end(), pass.name) == eyePasses.end()) eyePasses.push_back(pass.name);
  md << "\n#### Hybrid: GPU time per pass (both eyes, ms)\n\n| scene | sep % | budget | classify | threshold | mask |";
  for (const std::string& name : eyePasses) md << " eye " << name << " |";
  md << "\n|---|---|---|---|---|---|";
  for (std::size_t i = 0; i < eyePasses.size(); ++i) md << "---|";
  md << "\n";
  for (const BenchRow* row : rows) {
    const frame::HybridTimings& t = row->hybridTimings ? *row->hybridTimings : frame::HybridTimings{};
    md << "| " << row->scene << " | " << percentText(row->maxSeparation) << " | " << format("%g", row->setting.budget)
       << " | " << msText(t.classify) << " | " << msText(t.threshold) << " | " << msText(t.mask) << " |";
    for (const std::string& name : eyePasses) {
      std::optional<double> both;
      for (const auto* passes : {&t.leftEyePasses, &t.rightEyePasses})
        for (const renderer::PassTiming& pass : *passes)
          if (pass.name == name) both = both.value_or(0.0) + pass.gpuMs;
      md << " " << (both ? msText(both) : std::string("-")) << " |";
    }
    md << "\n";
  }

  const float budget = stereo::StereoParameters{}.hybridBudget;
  md << "\n#### Hybrid targets (default budget " << format("%g", budget) << ", separation "
     << percentText(kHybridTargetSeparation) << " %, both eyes): whole-image PSNR >= " << format("%g", kHybridWholeTargetDb)
     << " dB, halo PSNR >= " << format("%g", kHybridHaloTargetDb) << " dB, time <= " << format("%g", kHybridTimeOverEyeTarget)
     << " of one reference eye\n\n";
  bool any = false;
  for (const BenchRow* row : rows) {
    if (row->setting.budget != budget || row->maxSeparation != kHybridTargetSeparation) continue;
    any = true;
    const std::optional<double> overEye = ratio(row->stereoGpuMs, row->referenceEyeGpuMs);
    const bool whole = std::min(row->left.display.psnrDb, row->right.display.psnrDb) >= kHybridWholeTargetDb;
    const bool halo = std::min(row->left.halo.psnrDb, row->right.halo.psnrDb) >= kHybridHaloTargetDb;
    md << "- " << row->scene << ": whole " << (whole ? "pass" : "fail") << " ("
       << dbPair(row->left.display.psnrDb, row->right.display.psnrDb) << " dB), halo " << (halo ? "pass" : "fail") << " ("
       << dbPair(row->left.halo.psnrDb, row->right.halo.psnrDb) << " dB), time "
       << (overEye ? (*overEye <= kHybridTimeOverEyeTarget ? "pass" : "fail") : "n/a") << " (" << ratioText(overEye)
       << " of an eye)\n";
  }
  if (!any) md << "- not measured: the sweep has no row at the default budget and this separation\n";
  return md.str();
}

}  // namespace s3d::app
