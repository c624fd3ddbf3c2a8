#pragma once
// A stand-in for an engine that owns its Vulkan objects: its own instance (Khronos validation with
// synchronization validation on), its own device made with s3d's requirements patched in, its own
// command pool; s3d adopts the device through vk::HostDevice.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "s3d/vk/check.h"
#include "s3d/vk/context.h"

namespace s3d::test {

class TestHost {
 public:
  TestHost() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "s3d test host";
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkDebugUtilsMessengerCreateInfoEXT messenger = messengerInfo();
    features.pNext = &messenger;  // also reports what instance creation itself finds
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, &features};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
    S3D_VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    S3D_VK_CHECK(create(instance, &messenger, nullptr, &messenger_));
    std::uint32_t count = 0;
    S3D_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    S3D_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    for (VkPhysicalDevice candidate : devices)  // the CPU device, as in CI; any usable one otherwise
      if (vk::missingDeviceSupport(candidate).empty() && (!physicalDevice || isCpu(candidate))) physicalDevice = candidate;
    if (!physicalDevice) throw std::runtime_error("test host: no device s3d can use");
    std::uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
    while (!(families[queueFamily].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++queueFamily;

    VkDeviceCreateInfo deviceInfo = baseDeviceInfo();
    vk::DeviceRequirementsPatch patch(physicalDevice, deviceInfo);
    device = createDevice(deviceInfo);
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queueFamily;
    S3D_VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &commandPool));
  }
  ~TestHost() {
    vkDestroyCommandPool(device, commandPool, nullptr);
    vkDestroyDevice(device, nullptr);
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance, messenger_, nullptr);
    vkDestroyInstance(instance, nullptr);
  }

  // One graphics+compute queue and nothing else: what a device gets before s3d's requirements are added.
  VkDeviceCreateInfo baseDeviceInfo() {
    queueInfo_.queueFamilyIndex = queueFamily;
    queueInfo_.queueCount = 1;
    queueInfo_.pQueuePriorities = &priority_;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo_;
    return info;
  }
  VkDevice createDevice(const VkDeviceCreateInfo& info) {
    VkDevice created = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateDevice(physicalDevice, &info, nullptr, &created));
    return created;
  }
  vk::HostDevice hostDevice() const {
    vk::HostDevice host;
    host.instance = instance;
    host.physicalDevice = physicalDevice;
    host.device = device;
    host.queueFamily = queueFamily;
    host.queue = queue;
    return host;
  }

  std::vector<std::string> messages() {
    std::lock_guard lock(mutex_);
    return messages_;
  }
  void clearMessages() {
    std::lock_guard lock(mutex_);
    messages_.clear();
  }

  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool commandPool = VK_NULL_HANDLE;

 private:
  static bool isCpu(VkPhysicalDevice device) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(device, &properties);
    return properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  }
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo() {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    info.pfnUserCallback = [](VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) -> VkBool32 {
      auto* host = static_cast<TestHost*>(user);
      std::lock_guard lock(host->mutex_);
      host->messages_.emplace_back(data && data->pMessage ? data->pMessage : "(no message)");
      return VK_FALSE;
    };
    info.pUserData = this;
    return info;
  }

  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  float priority_ = 1.0f;
  VkDeviceQueueCreateInfo queueInfo_{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  std::mutex mutex_;
  std::vector<std::string> messages_;
};

inline TestHost& sharedTestHost() {
  static std::unique_ptr<TestHost> host = std::make_unique<TestHost>();
  return *host;
}

// Records into a command buffer of the host's pool, submits it on the host's queue and waits (what an engine's
// frame does, minus the swapchain).
inline void runOnHostQueue(TestHost& host, const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = host.commandPool;
  info.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkAllocateCommandBuffers(host.device, &info, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  S3D_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  S3D_VK_CHECK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  S3D_VK_CHECK(vkQueueSubmit(host.queue, 1, &submit, VK_NULL_HANDLE));
  S3D_VK_CHECK(vkQueueWaitIdle(host.queue));
  vkFreeCommandBuffers(host.device, host.commandPool, 1, &cmd);
}

// Frames in flight: `frames` recordings (record(cmd, frame)), each in a command buffer of its own or all in one,
// every buffer submitted before any is waited for, then the queue waited for.
inline void runFramesInFlight(TestHost& host, int frames, bool oneCommandBuffer,
                              const std::function<void(VkCommandBuffer, int)>& record) {
  const int buffers = oneCommandBuffer ? 1 : frames;
  std::vector<VkCommandBuffer> cmds(std::size_t(buffers), VK_NULL_HANDLE);
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = host.commandPool;
  info.commandBufferCount = std::uint32_t(buffers);
  S3D_VK_CHECK(vkAllocateCommandBuffers(host.device, &info, cmds.data()));
  for (int f = 0; f < frames; ++f) {
    VkCommandBuffer cmd = cmds[oneCommandBuffer ? 0 : std::size_t(f)];
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    if (f == 0 || !oneCommandBuffer) S3D_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd, f);
    if (f == frames - 1 || !oneCommandBuffer) S3D_VK_CHECK(vkEndCommandBuffer(cmd));
  }
  for (VkCommandBuffer cmd : cmds) {
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    S3D_VK_CHECK(vkQueueSubmit(host.queue, 1, &submit, VK_NULL_HANDLE));
  }
  S3D_VK_CHECK(vkQueueWaitIdle(host.queue));
  vkFreeCommandBuffers(host.device, host.commandPool, std::uint32_t(buffers), cmds.data());
}

// Any validation message (synchronization validation included) recorded on the host fails the test.
class HostTest : public ::testing::Test {
 protected:
  TestHost& host() { return sharedTestHost(); }
  void SetUp() override { host().clearMessages(); }
  void TearDown() override {
    for (const std::string& message : host().messages()) ADD_FAILURE() << "validation: " << message;
    host().clearMessages();
  }
};

// A HostTest with an s3d context adopted on the shared host's device: made per test, destroyed before the
// validation messages are checked (its objects' destruction is checked too).
class HostContextTest : public HostTest {
 protected:
  void SetUp() override {
    HostTest::SetUp();
    context_ = std::make_unique<vk::Context>(host().hostDevice());
  }
  void TearDown() override {
    context_.reset();
    HostTest::TearDown();
  }
  std::unique_ptr<vk::Context> context_;
};

}  // namespace s3d::test
