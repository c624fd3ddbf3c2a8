#pragma once
// GPU time of command ranges from Vulkan timestamp queries.
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/vk/context.h"
#include "s3d/vk/unique.h"

namespace s3d::vk {

class TimestampQueries {
 public:
  TimestampQueries(const Context& context, std::uint32_t count);
  void reset(VkCommandBuffer cmd);  // record before the first write
  void write(VkCommandBuffer cmd, std::uint32_t index, VkPipelineStageFlags2 stage);
  // Milliseconds between two written timestamps; nullopt when the device has no timestamps.
  std::optional<double> elapsedMs(std::uint32_t begin, std::uint32_t end) const;
  // A written timestamp's raw ticks (Context::timestampPeriodNs each); nullopt when the device has no timestamps.
  // Ticks of one queue compare; across queues they share the device's time domain (VK_KHR_calibrated_timestamps'
  // DEVICE domain covers every vkCmdWriteTimestamp), which core Vulkan does not promise: check what they give.
  std::optional<std::uint64_t> ticks(std::uint32_t index) const;
  bool supported() const { return supported_; }

 private:
  const Context* context_;
  Unique<VkQueryPool> pool_;
  std::uint32_t count_;
  bool supported_;
};

}  // namespace s3d::vk
