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

// What s3d needs of a device; a host that creates its own device enables these (DeviceRequirementsPatch).
struct DeviceRequirements {
  std::uint32_t apiVersion = VK_API_VERSION_1_3;
  std::vector<std::string> extensions;  // device extensions
  std::vector<std::string> features;    // Vulkan 1.3 feature names (VkPhysicalDeviceVulkan13Features members)
};
DeviceRequirements deviceRequirements();

// Each requirement `physicalDevice` does not support, named ("Vulkan 1.3", "synchronization2",
// "VK_KHR_push_descriptor"); empty when s3d can run on it.
std::vector<std::string> missingDeviceSupport(VkPhysicalDevice physicalDevice);

// Each requirement a device made from `info` would not have enabled (extensions, and features found in its
// pNext chain as VkPhysicalDeviceVulkan13Features or the per-feature structs).
std::vector<std::string> missingEnabledRequirements(const VkDeviceCreateInfo& info);

// Adds s3d's extensions and features to a host's VkDeviceCreateInfo before vkCreateDevice: sets the features
// in the feature structs the chain already has, links its own structs otherwise, and points the extension list
// at a copy with s3d's added. Keep the patch alive until vkCreateDevice returns. Throws std::runtime_error
// naming every requirement the physical device does not support.
class DeviceRequirementsPatch {
 public:
  DeviceRequirementsPatch(VkPhysicalDevice physicalDevice, VkDeviceCreateInfo& info);
  DeviceRequirementsPatch(const DeviceRequirementsPatch&) = delete;
  DeviceRequirementsPatch& operator=(const DeviceRequirementsPatch&) = delete;

 private:
  std::vector<const char*> extensions_;
  // sTypes set by the constructor: the headers stay clean under a consumer's -Wextra.
  VkPhysicalDeviceVulkan13Features vulkan13_{};
  VkPhysicalDeviceSynchronization2Features synchronization2_{};
  VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering_{};
  VkPhysicalDeviceMaintenance4Features maintenance4_{};
};

// A host's device for s3d to run on. s3d destroys none of these handles; the host keeps them alive (and the
// device idle of s3d's work) until every s3d object made from the context is gone.
struct HostDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;  // must support compute; s3d records only into the host's command buffers
  VkQueue queue = VK_NULL_HANDLE;  // used only by the context's uploads (submitAndWait), never per frame
  const VkAllocationCallbacks* allocator = nullptr;  // passed to every s3d create/destroy
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;   // used for every s3d pipeline
  // The create info the device was made with (read only during construction): when given, s3d checks that
  // its features and extensions were enabled, not only supported.
  const VkDeviceCreateInfo* createInfo = nullptr;
};

class Context {
 public:
  // s3d's own instance and device (the tools, the tests).
  explicit Context(const ContextOptions& options = {});
  // Adopts a host's device without owning it. Throws std::runtime_error naming each missing requirement.
  explicit Context(const HostDevice& host);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  // Whether s3d's own device has an asynchronous compute queue (a family with compute and no graphics: GPUs; not
  // lavapipe, not a host's device): work submitted there runs beside queue()'s (submitConcurrentlyAndWait).
  bool hasConcurrentQueue() const { return concurrentQueue_ != VK_NULL_HANDLE; }
  // The queue families every buffer and image is shared between (VK_SHARING_MODE_CONCURRENT where two): queue()'s,
  // and the compute queue's where there is one, so either queue may use any resource without ownership transfers.
  const std::vector<std::uint32_t>& sharingFamilies() const { return sharingFamilies_; }
  VkSurfaceKHR surface() const { return surface_; }  // VK_NULL_HANDLE without ContextOptions::createSurface
  std::uint32_t queueFamily() const { return queueFamily_; }
  const std::string& deviceName() const { return deviceName_; }
  bool isCpuDevice() const { return deviceType_ == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  bool ownsDevice() const { return ownsDevice_; }
  const VkAllocationCallbacks* allocator() const { return allocator_; }
  VkPipelineCache pipelineCache() const { return pipelineCache_; }
  // Nanoseconds per timestamp tick; 0 when the queue has no timestamp support.
  double timestampPeriodNs() const { return timestampPeriodNs_; }
  // Whether pipelines capture the driver's statistics (pipeline_statistics.h): asked for, and s3d's own device.
  bool capturesPipelineStatistics() const { return capturesPipelineStatistics_; }

  std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                               VkMemoryPropertyFlags preferred = 0) const;

  // Records commands into a fresh command buffer, submits them to queue() and waits for them (the one-recording
  // submitConcurrentlyAndWait).
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);
  // Records each function into a command buffer of its own and waits for all of them: the first on queue(), the
  // others on the compute queue where there is one (so they may record only compute and transfer work: no
  // graphics stages, not even in barriers), so that one's passes run while another's wait on their barriers;
  // without it, all on queue() in order. The recordings must not touch each other's resources.
  void submitConcurrentlyAndWait(const std::vector<std::function<void(VkCommandBuffer)>>& records);

  // Messages reported by the validation layer since creation (empty when validation is off).
  std::vector<std::string> validationMessages() const;
  void clearValidationMessages();

  // VK_KHR_push_descriptor entry point: passes bind their resources without descriptor pools.
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

 private:
  void release();
  void initDeviceState();  // properties, memory types, entry points, command pool of the chosen device
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
  VkQueue concurrentQueue_ = VK_NULL_HANDLE;
  VkCommandPool concurrentPool_ = VK_NULL_HANDLE;
  std::vector<std::uint32_t> sharingFamilies_;  // set in the constructors
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  bool ownsDevice_ = true;
  const VkAllocationCallbacks* allocator_ = nullptr;
  VkPipelineCache pipelineCache_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  std::string deviceName_;
  VkPhysicalDeviceType deviceType_ = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  double timestampPeriodNs_ = 0.0;
  bool capturesPipelineStatistics_ = false;
  VkPhysicalDeviceMemoryProperties memoryProperties_{};

  mutable std::mutex messagesMutex_;
  std::vector<std::string> validationMessages_;
};

}  // namespace s3d::vk
