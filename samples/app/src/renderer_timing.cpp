#include "renderer_timing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <sstream>

#include "bench_text.h"
#include "s3d/frame/renderer_timing.h"

namespace s3d::app::detail {

std::vector<MaskedRenderRow> timeMaskedRenders(vk::Context& context, renderer::DeferredRenderer& deferred,
                                               const renderer::ViewMatrices& view, const std::string& scene, int repeat) {
  const DepthImage depth = deferred.readLinearDepth();
  std::vector<MaskedRenderRow> rows;
  for (double share : kMaskedRenderShares) {
    const std::vector<std::uint32_t> values = frame::depthEdgeMask(depth, share);
    vk::Image mask = vk::createImage(context, VK_FORMAT_R32_UINT, deferred.width(), deferred.height(),
                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(context, mask, std::as_bytes(std::span(values)), vk::kComputeWrite);
    auto [frameMs, passes] = frame::timeFrames(deferred, view, repeat, renderer::ShadeMask{&mask, 1});
    const double shaded = double(std::count(values.begin(), values.end(), 1u)) / double(values.size());
    rows.push_back({scene, share, shaded, frameMs, std::move(passes)});
  }
  return rows;
}

std::string maskedRenderMarkdown(const std::vector<MaskedRenderRow>& rows, int repeat) {
  std::ostringstream md;
  md << "Masked center frame (`DeferredRenderer::render` with a `ShadeMask` of the pixels with the largest depth "
        "steps, as the hybrid method picks them), GPU ms, median of "
     << repeat << " warm frames:\n\n";
  std::vector<std::string> names;
  for (const MaskedRenderRow& row : rows)
    for (const renderer::PassTiming& pass : row.passes)
      if (pass.name.rfind("shadow-", 0) != 0 && std::find(names.begin(), names.end(), pass.name) == names.end())
        names.push_back(pass.name);
  md << "| scene | mask share | frame | shadow maps |";
  for (const std::string& name : names) md << ' ' << name << " |";
  md << "\n|---|---|---|---|";
  for (std::size_t i = 0; i < names.size(); ++i) md << "---|";
  md << '\n';
  for (const MaskedRenderRow& row : rows) {
    double shadowMs = 0.0;
    for (const renderer::PassTiming& pass : row.passes)
      if (pass.name.rfind("shadow-", 0) == 0) shadowMs += pass.gpuMs;
    char share[32];
    std::snprintf(share, sizeof(share), "%g %%", std::round(row.shadedShare * 1000.0) / 10.0);
    md << "| " << row.scene << " | " << share << " | " << bench_text::msText(row.frameGpuMs) << " | " << bench_text::msText(shadowMs) << " |";
    for (const std::string& name : names) {
      auto pass = std::find_if(row.passes.begin(), row.passes.end(),
                               [&](const renderer::PassTiming& p) { return p.name == name; });
      md << ' ' << (pass == row.passes.end() ? std::string("-") : bench_text::msText(pass->gpuMs)) << " |";
    }
    md << '\n';
  }
  return md.str();
}

}  // namespace s3d::app::detail
