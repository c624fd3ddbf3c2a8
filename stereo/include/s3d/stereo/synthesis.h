#pragma once
// One call for any stereo method on GPU images: what `s3d render` and `s3d convert` run.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "s3d/stereo/previous_fill_pass.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// Any displacement method's GPU pass with its constants for one image size (a hybrid: its base), created once
// and recorded any number of times. Inputs and eyes as StereoPass's (RGBA8 color and R32F depth in, RGBA8 eyes
// out, all GENERAL; StereoPass::recordInputBarriers / recordInputRelease apply). The eyes carry the center's
// alpha (the weapon mask); with markFilled the iterative method's alpha is its fill flag instead (0: filled).
class DisplacementPass {
 public:
  DisplacementPass(const vk::Context& context, const StereoParameters& parameters, std::uint32_t width,
                   std::uint32_t height, bool markFilled = false);
  void record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth, const vk::Image& leftEye,
              const vk::Image& rightEye) const {
    record_(cmd, centerColor, linearDepth, leftEye, rightEye);
  }
  StereoMethod method() const { return method_; }

 private:
  StereoMethod method_;
  std::function<void(VkCommandBuffer, const vk::Image&, const vk::Image&, const vk::Image&, const vk::Image&)> record_;
};

// The iterative method's filled pixels per eye (left, right): one untimed dispatch whose alpha is the fill flag.
// Inputs as synthesizeTimed's.
std::pair<std::uint64_t, std::uint64_t> countIterativeFills(vk::Context& context, const vk::Image& centerColor,
                                                           const vk::Image& linearDepth,
                                                           const StereoParameters& parameters);

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

// One frame of the forward method with its disocclusions filled from the previous frame's eyes (parameters.method
// must be Forward): as above, each run the forward pass followed by `fill`, whose history then advances to this
// frame. `motion`: each eye's camera from this frame to the previous one (reprojection.h), on these images.
SynthesisResult synthesizeTimed(vk::Context& context, const vk::Image& centerColor, const vk::Image& linearDepth,
                                const StereoParameters& parameters, PreviousFillPass& fill,
                                const std::array<gpu::EyeMotion, 2>& motion, int timedRuns = 1);

// Median of the samples (the mean of the middle two for an even count); empty for no samples.
std::optional<double> medianMs(std::vector<double> samples);

}  // namespace s3d::stereo
