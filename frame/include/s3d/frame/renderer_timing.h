#pragma once
// Timing s3d's renderer: median frame and pass times of repeated renders after a warm-up, the process's CPU time
// per render (a CPU device's work), and the depth-edge shade masks the hybrid method's masked renders are timed with.
#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "s3d/image.h"
#include "s3d/renderer/deferred_renderer.h"

namespace s3d::frame {

// The median of the samples present (timestamps a device did not give are left out); empty when none is.
std::optional<double> medianOf(const std::vector<std::optional<double>>& samples);

// Renders `view` `repeat` times after `warmUp` of untimed frames; the median whole-frame time and the median
// time of each pass (first frame's order).
std::pair<std::optional<double>, std::vector<renderer::PassTiming>> timeFrames(
    renderer::DeferredRenderer& deferred, const renderer::ViewMatrices& view, int repeat,
    const renderer::ShadeMask& mask = {}, std::chrono::milliseconds warmUp = std::chrono::milliseconds(500));

// The process's user + system CPU time per render of `view`, over `repeat` renders (a CPU device's work).
double processCpuMsPerFrame(renderer::DeferredRenderer& deferred, const renderer::ViewMatrices& view, int repeat);

// A shade mask (1 = shade) of round(share x pixels) pixels picked as the hybrid method picks them: the largest
// step in log depth to a 4-neighbour first (depth edges, near and far alike; sky steps are the largest), ties
// broken by a fixed pixel hash, so the flat remainder is scattered rather than a block.
std::vector<std::uint32_t> depthEdgeMask(const DepthImage& depth, double share);

}  // namespace s3d::frame
