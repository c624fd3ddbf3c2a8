#include "host_vulkan.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include <s3d/vk/context.h>  // s3d's device requirements: the one thing the host asks s3d while making its device

namespace host {

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw std::runtime_error(std::string(call) + " failed: VkResult " + std::to_string(int(result)));
}

namespace {

bool layerAvailable(const char* name) {
  std::uint32_t count = 0;
  HOST_VK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  HOST_VK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  for (const VkLayerProperties& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

VkBool32 onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  ++static_cast<Device*>(user)->validationMessages;
  std::fprintf(stderr, "s3d_host: validation: %s\n", data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
}

}  // namespace

Device::Device(bool withValidation) {
  const char* layerName = "VK_LAYER_KHRONOS_validation";
  validation = withValidation && layerAvailable(layerName);
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "s3d host example";
  app.apiVersion = VK_API_VERSION_1_3;
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  messengerInfo.pfnUserCallback = onValidationMessage;
  messengerInfo.pUserData = this;
  features.pNext = &messengerInfo;
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, validation ? &features : nullptr};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = validation ? 1 : 0;
  info.ppEnabledLayerNames = &layerName;
  info.enabledExtensionCount = validation ? 1 : 0;
  info.ppEnabledExtensionNames = &extension;
  HOST_VK(vkCreateInstance(&info, nullptr, &instance));
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    HOST_VK(create(instance, &messengerInfo, nullptr, &messenger_));
  }

  std::uint32_t count = 0;
  HOST_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  HOST_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  for (VkPhysicalDevice candidate : devices) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(candidate, &properties);
    if (s3d::vk::missingDeviceSupport(candidate).empty() &&
        (!physicalDevice || properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)) {
      physicalDevice = candidate;
      name = properties.deviceName;
    }
  }
  if (!physicalDevice) throw std::runtime_error("no Vulkan 1.3 device with what s3d needs");
  std::uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
  const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;  // the scene and s3d on one queue
  while (queueFamily < familyCount && (families[queueFamily].queueFlags & needed) != needed) ++queueFamily;
  if (queueFamily == familyCount) throw std::runtime_error("no queue family does graphics and compute");

  // The engine's own device: its queue and the features its renderer uses, then s3d's requirements added.
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features vulkan13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  vulkan13.dynamicRendering = VK_TRUE;  // the host renders without render pass objects
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &vulkan13};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  s3d::vk::DeviceRequirementsPatch patch(physicalDevice, deviceInfo);  // synchronization2, push descriptors, ...
  HOST_VK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
  vkGetDeviceQueue(device, queueFamily, 0, &queue);
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = queueFamily;
  HOST_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
}

Device::~Device() {
  vkDestroyCommandPool(device, pool, nullptr);
  vkDestroyDevice(device, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance, messenger_, nullptr);
  }
  vkDestroyInstance(instance, nullptr);
}

std::uint32_t Device::memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties properties{};
  vkGetPhysicalDeviceMemoryProperties(physicalDevice, &properties);
  for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw std::runtime_error("no Vulkan memory type with the properties the host needs");
}

void Device::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  HOST_VK(vkAllocateCommandBuffers(device, &allocInfo, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  HOST_VK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  HOST_VK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  HOST_VK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  HOST_VK(vkQueueSubmit(queue, 1, &submit, fence));
  HOST_VK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
  vkDestroyFence(device, fence, nullptr);
  vkFreeCommandBuffers(device, pool, 1, &cmd);
}

Image::Image(const Device& device, VkFormat format_, std::uint32_t width_, std::uint32_t height_, VkImageUsageFlags usage)
    : owner(&device), format(format_), width(width_), height(height_) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  HOST_VK(vkCreateImage(device.device, &info, nullptr, &image));
  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device.device, image, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = device.memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  HOST_VK(vkAllocateMemory(device.device, &alloc, nullptr, &memory));
  HOST_VK(vkBindImageMemory(device.device, image, memory, 0));
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = format;
  viewInfo.subresourceRange = {aspect(), 0, 1, 0, 1};
  HOST_VK(vkCreateImageView(device.device, &viewInfo, nullptr, &view));
}

Image::~Image() {
  vkDestroyImageView(owner->device, view, nullptr);
  vkDestroyImage(owner->device, image, nullptr);
  vkFreeMemory(owner->device, memory, nullptr);
}

VkImageAspectFlags Image::aspect() const {
  return format == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

Buffer::Buffer(const Device& device, VkDeviceSize size_, VkBufferUsageFlags usage) : owner(&device), size(size_) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  HOST_VK(vkCreateBuffer(device.device, &info, nullptr, &buffer));
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device.device, buffer, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = device.memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                            VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  HOST_VK(vkAllocateMemory(device.device, &alloc, nullptr, &memory));
  HOST_VK(vkBindBufferMemory(device.device, buffer, memory, 0));
  HOST_VK(vkMapMemory(device.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped));
}

Buffer::~Buffer() {
  vkDestroyBuffer(owner->device, buffer, nullptr);
  vkFreeMemory(owner->device, memory, nullptr);  // unmaps
}

void imageBarrier(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image.image;
  barrier.subresourceRange = {image.aspect(), 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void copyImageToBuffer(VkCommandBuffer cmd, const Image& image, const Buffer& buffer) {
  VkBufferImageCopy region{};
  region.imageSubresource = {image.aspect(), 0, 0, 1};
  region.imageExtent = {image.width, image.height, 1};
  vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &region);
}

}  // namespace host
