#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "s3d/vk/check.h"
#include "s3d/vk/context.h"

namespace s3d::vk {
namespace {

// The Vulkan 1.3 features s3d uses: dynamic rendering (renderer, HUD), synchronization2 (every barrier),
// maintenance4 (glslang emits LocalSizeId for SPIR-V 1.6 compute shaders).
constexpr const char* kFeatures[] = {"dynamicRendering", "synchronization2", "maintenance4"};
constexpr const char* kExtensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};

VkBool32* featureIn(VkPhysicalDeviceVulkan13Features& f, std::string_view name) {
  if (name == "dynamicRendering") return &f.dynamicRendering;
  if (name == "synchronization2") return &f.synchronization2;
  return &f.maintenance4;
}

// The chain's flag for `name`, from VkPhysicalDeviceVulkan13Features or the feature's own struct; null if absent.
VkBool32* findFeature(const void* chain, std::string_view name) {
  for (auto* s = static_cast<VkBaseOutStructure*>(const_cast<void*>(chain)); s; s = s->pNext) {
    switch (s->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
        return featureIn(*reinterpret_cast<VkPhysicalDeviceVulkan13Features*>(s), name);
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
        if (name == "synchronization2") return &reinterpret_cast<VkPhysicalDeviceSynchronization2Features*>(s)->synchronization2;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
        if (name == "dynamicRendering") return &reinterpret_cast<VkPhysicalDeviceDynamicRenderingFeatures*>(s)->dynamicRendering;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
        if (name == "maintenance4") return &reinterpret_cast<VkPhysicalDeviceMaintenance4Features*>(s)->maintenance4;
        break;
      default:
        break;
    }
  }
  return nullptr;
}

bool chainHas(const void* chain, VkStructureType type) {
  for (auto* s = static_cast<const VkBaseInStructure*>(chain); s; s = s->pNext)
    if (s->sType == type) return true;
  return false;
}

bool listHas(const char* const* names, std::uint32_t count, const char* name) {
  return std::any_of(names, names + count, [&](const char* n) { return std::strcmp(n, name) == 0; });
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

}  // namespace

DeviceRequirements deviceRequirements() {
  DeviceRequirements requirements;
  requirements.extensions.assign(std::begin(kExtensions), std::end(kExtensions));
  requirements.features.assign(std::begin(kFeatures), std::end(kFeatures));
  return requirements;
}

std::vector<std::string> missingDeviceSupport(VkPhysicalDevice physicalDevice) {
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(physicalDevice, &properties);
  if (properties.apiVersion < VK_API_VERSION_1_3) return {"Vulkan 1.3"};
  std::vector<std::string> missing;
  std::uint32_t count = 0;
  S3D_VK_CHECK(vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  S3D_VK_CHECK(vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, extensions.data()));
  for (const char* name : kExtensions)
    if (std::none_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; }))
      missing.emplace_back(name);
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
  vkGetPhysicalDeviceFeatures2(physicalDevice, &features);
  for (const char* name : kFeatures)
    if (!*featureIn(features13, name)) missing.emplace_back(name);
  return missing;
}

std::vector<std::string> missingEnabledRequirements(const VkDeviceCreateInfo& info) {
  std::vector<std::string> missing;
  for (const char* name : kExtensions)
    if (!listHas(info.ppEnabledExtensionNames, info.enabledExtensionCount, name)) missing.emplace_back(name);
  for (const char* name : kFeatures) {
    const VkBool32* flag = findFeature(info.pNext, name);
    if (!flag || !*flag) missing.emplace_back(name);
  }
  return missing;
}

DeviceRequirementsPatch::DeviceRequirementsPatch(VkPhysicalDevice physicalDevice, VkDeviceCreateInfo& info) {
  vulkan13_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  synchronization2_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES;
  dynamicRendering_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES;
  maintenance4_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES;
  if (std::vector<std::string> missing = missingDeviceSupport(physicalDevice); !missing.empty()) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(physicalDevice, &properties);
    throw std::runtime_error(std::string("s3d cannot run on ") + properties.deviceName + ": it does not support " +
                             joined(missing));
  }
  extensions_.assign(info.ppEnabledExtensionNames, info.ppEnabledExtensionNames + info.enabledExtensionCount);
  for (const char* name : kExtensions)
    if (!listHas(extensions_.data(), std::uint32_t(extensions_.size()), name)) extensions_.push_back(name);
  info.enabledExtensionCount = std::uint32_t(extensions_.size());
  info.ppEnabledExtensionNames = extensions_.data();

  // Vulkan forbids VkPhysicalDeviceVulkan13Features next to the per-feature structs, so add whichever kind is there.
  const bool perFeatureStructs = chainHas(info.pNext, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES) ||
                                 chainHas(info.pNext, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES) ||
                                 chainHas(info.pNext, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES);
  auto link = [&](auto& structure) {
    structure.pNext = const_cast<void*>(info.pNext);
    info.pNext = &structure;
  };
  for (const char* name : kFeatures) {
    if (VkBool32* flag = findFeature(info.pNext, name)) {
      *flag = VK_TRUE;
    } else if (!perFeatureStructs) {
      for (const char* all : kFeatures) *featureIn(vulkan13_, all) = VK_TRUE;  // none of them was in the chain
      link(vulkan13_);
    } else if (std::string_view(name) == "synchronization2") {
      synchronization2_.synchronization2 = VK_TRUE;
      link(synchronization2_);
    } else if (std::string_view(name) == "dynamicRendering") {
      dynamicRendering_.dynamicRendering = VK_TRUE;
      link(dynamicRendering_);
    } else {
      maintenance4_.maintenance4 = VK_TRUE;
      link(maintenance4_);
    }
  }
}

}  // namespace s3d::vk
