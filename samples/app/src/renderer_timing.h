#pragma once
// `s3d bench`'s renderer timings: median frame and pass times of repeated renders, and the masked-render cost
// at a range of mask shares (the hybrid stereo method renders only part of each eye).
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "s3d/app/bench_job.h"
#include "s3d/image.h"
#include "s3d/renderer/deferred_renderer.h"

namespace s3d::app::detail {

// The median of the samples present (timestamps a device did not give are left out); empty when none is.
std::optional<double> medianOf(const std::vector<std::optional<double>>& samples);

// Renders `view` `repeat` times after `warmUp` of untimed frames; the median whole-frame time and the median
// time of each pass (first frame's order).
std::pair<std::optional<double>, std::vector<renderer::PassTiming>> timeFrames(
    renderer::DeferredRenderer& deferred, const renderer::ViewMatrices& view, int repeat,
    const renderer::ShadeMask& mask = {}, std::chrono::milliseconds warmUp = std::chrono::milliseconds(500));

// The process's user + system CPU time per render of `view`, over `repeat` renders (a CPU device's work).
double processCpuMsPerFrame(renderer::DeferredRenderer& deferred, const renderer::ViewMatrices& view, int repeat);

// Mask shares the bench times: nothing, the hybrid method's typical budgets, everything.
inline constexpr double kMaskedRenderShares[] = {0.0, 0.05, 0.2, 1.0};

// A shade mask (1 = shade) of round(share x pixels) pixels picked as the hybrid method picks them: the largest
// step in log depth to a 4-neighbour first (depth edges, near and far alike; sky steps are the largest), ties
// broken by a fixed pixel hash, so the flat remainder is scattered rather than a block.
std::vector<std::uint32_t> depthEdgeMask(const DepthImage& depth, double share);

// The center view rendered with depthEdgeMask at each kMaskedRenderShares share (`deferred` holds the scene and
// the unmasked center view's depth must be its last render).
std::vector<MaskedRenderRow> timeMaskedRenders(vk::Context& context, renderer::DeferredRenderer& deferred,
                                               const renderer::ViewMatrices& view, const std::string& scene, int repeat);

std::string maskedRenderMarkdown(const std::vector<MaskedRenderRow>& rows, int repeat);

}  // namespace s3d::app::detail
