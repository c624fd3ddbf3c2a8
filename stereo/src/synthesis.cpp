#include "s3d/stereo/synthesis.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

#include "s3d/stereo/forward_pass.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/iterative_pass.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/vk/timestamps.h"

namespace s3d::stereo {
namespace {

ImageRGBA8 readEye(vk::Context& context, const vk::Image& image) {
  ImageRGBA8 eye(image.width, image.height);
  std::vector<std::byte> bytes = vk::readbackImage(context, image, vk::kComputeWrite);
  std::memcpy(eye.pixels.data(), bytes.data(), bytes.size());
  return eye;
}

// Pixels the iterative method flagged as filled (markFilled: alpha 0).
std::uint64_t countFillFlags(const ImageRGBA8& eye) {
  std::uint64_t filled = 0;
  for (std::size_t i = 3; i < eye.pixels.size(); i += 4) filled += eye.pixels[i] == 0 ? 1 : 0;
  return filled;
}

// Pass: anything with record(cmd, color, depth, left, right) (a DisplacementPass, the forward pass with its fill).
template <typename Pass>
SynthesisResult run(vk::Context& context, const Pass& pass, const vk::Image& color, const vk::Image& depth,
                    int timedRuns) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  vk::Image left = vk::createImage(context, StereoPass::kColorFormat, color.width, color.height, usage);
  vk::Image right = vk::createImage(context, StereoPass::kColorFormat, color.width, color.height, usage);
  vk::TimestampQueries timestamps(context, 2);
  std::vector<double> gpuMsRuns;
  // Untimed warm-up: once (pipeline compilation), and with several timed runs (a benchmark) for at least
  // kWarmUp of wall time. On an H100 that had idled through seconds of host work this alone did not bring the
  // clocks back (the pass timed 4x slow); s3d bench also renders center frames for 500 ms first.
  constexpr std::chrono::milliseconds kWarmUp{50};
  const auto warmUpStart = std::chrono::steady_clock::now();
  int warmUpRuns = 0;
  auto warmingUp = [&] {
    return warmUpRuns == 0 || (timedRuns > 1 && std::chrono::steady_clock::now() - warmUpStart < kWarmUp);
  };
  for (int run = 0; run < timedRuns;) {
    const bool timed = !warmingUp();
    if (!timed) ++warmUpRuns;
    context.submitAndWait([&](VkCommandBuffer cmd) {
      StereoPass::recordInputBarriers(cmd, color, depth, left, right);
      if (timed && timestamps.supported()) {
        timestamps.reset(cmd);
        timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      }
      pass.record(cmd, color, depth, left, right);
      if (timed && timestamps.supported()) timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      StereoPass::recordInputRelease(cmd, color, depth);
    });
    if (timed) {
      if (std::optional<double> ms = timestamps.elapsedMs(0, 1)) gpuMsRuns.push_back(*ms);
      ++run;
    }
  }
  SynthesisResult result{{readEye(context, left), readEye(context, right)}, medianMs(gpuMsRuns), gpuMsRuns, 0, 0};
  return result;
}

// The forward pass and the previous-frame fill as one pass for run().
struct ForwardWithPreviousFill {
  const ForwardStereoPass& forward;
  const PreviousFillPass& fill;
  const std::array<gpu::EyeMotion, 2>& motion;
  gpu::ForwardConstants constants;
  void record(VkCommandBuffer cmd, const vk::Image& color, const vk::Image& depth, const vk::Image& left,
              const vk::Image& right) const {
    forward.record(cmd, color, depth, left, right, constants);
    fill.record(cmd, forward, left, right, constants, motion);
  }
};

void requireRendererImages(const vk::Image& centerColor, const vk::Image& linearDepth) {
  if (centerColor.format != StereoPass::kColorFormat || linearDepth.format != StereoPass::kDepthFormat)
    throw std::invalid_argument("stereo synthesis needs RGBA8 unorm color and R32 float linear depth");
}

}  // namespace

