#include "s3d/vk/context.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "s3d/vk/check.h"
#include "s3d/vk/pipeline_statistics.h"
#include "s3d/vk/unique.h"

namespace s3d::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
  std::uint32_t count = 0;
  S3D_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  S3D_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  S3D_VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  S3D_VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<VkQueueFamilyProperties> queueFamilies(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  return families;
}

// A family with compute and without graphics (a GPU's asynchronous compute) and timestamps, or UINT32_MAX.
std::uint32_t findComputeOnlyQueue(VkPhysicalDevice device) {
  const std::vector<VkQueueFamilyProperties> families = queueFamilies(device);
  for (std::uint32_t i = 0; i < families.size(); ++i)
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && !(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
        families[i].timestampValidBits > 0)
      return i;
  return UINT32_MAX;
}

std::uint32_t findComputeGraphicsQueue(VkPhysicalDevice device) {
  const std::vector<VkQueueFamilyProperties> families = queueFamilies(device);
  for (std::uint32_t i = 0; i < families.size(); ++i)
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) return i;
  return UINT32_MAX;
}

// With a surface (presentation), the device must also present to it from the graphics+compute queue.
PhysicalDeviceInfo describe(VkPhysicalDevice device, std::uint32_t index, VkSurfaceKHR surface = VK_NULL_HANDLE) {
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device, &properties);
  PhysicalDeviceInfo info;
  info.index = index;
  info.name = properties.deviceName;
  info.type = properties.deviceType;
  info.apiVersion = properties.apiVersion;

  if (std::vector<std::string> missing = missingDeviceSupport(device); !missing.empty()) {
    for (const std::string& name : missing) info.unusableReason += (info.unusableReason.empty() ? "" : ", ") + name;
    info.unusableReason += " missing";
  } else if (findComputeGraphicsQueue(device) == UINT32_MAX)
    info.unusableReason = "no graphics+compute queue";
  else if (surface && !hasDeviceExtension(device, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
    info.unusableReason = "VK_KHR_swapchain missing (needed to show a window)";
  else
    info.usable = true;
  if (info.usable && surface) {
    VkBool32 presents = VK_FALSE;
    S3D_VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(device, findComputeGraphicsQueue(device), surface, &presents));
    if (!presents) {
      info.usable = false;
      info.unusableReason = "its graphics+compute queue cannot present to the window";
    }
  }
  return info;
}

