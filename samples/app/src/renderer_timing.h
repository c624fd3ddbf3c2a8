#pragma once
// `s3d bench`'s masked-render table: the renderer's cost at a range of mask shares (the hybrid stereo method
// renders only part of each eye), timed with s3d/frame/renderer_timing.h.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "s3d/app/bench_job.h"
#include "s3d/frame/renderer_timing.h"
#include "s3d/renderer/deferred_renderer.h"

namespace s3d::app::detail {

// Mask shares the bench times: nothing, the hybrid method's typical budgets, everything.
inline constexpr double kMaskedRenderShares[] = {0.0, 0.05, 0.2, 1.0};

// The center view rendered with depthEdgeMask at each kMaskedRenderShares share (`deferred` holds the scene and
// the unmasked center view's depth must be its last render).
std::vector<MaskedRenderRow> timeMaskedRenders(vk::Context& context, renderer::DeferredRenderer& deferred,
                                               const renderer::ViewMatrices& view, const std::string& scene, int repeat);

std::string maskedRenderMarkdown(const std::vector<MaskedRenderRow>& rows, int repeat);

}  // namespace s3d::app::detail
