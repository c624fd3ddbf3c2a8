#pragma once
// RAII ownership of device-level Vulkan handles: the destroy function is bound at creation, so an object
// is destroyed in exactly one place.
#include <utility>

#include <vulkan/vulkan.h>

namespace s3d::vk {

template <typename Handle>
class Unique {
 public:
  using Destroy = void (*)(VkDevice, Handle, const VkAllocationCallbacks*);

  Unique() = default;
  Unique(VkDevice device, Handle handle, Destroy destroy) : device_(device), handle_(handle), destroy_(destroy) {}
  Unique(const Unique&) = delete;
  Unique& operator=(const Unique&) = delete;
  Unique(Unique&& other) noexcept { swap(other); }
  Unique& operator=(Unique&& other) noexcept {
    if (this != &other) {
      reset();
      swap(other);
    }
    return *this;
  }
  ~Unique() { reset(); }

  Handle get() const { return handle_; }
  operator Handle() const { return handle_; }  // NOLINT: handles pass straight into Vulkan calls
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

  void reset() {
    if (handle_ != VK_NULL_HANDLE) destroy_(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  void swap(Unique& other) noexcept {
    std::swap(device_, other.device_);
    std::swap(handle_, other.handle_);
    std::swap(destroy_, other.destroy_);
  }

  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
  Destroy destroy_ = nullptr;
};

}  // namespace s3d::vk
