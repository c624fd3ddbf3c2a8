#pragma once
// One descriptor of a compute pass's push-descriptor layout (occlusion, tile lists, lighting, G-buffer resolve).
#include <cstdint>

#include <vulkan/vulkan.h>

namespace s3d::renderer::detail {

inline VkDescriptorSetLayoutBinding computeBinding(std::uint32_t index, VkDescriptorType type) {
  return {index, type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
}

}  // namespace s3d::renderer::detail
