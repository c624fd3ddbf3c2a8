#include "s3d/vk/timestamps.h"

#include <vector>

#include "s3d/vk/check.h"

namespace s3d::vk {

TimestampQueries::TimestampQueries(const Context& context, std::uint32_t count)
    : context_(&context), count_(count), supported_(context.timestampPeriodNs() > 0.0) {
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count;
  VkQueryPool pool = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateQueryPool(context.device(), &info, context.allocator(), &pool));
  pool_ = Unique<VkQueryPool>(context.device(), pool, vkDestroyQueryPool, context.allocator());
}

void TimestampQueries::reset(VkCommandBuffer cmd) { vkCmdResetQueryPool(cmd, pool_, 0, count_); }

void TimestampQueries::write(VkCommandBuffer cmd, std::uint32_t index, VkPipelineStageFlags2 stage) {
  vkCmdWriteTimestamp2(cmd, stage, pool_, index);
  // A full barrier right after the timestamp: lavapipe bins timestamps with its deferred draw work while it
  // runs compute dispatches at once, so without it a timestamp taken before a dispatch is resolved after it.
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

std::optional<std::uint64_t> TimestampQueries::ticks(std::uint32_t index) const {
  if (!supported_) return std::nullopt;
  std::uint64_t value = 0;
  S3D_VK_CHECK(vkGetQueryPoolResults(context_->device(), pool_, index, 1, sizeof(std::uint64_t), &value,
                                     sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return value;
}

std::optional<double> TimestampQueries::elapsedMs(std::uint32_t begin, std::uint32_t end) const {
  if (!supported_) return std::nullopt;
  // Two queries read separately: they need not be adjacent.
  return double(*ticks(end) - *ticks(begin)) * context_->timestampPeriodNs() * 1e-6;
}

}  // namespace s3d::vk
