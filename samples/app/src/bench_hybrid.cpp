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
        "Masked: the share of each eye's compared pixels rendered from the eye camera (left / right). Times: the base\n"
        "displacement, the classification (classify, threshold, masks), both eyes' G-buffer rasterization, both eyes'\n"
        "other renderer passes (shadows, lighting and resolve of the masked pixels) and both composites; / eye: the\n"
        "total over one reference eye. PSNR and SSIM left / right against the two-pass reference.\n\n"
        "| scene | sep % | budget | masked % | displace ms | classify ms | geometry ms | shading ms | composite ms | "
        "total ms | / eye | PSNR all | halo | disocclusion | SSIM |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchRow* row : rows) {
    const HybridTimings& t = row->hybridTimings ? *row->hybridTimings : HybridTimings{};
    md << "| " << row->scene << " | " << percentText(row->maxSeparation) << " | " << format("%g", row->setting.budget)
       << " | " << shareText(row->maskedShareLeft) << " / " << shareText(row->maskedShareRight) << " | "
       << msText(t.displacement) << " | " << msText(t.classification) << " | " << msText(t.eyeGeometry) << " | "
       << msText(t.maskedShading) << " | " << msText(t.composite) << " | " << msText(row->stereoGpuMs) << " | "
       << ratioText(ratio(row->stereoGpuMs, row->referenceEyeGpuMs)) << " | "
       << dbPair(row->left.display.psnrDb, row->right.display.psnrDb) << " | "
       << dbPair(row->left.halo.psnrDb, row->right.halo.psnrDb) << " | "
       << dbPair(row->left.disocclusion.psnrDb, row->right.disocclusion.psnrDb) << " | "
       << format("%.4f", row->left.display.ssim) << " / " << format("%.4f", row->right.display.ssim) << " |\n";
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
