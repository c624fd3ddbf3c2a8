#pragma once
// One call for any stereo method on GPU images: what `s3d render` and `s3d convert` run.
#include <cstdint>
#include <optional>
#include <vector>

#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

struct SynthesisResult {
  StereoPair eyes;                 // alpha: the center's (the weapon mask), carried by every method
  std::optional<double> gpuMs;     // median of the timed dispatches (both eyes); empty without timestamps
  std::vector<double> gpuMsRuns;   // every timed dispatch, in order
  std::uint64_t filledLeft = 0;    // iterative method: disoccluded pixels filled from the background side
  std::uint64_t filledRight = 0;
};

// Runs parameters.method on centerColor (RGBA8) and linearDepth (R32F), both in vk::kComputeWrite state (as
// the renderer leaves them) and left in that state: once untimed (first use compiles on lavapipe), then
// timedRuns times (>= 1), each its own submission timed with timestamps, then reads both eyes back.
SynthesisResult synthesizeTimed(vk::Context& context, const vk::Image& centerColor, const vk::Image& linearDepth,
                                const StereoParameters& parameters, int timedRuns = 1);

// Median of the samples (the mean of the middle two for an even count); empty for no samples.
std::optional<double> medianMs(std::vector<double> samples);

}  // namespace s3d::stereo
