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
  // `allocator`: the callbacks the handle was created with (a host's, when s3d runs on its device).
  Unique(VkDevice device, Handle handle, Destroy destroy, const VkAllocationCallbacks* allocator = nullptr)
      : device_(device), handle_(handle), destroy_(destroy), allocator_(allocator) {}
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
    if (handle_ != VK_NULL_HANDLE) destroy_(device_, handle_, allocator_);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  void swap(Unique& other) noexcept {
    std::swap(device_, other.device_);
    std::swap(handle_, other.handle_);
    std::swap(destroy_, other.destroy_);
    std::swap(allocator_, other.allocator_);
  }

  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
  Destroy destroy_ = nullptr;
  const VkAllocationCallbacks* allocator_ = nullptr;
};

}  // namespace s3d::vk
