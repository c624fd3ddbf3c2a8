#pragma once
// Every Vulkan call is checked: a failure becomes an exception that names the VkResult and the call.
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace s3d::vk {

const char* resultName(VkResult result);

class VulkanError : public std::runtime_error {
 public:
  VulkanError(VkResult result, const std::string& call)
      : std::runtime_error(call + " failed: " + resultName(result)), result_(result) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

inline void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw VulkanError(result, call);
}

}  // namespace s3d::vk

// S3D_VK_CHECK(vkCreateBuffer(...)) throws VulkanError("vkCreateBuffer(...) failed: VK_ERROR_...").
#define S3D_VK_CHECK(call) ::s3d::vk::check((call), #call)
