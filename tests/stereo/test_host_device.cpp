// A host's own device adopted by s3d: what s3d asks of the device, the patch that enables it in the host's
// VkDeviceCreateInfo, the error that names what is missing, and s3d's passes running on the adopted device.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>

#include "s3d/stereo/stereo.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "test_host.h"

namespace s3d::test {
namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string adoptionError(const vk::HostDevice& host) {
  try {
    vk::Context context(host);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

class HostDeviceTest : public HostTest {};

TEST(DeviceRequirements, NameVulkan13PushDescriptorsAndTheFeaturesS3dUses) {
  const vk::DeviceRequirements requirements = vk::deviceRequirements();
  EXPECT_EQ(requirements.apiVersion, VK_API_VERSION_1_3);
  EXPECT_TRUE(contains(requirements.extensions, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME));
  for (const char* feature : {"synchronization2", "dynamicRendering", "maintenance4"})
    EXPECT_TRUE(contains(requirements.features, feature)) << feature;
}

TEST_F(HostDeviceTest, AnAdoptedDeviceRunsTheStereoPassLikeTheReference) {
  vk::Context context(host().hostDevice());
  EXPECT_FALSE(context.ownsDevice());
  EXPECT_EQ(context.device(), host().device);
  const SyntheticView view = makeBlockView(64, 40, 7, 0.3f, 7, 5, false);
  stereo::StereoParameters parameters;
  parameters.maxSeparation = 0.05f;
  const gpu::StereoConstants constants = stereo::makeStereoConstants(parameters, 64, 40);
  const stereo::StereoPair gpu = stereo::synthesizeStereoOnGpu(context, view.color, view.depth, constants);
  const stereo::StereoPair cpu = stereo::synthesizeStereoReference(view.color, view.depth, constants);
  EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1);  // the reference's rounding (test_stereo_pass)
  EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1);
}

TEST_F(HostDeviceTest, ContextDestructionLeavesTheHostsDeviceAlive) {
  { vk::Context context(host().hostDevice()); }
  EXPECT_EQ(vkDeviceWaitIdle(host().device), VK_SUCCESS);
}

TEST_F(HostDeviceTest, ADeviceWithoutSynchronization2IsRefusedNamingIt) {
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  features13.dynamicRendering = VK_TRUE;
  features13.maintenance4 = VK_TRUE;
  const char* extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  VkDeviceCreateInfo info = host().baseDeviceInfo();
  info.pNext = &features13;
  info.enabledExtensionCount = 1;
  info.ppEnabledExtensionNames = extensions;
  VkDevice device = host().createDevice(info);
  vk::HostDevice adopted = host().hostDevice();
  adopted.device = device;
  vkGetDeviceQueue(device, host().queueFamily, 0, &adopted.queue);
  adopted.createInfo = &info;
  const std::string error = adoptionError(adopted);
  vkDestroyDevice(device, nullptr);
  EXPECT_NE(error.find("synchronization2"), std::string::npos) << error;
  EXPECT_EQ(error.find("maintenance4"), std::string::npos) << error;
  EXPECT_EQ(error.find("push_descriptor"), std::string::npos) << error;
}

TEST_F(HostDeviceTest, ADeviceWithoutPushDescriptorsIsRefusedNamingTheExtension) {
  VkDeviceCreateInfo info = host().baseDeviceInfo();
  VkDevice device = host().createDevice(info);
  vk::HostDevice adopted = host().hostDevice();
  adopted.device = device;
  vkGetDeviceQueue(device, host().queueFamily, 0, &adopted.queue);
  adopted.createInfo = &info;
  const std::string error = adoptionError(adopted);
  vkDestroyDevice(device, nullptr);
  EXPECT_NE(error.find(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME), std::string::npos) << error;
  EXPECT_NE(error.find("dynamicRendering"), std::string::npos) << error;
}

TEST_F(HostDeviceTest, ThePatchKeepsTheHostsOwnExtensionsAndFeatureStructs) {
  // The host already chains the per-feature struct for synchronization2 (Vulkan forbids mixing it with
  // VkPhysicalDeviceVulkan13Features) and enables an extension of its own.
  VkPhysicalDeviceSynchronization2Features synchronization2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
  const char* hostExtensions[] = {VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME};
  VkDeviceCreateInfo info = host().baseDeviceInfo();
  info.pNext = &synchronization2;
  info.enabledExtensionCount = 1;
  info.ppEnabledExtensionNames = hostExtensions;
  vk::DeviceRequirementsPatch patch(host().physicalDevice, info);
  EXPECT_EQ(synchronization2.synchronization2, VK_TRUE);
  EXPECT_TRUE(vk::missingEnabledRequirements(info).empty());
  ASSERT_EQ(info.enabledExtensionCount, 2u);
  EXPECT_STREQ(info.ppEnabledExtensionNames[0], VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME);
  VkDevice device = host().createDevice(info);  // validation fails the test if the chain mixed struct kinds
  vkDestroyDevice(device, nullptr);
}

// Counts live blocks; a 64-byte header keeps each block's size for reallocation.
struct CountingAllocator {
  static constexpr std::size_t kHeader = 64;
  static inline std::atomic<int> live{0}, calls{0};
  static void* allocate(void*, std::size_t size, std::size_t alignment, VkSystemAllocationScope) {
    if (alignment > kHeader) return nullptr;
    ++calls;
    ++live;
    auto* block = static_cast<std::byte*>(std::aligned_alloc(kHeader, (kHeader + size + kHeader - 1) / kHeader * kHeader));
    *reinterpret_cast<std::size_t*>(block) = size;
    return block + kHeader;
  }
  static void release(void*, void* memory) {
    if (!memory) return;
    --live;
    std::free(static_cast<std::byte*>(memory) - kHeader);
  }
  static void* reallocate(void* user, void* original, std::size_t size, std::size_t alignment, VkSystemAllocationScope scope) {
    void* moved = size ? allocate(user, size, alignment, scope) : nullptr;
    if (original && moved)
      std::memcpy(moved, original, std::min(size, *reinterpret_cast<std::size_t*>(static_cast<std::byte*>(original) - kHeader)));
    release(user, original);
    return moved;
  }
};

TEST_F(HostDeviceTest, ObjectsAreMadeWithTheHostsAllocationCallbacks) {
  VkAllocationCallbacks callbacks{};
  callbacks.pfnAllocation = &CountingAllocator::allocate;
  callbacks.pfnReallocation = &CountingAllocator::reallocate;
  callbacks.pfnFree = &CountingAllocator::release;
  vk::HostDevice adopted = host().hostDevice();
  adopted.allocator = &callbacks;
  {
    vk::Context context(adopted);
    const SyntheticView view = makeBlockView(16, 8, 3, 0.3f, 7, 5, false);
    stereo::synthesizeStereoOnGpu(context, view.color, view.depth,
                                  stereo::makeStereoConstants(stereo::StereoParameters{}, 16, 8));
  }
  EXPECT_GT(CountingAllocator::calls.load(), 0);
  EXPECT_EQ(CountingAllocator::live.load(), 0);  // everything s3d made with them went back through them
}

}  // namespace
}  // namespace s3d::test
