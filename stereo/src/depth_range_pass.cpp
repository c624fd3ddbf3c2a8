#include "s3d/stereo/depth_range_pass.h"

#include <cstring>
#include <span>
#include <stdexcept>
#include <string>

#include "s3d/stereo/detail/host_barriers.h"
#include "s3d/vk/timestamps.h"

// clang-format off
#include <s3d_spirv/depth_range_comp.h>
#include <s3d_spirv/depth_range_host_comp.h>
// clang-format on

namespace s3d::stereo {

namespace {

VkWriteDescriptorSet storageBufferWrite(std::uint32_t binding, const VkDescriptorBufferInfo* info) {
  VkWriteDescriptorSet write = vk::uniformBufferWrite(binding, info);
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  return write;
}

DepthReductionShape checkedShape(const vk::Context& context, DepthReductionShape shape) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  const VkPhysicalDeviceLimits& limits = properties.limits;
  if (shape.groupSide == 0 || shape.run == 0 || shape.groupSide > limits.maxComputeWorkGroupSize[0] ||
      shape.groupSide > limits.maxComputeWorkGroupSize[1] ||
      std::uint64_t(shape.groupSide) * shape.groupSide > limits.maxComputeWorkGroupInvocations)
    throw std::invalid_argument("DepthRangePass: the device cannot run workgroups of " + std::to_string(shape.groupSide) +
                                "x" + std::to_string(shape.groupSide) + " invocations with runs of " +
                                std::to_string(shape.run) + " pixels");
  return shape;
}

struct HostDepthPush {
  gpu::LinearDepthParams depthParams;
  int deviceDepth;  // 1: hardware depth to linearize
};

}  // namespace

DepthReductionShape depthReductionShapeFor(const vk::Context& context) {
  return context.isCpuDevice() ? kDepthReductionCpuShape : kDepthReductionGpuShape;
}

DepthRangePass::DepthRangePass(vk::Context& context, std::optional<DepthReductionShape> shape)
    : context_(&context), shape_(checkedShape(context, shape.value_or(depthReductionShapeFor(context)))) {
  const vk::SpecializationWords constants({shape_.groupSide, shape_.groupSide, shape_.run});
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  layout_ = vk::createPushDescriptorLayout(context, bindings, 0, VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context, layout_.layout, spirv_depth_range_comp, constants);
  const VkDescriptorSetLayoutBinding hostBindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  hostLayout_ = vk::createPushDescriptorLayout(context, hostBindings, sizeof(HostDepthPush), VK_SHADER_STAGE_COMPUTE_BIT);
  hostPipeline_ = vk::createComputePipeline(context, hostLayout_.layout, spirv_depth_range_host_comp, constants);
  sampler_ = vk::createNearestClampSampler(context);
  // The atomics land in device memory (host-visible memory may sit across the bus on a discrete GPU); the last
  // workgroup writes the result into the host-visible buffer.
  counters_ = vk::createBuffer(context, sizeof(gpu::DepthRangeCounters),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               vk::MemoryLocation::Device);
  gpu::DepthRangeCounters start{};
  start.range.nearestBits = 0x7f800000u;  // +inf
  vk::uploadBuffer(context, counters_, std::as_bytes(std::span(&start, 1)));
  buffer_ = vk::createBuffer(context, sizeof(gpu::DepthRangeBuffer), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             vk::MemoryLocation::HostVisible);
  std::memcpy(buffer_.mapped, &start.range, sizeof(start.range));  // no frame: an empty range
}

