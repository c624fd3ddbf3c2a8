#pragma once
// Vulkan instance, device and queue: the one place that creates and destroys them.
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace s3d::vk {

struct ContextOptions {
  // "auto" (a GPU when present, else Mesa lavapipe), "cpu", "gpu", or a physical-device index.
  std::string device = "auto";
  // Turn on VK_LAYER_KHRONOS_validation; every message it reports is recorded (see validationMessages()).
  bool validation = false;
  // Presentation, for windowed tools (s3d tune); offscreen users leave both empty and get no surface, no
  // VK_KHR_swapchain and the same device choice as before. instanceExtensions are enabled on the instance (for
  // a window: glfwGetRequiredInstanceExtensions); createSurface is called once with the new instance, the
  // context owns the surface it returns, and only a device that can present to it from its queue is chosen.
  std::vector<std::string> instanceExtensions;
  std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

struct PhysicalDeviceInfo {
  std::uint32_t index = 0;
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::uint32_t apiVersion = 0;
  bool usable = false;          // Vulkan 1.3 + the extensions and features s3d needs
  std::string unusableReason;   // why not, when !usable
};

// Lists every physical device the loader reports, with whether s3d can use it.
std::vector<PhysicalDeviceInfo> listPhysicalDevices();

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  VkSurfaceKHR surface() const { return surface_; }  // VK_NULL_HANDLE without ContextOptions::createSurface
  std::uint32_t queueFamily() const { return queueFamily_; }
  const std::string& deviceName() const { return deviceName_; }
  bool isCpuDevice() const { return deviceType_ == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  // Nanoseconds per timestamp tick; 0 when the queue has no timestamp support.
  double timestampPeriodNs() const { return timestampPeriodNs_; }

  std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                               VkMemoryPropertyFlags preferred = 0) const;

  // Records commands into a fresh command buffer, submits them and waits for the queue to finish.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

  // Messages reported by the validation layer since creation (empty when validation is off).
  std::vector<std::string> validationMessages() const;
  void clearValidationMessages();

  // VK_KHR_push_descriptor entry point: passes bind their resources without descriptor pools.
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

 private:
  void release();
  static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT types,
                                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                            void* user);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  std::string deviceName_;
  VkPhysicalDeviceType deviceType_ = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  double timestampPeriodNs_ = 0.0;
  VkPhysicalDeviceMemoryProperties memoryProperties_{};

  mutable std::mutex messagesMutex_;
  std::vector<std::string> validationMessages_;
};

}  // namespace s3d::vk
