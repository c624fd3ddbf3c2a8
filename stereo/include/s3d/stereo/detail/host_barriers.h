#pragma once
// The barriers a pass on a host's images records (synchronization2): up to Capacity image barriers plus an optional
// compute -> compute memory barrier for the pass's own images, in one vkCmdPipelineBarrier2, without allocating.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace s3d::stereo::detail {

inline bool isHostDepthFormat(VkFormat f) {
  return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D16_UNORM;
}
// A combined depth/stencil image changes layout in both aspects.
inline VkImageAspectFlags hostBarrierAspect(VkFormat f) {
  if (f == VK_FORMAT_D24_UNORM_S8_UINT) return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
  return isHostDepthFormat(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}
// Layouts a compute shader can sample as they are.
inline bool sampledReadable(VkImageLayout l) {
  return l == VK_IMAGE_LAYOUT_GENERAL || l == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL ||
         l == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL ||
         l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
}
// The layout a pass samples a host's image in: its own where a compute shader can sample it, else
// SHADER_READ_ONLY_OPTIMAL after a barrier from the host's stage. Throws std::invalid_argument naming `image` (e.g.
// "HostStereoPass: the depth image") when neither is possible.
inline VkImageLayout sampledReadLayout(VkImageLayout layout, VkPipelineStageFlags2 stage, const std::string& image) {
  if (sampledReadable(layout)) return layout;
  if (stage == VK_PIPELINE_STAGE_2_NONE)
    throw std::invalid_argument(image + " is in a layout s3d cannot read and the host gave no access for a barrier");
  return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

template <std::size_t Capacity>
struct HostBarriers {
  std::array<VkImageMemoryBarrier2, Capacity> images{};
  std::uint32_t count = 0;
  bool memory = false;  // a compute -> compute dependency for the pass's own images (this and earlier frames)

  void image(VkImage image, VkFormat format, VkImageLayout fromLayout, VkPipelineStageFlags2 fromStage,
             VkAccessFlags2 fromAccess, VkImageLayout toLayout, VkPipelineStageFlags2 toStage, VkAccessFlags2 toAccess,
             std::uint32_t layer = 0) {
    if (count == Capacity) throw std::logic_error("HostBarriers: capacity exceeded");
    VkImageMemoryBarrier2& b = images[count++];
    b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = fromStage;
    b.srcAccessMask = fromAccess;
    b.dstStageMask = toStage;
    b.dstAccessMask = toAccess;
    b.oldLayout = fromLayout;
    b.newLayout = toLayout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {hostBarrierAspect(format), 0, 1, layer, 1};
  }
  void record(VkCommandBuffer cmd) const {
    VkMemoryBarrier2 global{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    global.srcStageMask = global.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    global.srcAccessMask = global.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = memory ? 1 : 0;
    dependency.pMemoryBarriers = &global;
    dependency.imageMemoryBarrierCount = count;
    dependency.pImageMemoryBarriers = images.data();
    if (memory || count > 0) vkCmdPipelineBarrier2(cmd, &dependency);
  }
};

}  // namespace s3d::stereo::detail