void DepthRangePass::recordReduction(VkCommandBuffer cmd, const std::function<void()>& bindAndPush, std::uint32_t width,
                                     std::uint32_t height) const {
  // The previous dispatch on the queue (this pass's or another's) has reset the counters and written the result.
  vk::computeStorageBarrier(cmd);
  bindAndPush();
  auto groups = [](std::uint32_t size, std::uint32_t perGroup) { return (size + perGroup - 1) / perGroup; };
  vkCmdDispatch(cmd, groups(width, shape_.groupSide * shape_.run), groups(height, shape_.groupSide), 1);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

void DepthRangePass::record(VkCommandBuffer cmd, const vk::Image& linearDepth) const {
  VkDescriptorImageInfo image{VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorBufferInfo buffers[2] = {{counters_.buffer, 0, VK_WHOLE_SIZE}, {buffer_.buffer, 0, VK_WHOLE_SIZE}};
  recordReduction(cmd, [&] {
    VkWriteDescriptorSet writes[3] = {vk::storageImageWrite(0, &image), storageBufferWrite(1, &buffers[0]),
                                      storageBufferWrite(2, &buffers[1])};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 3, writes);
  }, linearDepth.width, linearDepth.height);
}

void DepthRangePass::recordHost(VkCommandBuffer cmd, const HostImage& depth, std::uint32_t width, std::uint32_t height,
                                const HostProjection& projection, float weaponDepthOffset, float weaponDepthScale) const {
  const bool hardware = detail::isHostDepthFormat(depth.format);
  if (!hardware && depth.format != VK_FORMAT_R32_SFLOAT)
    throw std::invalid_argument("DepthRangePass: the host's depth must be D32, D24S8, D16 or R32F linear depth (format " +
                                std::to_string(int(depth.format)) + ")");
  if (!depth.image || !depth.view || width == 0 || height == 0)
    throw std::invalid_argument("DepthRangePass: the host's depth image is missing or empty");
  HostDepthPush push{};
  push.depthParams = linearDepthParams(projection, weaponDepthOffset, weaponDepthScale);  // checks the projection
  push.deviceDepth = hardware ? 1 : 0;
  // Read in its own layout where a compute shader can sample it, else barriered into a read-only one and back.
  const VkImageLayout layout = detail::sampledReadLayout(depth.layout, depth.stage, "DepthRangePass: the host's depth image");
  constexpr VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  constexpr VkAccessFlags2 sampled = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
  const bool barriers = depth.stage != VK_PIPELINE_STAGE_2_NONE;
  if (barriers) {
    detail::HostBarriers<1> before;
    before.image(depth.image, depth.format, depth.layout, depth.stage, depth.access, layout, compute, sampled, depth.layer);
    before.record(cmd);
  }
  VkDescriptorImageInfo image{sampler_.get(), depth.view, layout};
  const VkDescriptorBufferInfo buffers[2] = {{counters_.buffer, 0, VK_WHOLE_SIZE}, {buffer_.buffer, 0, VK_WHOLE_SIZE}};
  recordReduction(cmd, [&] {
    VkWriteDescriptorSet writes[3] = {vk::sampledImageWrite(0, &image), storageBufferWrite(1, &buffers[0]),
                                      storageBufferWrite(2, &buffers[1])};
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, hostPipeline_);
    context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, hostLayout_.layout, 0, 3, writes);
    vkCmdPushConstants(cmd, hostLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
  }, width, height);
  if (barriers) {
    detail::HostBarriers<1> after;
    after.image(depth.image, depth.format, layout, compute, sampled, depth.layout, depth.stage, depth.access, depth.layer);
    after.record(cmd);
  }
}

DepthRange DepthRangePass::result() const {
  gpu::DepthRangeBuffer copy;
  std::memcpy(&copy, buffer_.mapped, sizeof(copy));
  return depthRangeFromBuffer(copy);
}

TimedDepthRange reduceDepthRangeTimed(vk::Context& context, const DepthRangePass& pass, const vk::Image& linearDepth) {
  vk::TimestampQueries timestamps(context, 2);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, linearDepth, vk::kComputeWrite, vk::kComputeRead);
    if (timestamps.supported()) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
    pass.record(cmd, linearDepth);
    if (timestamps.supported()) timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    vk::transition(cmd, linearDepth, vk::kComputeRead, vk::kComputeWrite);
  });
  return {pass.result(), timestamps.elapsedMs(0, 1)};
}

DepthRange reduceDepthRangeOnGpu(vk::Context& context, const DepthImage& linearDepth,
                                 std::optional<DepthReductionShape> shape) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, linearDepth.width, linearDepth.height, usage);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeRead);
  const DepthRangePass pass(context, shape);
  context.submitAndWait([&](VkCommandBuffer cmd) { pass.record(cmd, depth); });
  return pass.result();
}

}  // namespace s3d::stereo
