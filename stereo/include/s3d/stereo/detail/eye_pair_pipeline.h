#pragma once
// What every stereo compute pass shares: four storage images (center color, linear depth, left eye, right
// eye) bound by push descriptors, a block of push constants, one dispatch for both eyes; and a helper that
// runs a pass on CPU images (tests, tools).
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo::detail {

struct EyePairPipeline {
  vk::PipelineLayout layout;
  vk::Unique<VkPipeline> pipeline;
  std::uint32_t pushConstantBytes = 0;
  int groupWidth = 8;  // the shader's local size
  int groupHeight = 8;
};

inline EyePairPipeline createEyePairPipeline(const vk::Context& context, std::span<const std::uint32_t> spirv,
                                             std::uint32_t pushConstantBytes, int groupWidth, int groupHeight) {
  auto storageImage = [](std::uint32_t binding) {
    return VkDescriptorSetLayoutBinding{binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  };
  const VkDescriptorSetLayoutBinding bindings[] = {storageImage(0), storageImage(1), storageImage(2), storageImage(3)};
  EyePairPipeline result;
  result.layout = vk::createPushDescriptorLayout(context, bindings, pushConstantBytes, VK_SHADER_STAGE_COMPUTE_BIT);
  result.pipeline = vk::createComputePipeline(context, result.layout.layout, spirv);
  result.pushConstantBytes = pushConstantBytes;
  result.groupWidth = groupWidth;
  result.groupHeight = groupHeight;
  return result;
}

// Whether the device runs the row-tile shaders: Vulkan guarantees only 128 invocations per workgroup and
// 16 KiB of shared memory, and a row tile needs S3D_STEREO_ROW_TILE invocations and its shared arrays.
inline bool deviceRunsRowTiles(const vk::Context& context) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  const VkPhysicalDeviceLimits& limits = properties.limits;
  const std::uint32_t sharedBytes = 2 * 4 * S3D_STEREO_ROW_TILE_SPAN + 4;  // depth, color, the flat flag
  return limits.maxComputeWorkGroupInvocations >= S3D_STEREO_ROW_TILE &&
         limits.maxComputeWorkGroupSize[0] >= S3D_STEREO_ROW_TILE && limits.maxComputeSharedMemorySize >= sharedBytes;
}

// A pipeline created at first use: a pass that can run either kernel compiles (lavapipe compiles at
// creation) only the ones it runs.
class LazyEyePairPipeline {
 public:
  LazyEyePairPipeline(std::span<const std::uint32_t> spirv, std::uint32_t pushConstantBytes, int groupWidth,
                      int groupHeight)
      : spirv_(spirv), pushConstantBytes_(pushConstantBytes), groupWidth_(groupWidth), groupHeight_(groupHeight) {}
  const EyePairPipeline& get(const vk::Context& context) const {
    if (!pipeline_) pipeline_ = createEyePairPipeline(context, spirv_, pushConstantBytes_, groupWidth_, groupHeight_);
    return *pipeline_;
  }

 private:
  std::span<const std::uint32_t> spirv_;
  std::uint32_t pushConstantBytes_;
  int groupWidth_, groupHeight_;
  mutable std::optional<EyePairPipeline> pipeline_;
};

// Binds the four images, pushes the constants and dispatches one invocation per pixel.
inline void recordEyePairDispatch(VkCommandBuffer cmd, const vk::Context& context, const EyePairPipeline& pass,
                                  const vk::Image& centerColor, const vk::Image& linearDepth, const vk::Image& leftEye,
                                  const vk::Image& rightEye, const void* constants, int width, int height,
                                  const char* passName) {
  for (const vk::Image* image : {&centerColor, &linearDepth, &leftEye, &rightEye})
    if (int(image->width) != width || int(image->height) != height)
      throw std::invalid_argument(std::string(passName) + ": image size does not match the constants");
  VkDescriptorImageInfo infos[4] = {{VK_NULL_HANDLE, centerColor.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, leftEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, rightEye.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[4];
  for (std::uint32_t i = 0; i < 4; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline);
  context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.layout.layout, 0, 4, writes);
  vkCmdPushConstants(cmd, pass.layout.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass.pushConstantBytes, constants);
  auto groups = [](int size, int group) { return std::uint32_t((size + group - 1) / group); };
  vkCmdDispatch(cmd, groups(width, pass.groupWidth), groups(height, pass.groupHeight), 1);
}

// Uploads CPU images, runs the pass once and reads both eyes back.
template <typename Pass, typename Constants>
StereoPair runOnCpuImages(vk::Context& context, const Pass& pass, const ImageRGBA8& center, const DepthImage& linearDepth,
                          const Constants& constants) {
  requireSameSize(center, linearDepth, "stereo pass (color vs depth)");
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = [&](VkFormat format) { return vk::createImage(context, format, center.width, center.height, usage); };
  vk::Image color = image(VK_FORMAT_R8G8B8A8_UNORM), depth = image(VK_FORMAT_R32_SFLOAT);
  vk::Image left = image(VK_FORMAT_R8G8B8A8_UNORM), right = image(VK_FORMAT_R8G8B8A8_UNORM);
  vk::uploadImage(context, color, std::as_bytes(std::span(center.pixels)), vk::kComputeRead);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeRead);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, left, vk::kUndefined, vk::kComputeWrite);
    vk::transition(cmd, right, vk::kUndefined, vk::kComputeWrite);
    pass.record(cmd, color, depth, left, right, constants);
  });
  StereoPair pair{ImageRGBA8(center.width, center.height), ImageRGBA8(center.width, center.height)};
  for (auto [eye, target] : {std::pair{&left, &pair.left}, std::pair{&right, &pair.right}}) {
    std::vector<std::byte> bytes = vk::readbackImage(context, *eye, vk::kComputeWrite);
    std::memcpy(target->pixels.data(), bytes.data(), bytes.size());
  }
  return pair;
}

}  // namespace s3d::stereo::detail