DisplacementPass::DisplacementPass(const vk::Context& context, const StereoParameters& methodParameters,
                                   std::uint32_t width, std::uint32_t height, bool markFilled) {
  const StereoParameters parameters = displacementParameters(methodParameters);
  method_ = parameters.method;
  // Each pass owns its pipelines; the closure owns the pass and its constants.
  if (parameters.method == StereoMethod::Iterative) {
    auto pass = std::make_shared<IterativeStereoPass>(context, parameters.kernel);
    gpu::IterativeConstants constants = makeIterativeConstants(parameters, parameters.iterations, width, height);
    constants.markFilled = markFilled ? 1 : 0;
    record_ = [pass, constants](VkCommandBuffer cmd, const vk::Image& c, const vk::Image& d, const vk::Image& l,
                                const vk::Image& r) { pass->record(cmd, c, d, l, r, constants); };
  } else if (parameters.method == StereoMethod::Forward) {
    auto pass = std::make_shared<ForwardStereoPass>(context, parameters.kernel);
    const gpu::ForwardConstants constants = makeForwardConstants(parameters, width, height);
    record_ = [pass, constants](VkCommandBuffer cmd, const vk::Image& c, const vk::Image& d, const vk::Image& l,
                                const vk::Image& r) { pass->record(cmd, c, d, l, r, constants); };
  } else {
    auto pass = std::make_shared<StereoPass>(context, parameters.kernel);
    const gpu::StereoConstants constants = makeStereoConstants(parameters, width, height);
    record_ = [pass, constants](VkCommandBuffer cmd, const vk::Image& c, const vk::Image& d, const vk::Image& l,
                                const vk::Image& r) { pass->record(cmd, c, d, l, r, constants); };
  }
}

std::pair<std::uint64_t, std::uint64_t> countIterativeFills(vk::Context& context, const vk::Image& centerColor,
                                                           const vk::Image& linearDepth,
                                                           const StereoParameters& methodParameters) {
  const DisplacementPass flags(context, methodParameters, centerColor.width, centerColor.height, true);
  const SynthesisResult marked = run(context, flags, centerColor, linearDepth, 1);
  return {countFillFlags(marked.eyes.left), countFillFlags(marked.eyes.right)};
}

std::optional<double> medianMs(std::vector<double> samples) {
  if (samples.empty()) return std::nullopt;
  const std::size_t middle = samples.size() / 2;
  std::nth_element(samples.begin(), samples.begin() + std::ptrdiff_t(middle), samples.end());
  const double upper = samples[middle];
  if (samples.size() % 2 == 1) return upper;
  const double lower = *std::max_element(samples.begin(), samples.begin() + std::ptrdiff_t(middle));
  return 0.5 * (lower + upper);
}

SynthesisResult synthesizeTimed(vk::Context& context, const vk::Image& centerColor, const vk::Image& linearDepth,
                                const StereoParameters& methodParameters, int timedRuns) {
  const StereoParameters parameters = displacementParameters(methodParameters);
  if (timedRuns < 1)
    throw std::invalid_argument("stereo synthesis: timedRuns must be at least 1 (got " + std::to_string(timedRuns) + ")");
  requireRendererImages(centerColor, linearDepth);
  const DisplacementPass pass(context, parameters, centerColor.width, centerColor.height);
  SynthesisResult result = run(context, pass, centerColor, linearDepth, timedRuns);
  if (parameters.method == StereoMethod::Iterative)
    std::tie(result.filledLeft, result.filledRight) = countIterativeFills(context, centerColor, linearDepth, parameters);
  return result;
}

SynthesisResult synthesizeTimed(vk::Context& context, const vk::Image& centerColor, const vk::Image& linearDepth,
                                const StereoParameters& parameters, PreviousFillPass& fill,
                                const std::array<gpu::EyeMotion, 2>& motion, int timedRuns) {
  if (timedRuns < 1)
    throw std::invalid_argument("stereo synthesis: timedRuns must be at least 1 (got " + std::to_string(timedRuns) + ")");
  requireRendererImages(centerColor, linearDepth);
  if (parameters.method != StereoMethod::Forward)
    throw std::invalid_argument("the previous-frame fill needs the forward method");
  const ForwardStereoPass forward(context, parameters.kernel, ForwardKeys::Kept);  // the fill reads its z-buffers
  const ForwardWithPreviousFill pass{forward, fill, motion,
                                     makeForwardConstants(parameters, centerColor.width, centerColor.height)};
  SynthesisResult result = run(context, pass, centerColor, linearDepth, timedRuns);
  fill.advance();
  return result;
}

}  // namespace s3d::stereo