VkInstance createInstance(bool validation, const std::vector<std::string>& extraExtensions = {}) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "s3d";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  const char* layers[] = {kValidationLayer};
  std::vector<const char*> extensions;
  for (const std::string& name : extraExtensions) extensions.push_back(name.c_str());
  if (validation) {
    if (!hasLayer(kValidationLayer))
      throw std::runtime_error(std::string("validation requested but ") + kValidationLayer +
                               " is not installed (Debian package vulkan-validationlayers)");
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  info.enabledExtensionCount = std::uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw std::runtime_error(
        "no Vulkan driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER); install mesa-vulkan-drivers "
        "for the CPU device or a GPU driver");
  check(result, "vkCreateInstance");
  return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  std::uint32_t count = 0;
  S3D_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  S3D_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

bool isGpu(VkPhysicalDeviceType type) {
  return type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU || type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ||
         type == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU;
}

std::string listing(const std::vector<PhysicalDeviceInfo>& infos) {
  std::string text;
  for (const PhysicalDeviceInfo& i : infos)
    text += "\n  [" + std::to_string(i.index) + "] " + i.name + (i.usable ? "" : " (unusable: " + i.unusableReason + ")");
  return infos.empty() ? std::string("\n  (none)") : text;
}

// Picks the device named by `choice`: auto prefers a discrete GPU, then any GPU, then the CPU (lavapipe).
std::uint32_t chooseDevice(const std::vector<PhysicalDeviceInfo>& infos, const std::string& choice) {
  auto pick = [&](auto predicate) -> std::uint32_t {
    for (const PhysicalDeviceInfo& i : infos)
      if (i.usable && predicate(i)) return i.index;
    return UINT32_MAX;
  };
  std::uint32_t chosen = UINT32_MAX;
  if (choice == "auto" || choice == "gpu") {
    chosen = pick([](const PhysicalDeviceInfo& i) { return i.type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU; });
    if (chosen == UINT32_MAX) chosen = pick([](const PhysicalDeviceInfo& i) { return isGpu(i.type); });
    if (chosen == UINT32_MAX && choice == "auto")
      chosen = pick([](const PhysicalDeviceInfo& i) { return i.type == VK_PHYSICAL_DEVICE_TYPE_CPU; });
    if (chosen == UINT32_MAX) chosen = choice == "auto" ? pick([](const PhysicalDeviceInfo&) { return true; }) : chosen;
  } else if (choice == "cpu") {
    chosen = pick([](const PhysicalDeviceInfo& i) { return i.type == VK_PHYSICAL_DEVICE_TYPE_CPU; });
  } else if (!choice.empty() && std::all_of(choice.begin(), choice.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    std::uint32_t index = static_cast<std::uint32_t>(std::stoul(choice));
    if (index < infos.size() && infos[index].usable) chosen = index;
  } else {
    throw std::invalid_argument("unknown device choice '" + choice + "' (expected auto, cpu, gpu or an index)");
  }
  if (chosen == UINT32_MAX) {
    // Advice that fits what is there: a GPU driver when only the CPU device exists, lavapipe when nothing does.
    const bool hasCpu = std::any_of(infos.begin(), infos.end(), [](const PhysicalDeviceInfo& i) {
      return i.type == VK_PHYSICAL_DEVICE_TYPE_CPU && i.usable;
    });
    const std::string advice = choice == "gpu" && hasCpu ? "no usable GPU: install its Vulkan driver, or use --device cpu"
                               : hasCpu                  ? "--device auto picks a usable one"
                                                         : "install mesa-vulkan-drivers for the CPU device lavapipe";
    throw std::runtime_error("no usable Vulkan device for --device " + choice + "; devices found:" + listing(infos) +
                             "\n(" + advice + ")");
  }
  return chosen;
}

}  // namespace

std::vector<PhysicalDeviceInfo> listPhysicalDevices() {
  VkInstance instance = createInstance(false);
  std::vector<PhysicalDeviceInfo> infos;
  try {
    std::vector<VkPhysicalDevice> devices = physicalDevices(instance);
    for (std::uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return infos;
}

Context::Context(const ContextOptions& options) {
  instance_ = createInstance(options.validation, options.instanceExtensions);
  try {
    if (options.validation) {
      VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
      info.messageSeverity =
          VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
      info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
      info.pfnUserCallback = &Context::onValidationMessage;
      info.pUserData = this;
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (!create) throw std::runtime_error("vkCreateDebugUtilsMessengerEXT not available");
      S3D_VK_CHECK(create(instance_, &info, nullptr, &messenger_));
    }

    if (options.createSurface) {
      surface_ = options.createSurface(instance_);
      if (!surface_) throw std::runtime_error("creating the window surface failed");
    }
    std::vector<VkPhysicalDevice> devices = physicalDevices(instance_);
    std::vector<PhysicalDeviceInfo> infos;
    for (std::uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i, surface_));
    std::uint32_t chosen = chooseDevice(infos, options.device);
    physicalDevice_ = devices[chosen];
    deviceName_ = infos[chosen].name;
    deviceType_ = infos[chosen].type;
    queueFamily_ = findComputeGraphicsQueue(physicalDevice_);
    sharingFamilies_ = {queueFamily_};

    // And an asynchronous compute queue where the device has one: a stereo frame's second eye render runs there
    // beside the first (submitConcurrentlyAndWait).
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfos[2]{{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO},
                                          {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO}};
    queueInfos[0].queueFamilyIndex = queueFamily_;
    const std::uint32_t computeFamily = findComputeOnlyQueue(physicalDevice_);
    queueInfos[1].queueFamilyIndex = computeFamily;
    for (VkDeviceQueueCreateInfo& queueInfo : queueInfos) {
      queueInfo.queueCount = 1;
      queueInfo.pQueuePriorities = &priority;
    }
    // The tools' own device goes through the same requirements a host enables.
    std::vector<const char*> extensions;
    if (surface_) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.queueCreateInfoCount = computeFamily != UINT32_MAX ? 2u : 1u;
    deviceInfo.pQueueCreateInfos = queueInfos;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR statisticsFeature{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    capturesPipelineStatistics_ = pipelineStatisticsRequested() &&
                                  hasDeviceExtension(physicalDevice_, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    if (capturesPipelineStatistics_) {
      extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
      statisticsFeature.pipelineExecutableInfo = VK_TRUE;
      deviceInfo.pNext = &statisticsFeature;
    }
    deviceInfo.enabledExtensionCount = std::uint32_t(extensions.size());
    deviceInfo.ppEnabledExtensionNames = extensions.data();
    DeviceRequirementsPatch requirements(physicalDevice_, deviceInfo);
    S3D_VK_CHECK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
    if (computeFamily != UINT32_MAX) {
      vkGetDeviceQueue(device_, computeFamily, 0, &concurrentQueue_);
      sharingFamilies_ = {queueFamily_, computeFamily};
    }
    initDeviceState();
  } catch (...) {
    release();  // a throwing constructor runs no destructor
    throw;
  }
}

Context::Context(const HostDevice& host) : ownsDevice_(false), allocator_(host.allocator), pipelineCache_(host.pipelineCache) {
  if (!host.instance || !host.physicalDevice || !host.device || !host.queue)
    throw std::invalid_argument("s3d: the host device needs its VkInstance, VkPhysicalDevice, VkDevice and VkQueue");
  std::vector<std::string> missing = missingDeviceSupport(host.physicalDevice);
  if (missing.empty() && host.createInfo) missing = missingEnabledRequirements(*host.createInfo);
  if (!missing.empty()) {
    std::string names;
    for (const std::string& name : missing) names += (names.empty() ? "" : ", ") + name;
    throw std::runtime_error("s3d cannot run on the host's device: it lacks " + names +
                             " (enable s3d::vk::deviceRequirements() when creating it, e.g. with DeviceRequirementsPatch)");
  }
  const std::vector<VkQueueFamilyProperties> families = queueFamilies(host.physicalDevice);
  if (host.queueFamily >= families.size() || !(families[host.queueFamily].queueFlags & VK_QUEUE_COMPUTE_BIT))
    throw std::runtime_error("s3d cannot run on the host's queue family " + std::to_string(host.queueFamily) +
                             ": s3d records compute work and the family has no compute");
  instance_ = host.instance;
  physicalDevice_ = host.physicalDevice;
  device_ = host.device;
  queue_ = host.queue;
  queueFamily_ = host.queueFamily;
  sharingFamilies_ = {queueFamily_};
  try {
    initDeviceState();
  } catch (...) {
    release();
    throw;
  }
}

void Context::initDeviceState() {
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties);
  deviceName_ = properties.deviceName;
  deviceType_ = properties.deviceType;
  if (queueFamilies(physicalDevice_)[queueFamily_].timestampValidBits > 0) timestampPeriodNs_ = properties.limits.timestampPeriod;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);

  cmdPushDescriptorSet =
      reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
  if (!cmdPushDescriptorSet) throw std::runtime_error("vkCmdPushDescriptorSetKHR not available on " + deviceName_);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  S3D_VK_CHECK(vkCreateCommandPool(device_, &poolInfo, allocator_, &commandPool_));
  if (concurrentQueue_ != VK_NULL_HANDLE) {
    poolInfo.queueFamilyIndex = sharingFamilies_[1];
    S3D_VK_CHECK(vkCreateCommandPool(device_, &poolInfo, allocator_, &concurrentPool_));
  }
}

Context::~Context() { release(); }

void Context::release() {
  if (!ownsDevice_) {  // the host's device, instance and queue stay; only s3d's pool goes
    if (commandPool_) vkDestroyCommandPool(device_, commandPool_, allocator_);
    commandPool_ = VK_NULL_HANDLE;
    return;
  }
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (commandPool_) vkDestroyCommandPool(device_, commandPool_, nullptr);
    if (concurrentPool_) vkDestroyCommandPool(device_, concurrentPool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (instance_) vkDestroyInstance(instance_, nullptr);
  commandPool_ = concurrentPool_ = VK_NULL_HANDLE;
  device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  surface_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

std::uint32_t Context::findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                      VkMemoryPropertyFlags preferred) const {
  for (int pass = 0; pass < 2; ++pass) {
    VkMemoryPropertyFlags wanted = pass == 0 ? (required | preferred) : required;
    for (std::uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i)
      if ((typeBits & (1u << i)) && (memoryProperties_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  }
  throw std::runtime_error("no Vulkan memory type with the required properties on " + deviceName_);
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) { submitConcurrentlyAndWait({record}); }

void Context::submitConcurrentlyAndWait(const std::vector<std::function<void(VkCommandBuffer)>>& records) {
  if (records.empty()) return;
  std::vector<VkCommandBuffer> cmds(records.size(), VK_NULL_HANDLE);
  const VkCommandPool restPool = concurrentPool_ != VK_NULL_HANDLE ? concurrentPool_ : commandPool_;
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = commandPool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  S3D_VK_CHECK(vkAllocateCommandBuffers(device_, &allocInfo, cmds.data()));
  if (cmds.size() > 1) {
    allocInfo.commandPool = restPool;
    allocInfo.commandBufferCount = std::uint32_t(cmds.size() - 1);
    S3D_VK_CHECK(vkAllocateCommandBuffers(device_, &allocInfo, cmds.data() + 1));
  }
  struct FreeOnExit {
    VkDevice device;
    VkCommandPool pool, restPool;
    std::vector<VkCommandBuffer>& cmds;
    ~FreeOnExit() {
      vkFreeCommandBuffers(device, pool, 1, cmds.data());
      if (cmds.size() > 1) vkFreeCommandBuffers(device, restPool, std::uint32_t(cmds.size() - 1), cmds.data() + 1);
    }
  } freeOnExit{device_, commandPool_, restPool, cmds};
  for (std::size_t i = 0; i < records.size(); ++i) {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    S3D_VK_CHECK(vkBeginCommandBuffer(cmds[i], &begin));
    records[i](cmds[i]);
    S3D_VK_CHECK(vkEndCommandBuffer(cmds[i]));
  }
  std::vector<VkCommandBufferSubmitInfo> cmdInfos(cmds.size(), {VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO});
  for (std::size_t i = 0; i < cmds.size(); ++i) cmdInfos[i].commandBuffer = cmds[i];
  // The first recording on queue(), the rest together on the compute queue (or after it on queue()).
  const VkQueue rest = concurrentQueue_ != VK_NULL_HANDLE ? concurrentQueue_ : queue_;
  VkSubmitInfo2 firstSubmit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  firstSubmit.commandBufferInfoCount = 1;
  firstSubmit.pCommandBufferInfos = cmdInfos.data();
  VkSubmitInfo2 restSubmit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  restSubmit.commandBufferInfoCount = std::uint32_t(cmdInfos.size() - 1);
  restSubmit.pCommandBufferInfos = cmdInfos.data() + 1;
  // One fence per submission: the first's, and the rest's where there are more recordings.
  const std::uint32_t submissions = restSubmit.commandBufferInfoCount > 0 ? 2u : 1u;
  std::vector<Unique<VkFence>> fences;
  fences.reserve(submissions);
  std::vector<VkFence> rawFences;
  for (std::uint32_t i = 0; i < submissions; ++i) {
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence rawFence = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateFence(device_, &fenceInfo, allocator_, &rawFence));
    fences.emplace_back(device_, rawFence, vkDestroyFence, allocator_);
    rawFences.push_back(rawFence);
  }
  S3D_VK_CHECK(vkQueueSubmit2(queue_, 1, &firstSubmit, rawFences[0]));
  if (submissions > 1) S3D_VK_CHECK(vkQueueSubmit2(rest, 1, &restSubmit, rawFences[1]));
  S3D_VK_CHECK(vkWaitForFences(device_, submissions, rawFences.data(), VK_TRUE, UINT64_MAX));
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return validationMessages_;
}

void Context::clearValidationMessages() {
  std::lock_guard lock(messagesMutex_);
  validationMessages_.clear();
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                            VkDebugUtilsMessageTypeFlagsEXT,
                                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                            void* user) {
  auto* context = static_cast<Context*>(user);
  std::lock_guard lock(context->messagesMutex_);
  context->validationMessages_.emplace_back(data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
}

}  // namespace s3d::vk
