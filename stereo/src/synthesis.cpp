#include "s3d/stereo/synthesis.h"

#include <cstring>
#include <stdexcept>

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

// Counts the pixels the iterative method marked as filled (alpha 0) and makes them opaque again.
std::uint64_t countAndClearFillMarks(ImageRGBA8& eye) {
  std::uint64_t filled = 0;
  for (std::size_t i = 3; i < eye.pixels.size(); i += 4)
    if (eye.pixels[i] == 0) {
      ++filled;
      eye.pixels[i] = 255;
    }
  return filled;
}

template <typename Pass, typename Constants>
SynthesisResult run(vk::Context& context, const Pass& pass, const Constants& constants, const vk::Image& color,
                    const vk::Image& depth) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  vk::Image left = vk::createImage(context, StereoPass::kColorFormat, color.width, color.height, usage);
  vk::Image right = vk::createImage(context, StereoPass::kColorFormat, color.width, color.height, usage);
  vk::TimestampQueries timestamps(context, 2);
  for (bool timed : {false, true}) {
    context.submitAndWait([&](VkCommandBuffer cmd) {
      StereoPass::recordInputBarriers(cmd, color, depth, left, right);
      if (timed && timestamps.supported()) {
        timestamps.reset(cmd);
        timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      }
      pass.record(cmd, color, depth, left, right, constants);
      if (timed && timestamps.supported()) timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      StereoPass::recordInputRelease(cmd, color, depth);
    });
  }
  SynthesisResult result{{readEye(context, left), readEye(context, right)}, timestamps.elapsedMs(0, 1), 0, 0};
  return result;
}

}  // namespace

SynthesisResult synthesizeTimed(vk::Context& context, const vk::Image& centerColor, const vk::Image& linearDepth,
                                const StereoParameters& parameters) {
  if (centerColor.format != StereoPass::kColorFormat || linearDepth.format != StereoPass::kDepthFormat)
    throw std::invalid_argument("stereo synthesis needs RGBA8 unorm color and R32 float linear depth");
  if (parameters.method == StereoMethod::Iterative) {
    const IterativeStereoPass pass(context);
    const gpu::IterativeConstants constants =
        makeIterativeConstants(parameters, parameters.iterations, centerColor.width, centerColor.height);
    SynthesisResult result = run(context, pass, constants, centerColor, linearDepth);
    result.filledLeft = countAndClearFillMarks(result.eyes.left);
    result.filledRight = countAndClearFillMarks(result.eyes.right);
    return result;
  }
  const StereoPass pass(context);
  return run(context, pass, makeStereoConstants(parameters, centerColor.width, centerColor.height), centerColor,
             linearDepth);
}

}  // namespace s3d::stereo
