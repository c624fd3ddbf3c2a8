#pragma once
// The host engine's own Vulkan objects (nothing here comes from s3d): instance, device with s3d's requirements
// patched in, queue, command pool, images and buffers with their memory, one-shot submissions.
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace host {

// Every Vulkan call of the host is checked; the error names the call and its VkResult.
void check(VkResult result, const char* call);
#define HOST_VK(call) ::host::check((call), #call)

struct Device {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  std::string name;

  // Lavapipe (the CPU device) when present, else the first device s3d can use; `validation` turns on the Khronos
  // layer with synchronization validation, its messages counted in validationMessages.
  explicit Device(bool validation);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  std::uint32_t memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags flags) const;
  // Records with `record`, submits on the queue and waits (uploads at start-up, the host's frames here).
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

  bool validation = false;  // the layer was found and is on
  int validationMessages = 0;

 private:
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

struct Image {
  const Device* owner = nullptr;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t width = 0, height = 0;

  Image(const Device& device, VkFormat format, std::uint32_t width, std::uint32_t height, VkImageUsageFlags usage);
  ~Image();
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  VkImageAspectFlags aspect() const;
};

struct Buffer {
  const Device* owner = nullptr;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // host-visible, coherent, mapped for its lifetime
  VkDeviceSize size = 0;

  Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage);
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
};

// One image layout transition (synchronization2), whole image.
void imageBarrier(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess);
// Copies the whole image (in TRANSFER_SRC_OPTIMAL) into `buffer` at offset 0, tightly packed.
void copyImageToBuffer(VkCommandBuffer cmd, const Image& image, const Buffer& buffer);

}  // namespace host
