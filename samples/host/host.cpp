// A minimal engine frame around s3d: the host creates its instance and device (s3d's requirements patched in),
// fills its own colour (sRGB) and hardware depth (D32 with a first-person depth range) images, asks the library
// for the frame's comfort state, records the stereo pass into its own command buffer for an anaglyph and a
// side-by-side target, submits on its own queue, and checks both against s3d's C++ reference.
// Exit status 0 when they agree; writes anaglyph.ppm and side_by_side.ppm into the working directory.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <s3d/comfort/frame_comfort_state.h>
#include <s3d/hud/crosshair.h>
#include <s3d/stereo/host_stereo_pass.h>
#include <s3d/stereo/output_formats.h>
#include <s3d/stereo/stereo.h>
#include <s3d/vk/check.h>
#include <s3d/vk/context.h>
#include <s3d/vk/resources.h>

namespace {

constexpr std::uint32_t kWidth = 160, kHeight = 96;
constexpr float kNear = 0.1f, kFar = 200.0f, kFirstPersonRange = 0.1f, kWeaponNear = 0.05f, kWeaponFar = 5.0f;

struct HostVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;

  HostVulkan() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    S3D_VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    std::uint32_t count = 0;
    S3D_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    S3D_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    for (VkPhysicalDevice candidate : devices) {  // lavapipe by default: the CPU device
      VkPhysicalDeviceProperties properties{};
      vkGetPhysicalDeviceProperties(candidate, &properties);
      if (s3d::vk::missingDeviceSupport(candidate).empty() &&
          (!physicalDevice || properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU))
        physicalDevice = candidate;
    }
    if (!physicalDevice) throw std::runtime_error("no Vulkan device s3d can use");
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;  // family 0 does graphics and compute on lavapipe and desktop GPUs
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    s3d::vk::DeviceRequirementsPatch patch(physicalDevice, deviceInfo);  // s3d's extensions and features
    S3D_VK_CHECK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.queueFamilyIndex = queueFamily;
    S3D_VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  }
  ~HostVulkan() {
    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyDevice(device, nullptr);
    vkDestroyInstance(instance, nullptr);
  }
};

// The host's "scene": a checkered wall at 20 m, a box at 3 m, the weapon (first-person layer) at 0.3-0.6 m.
struct HostScene {
  s3d::ImageRGBA8 color{kWidth, kHeight};
  std::vector<float> device = std::vector<float>(std::size_t(kWidth) * kHeight);
  s3d::DepthImage linear{kWidth, kHeight};  // what the host drew, for its own bookkeeping (weapon unpushed)
  std::vector<std::uint8_t> weapon = std::vector<std::uint8_t>(std::size_t(kWidth) * kHeight);
};

float deviceDepth(float z, bool firstPerson) {
  const float n = firstPerson ? kWeaponNear : kNear, f = firstPerson ? kWeaponFar : kFar;
  const float d = f / (f - n) - f * n / ((f - n) * z);
  return firstPerson ? d * kFirstPersonRange : kFirstPersonRange + d * (1.0f - kFirstPersonRange);
}

HostScene drawScene() {
  HostScene scene;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::size_t i = std::size_t(y) * kWidth + x;
      std::uint8_t* c = scene.color.at(x, y);
      float z = 20.0f;
      bool firstPerson = false;
      std::uint8_t rgb[3] = {std::uint8_t(((x / 8 + y / 8) % 2) ? 200 : 60), 90, 140};
      if (x >= 50 && x < 90 && y >= 30 && y < 70) {
        z = 3.0f;
        rgb[0] = 230; rgb[1] = 180; rgb[2] = 40;
      }
      if (x >= 110 && y >= 60 && x - 110 < (y - 60) * 2) {
        z = 0.3f + 0.3f * float(kHeight - y) / 36.0f;
        firstPerson = true;
        rgb[0] = 70; rgb[1] = 70; rgb[2] = 80;
      }
      c[0] = rgb[0]; c[1] = rgb[1]; c[2] = rgb[2]; c[3] = 255;
      scene.device[i] = deviceDepth(z, firstPerson);
      scene.linear.pixels[i] = z;
      scene.weapon[i] = firstPerson;
    }
  return scene;
}

void writePpm(const char* path, const s3d::ImageRGBA8& image) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << image.width << " " << image.height << "\n255\n";
  for (std::size_t i = 0; i < image.pixelCount(); ++i) out.write(reinterpret_cast<const char*>(&image.pixels[i * 4]), 3);
}

int largestDifference(const s3d::ImageRGBA8& a, const s3d::ImageRGBA8& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
}

}  // namespace

int main() try {
  HostVulkan host;
  s3d::vk::HostDevice adopted;
  adopted.instance = host.instance;
  adopted.physicalDevice = host.physicalDevice;
  adopted.device = host.device;
  adopted.queueFamily = host.queueFamily;
  adopted.queue = host.queue;
  s3d::vk::Context context(adopted);
  const HostScene scene = drawScene();

  // Per frame: the comfort rules from the host's own knowledge (weapon depth range, nearest world depth, HUD).
  s3d::comfort::FrameComfortInput comfortInput;
  comfortInput.width = kWidth;
  comfortInput.parameters.maxSeparation = 0.03f;
  comfortInput.parameters.zeroParallaxDistance = 5.0f;
  comfortInput.parameters.method = s3d::stereo::StereoMethod::Search;
  comfortInput.rayCast = [](glm::vec3, glm::vec3, float maxDistance) -> std::optional<float> {
    return maxDistance > 3.0f ? std::optional<float>(3.0f) : std::nullopt;  // the host's physics: the box
  };
  comfortInput.weapon = {1, 0.3f, 0.6f};
  comfortInput.nearestWorldDepth = 3.0f;
  comfortInput.hud = {{"health", 2.0f}, {"ammo", 2.0f}};
  const s3d::comfort::FrameComfortState comfort = s3d::comfort::frameComfortState(comfortInput);
  std::printf("comfort: zero parallax %.3f m%s, weapon push %.3f + %.3f d, crosshair %.2f m (%+.2f px)\n",
              comfort.parameters.zeroParallaxDistance, comfort.zeroParallaxLimited ? " (held at the nearest depth)" : "",
              comfort.parameters.weaponDepthOffset, comfort.parameters.weaponDepthScale, comfort.crosshairDepth,
              comfort.crosshair.parallaxPx);

  s3d::stereo::HostFrame frame;
  frame.stereo = s3d::stereo::makeStereoConstants(comfort.parameters, kWidth, kHeight);
  frame.projection = {kNear, kFar, false, false, kFirstPersonRange, kWeaponNear, kWeaponFar};
  frame.weaponDepthOffset = comfort.parameters.weaponDepthOffset;
  frame.weaponDepthScale = comfort.parameters.weaponDepthScale;

  // The host's images (made with s3d's helpers for brevity; any VkImage with these usages works).
  using s3d::vk::ImageState;
  const ImageState shaderRead{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                              VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  const ImageState copiedOut{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
  const VkImageUsageFlags inputUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  s3d::vk::Image color = s3d::vk::createImage(context, VK_FORMAT_R8G8B8A8_SRGB, kWidth, kHeight, inputUsage);
  s3d::vk::Image depth = s3d::vk::createImage(context, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, inputUsage);
  s3d::vk::uploadImage(context, color, std::as_bytes(std::span(scene.color.pixels)), shaderRead);
  s3d::vk::uploadImage(context, depth, std::as_bytes(std::span(scene.device)), shaderRead);
  auto hostImage = [](const s3d::vk::Image& image, const ImageState& state) {
    return s3d::stereo::HostImage{image.image, image.view, image.format, state.layout, state.stage, state.access};
  };

  using s3d::stereo::HostOutput;
  s3d::stereo::HostStereoPass anaglyphPass(context, {kWidth, kHeight, color.format, depth.format, HostOutput::Anaglyph});
  s3d::stereo::HostStereoPass sideBySidePass(context, {kWidth, kHeight, color.format, depth.format, HostOutput::SideBySideHalf});
  const VkImageUsageFlags outputUsage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  s3d::vk::Image anaglyph = s3d::vk::createImage(context, anaglyphPass.eyeFormat(), kWidth, kHeight, outputUsage);
  s3d::vk::Image sideBySide = s3d::vk::createImage(context, sideBySidePass.eyeFormat(), kWidth, kHeight, outputUsage);

  // The host's frame: its own command buffer, queue and fence.
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = host.pool;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkAllocateCommandBuffers(host.device, &allocInfo, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  S3D_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  for (const s3d::vk::Image* target : {&anaglyph, &sideBySide})
    s3d::vk::transition(cmd, *target, s3d::vk::kUndefined, copiedOut);
  const s3d::stereo::HostImage anaglyphTarget = hostImage(anaglyph, copiedOut), sideBySideTarget = hostImage(sideBySide, copiedOut);
  anaglyphPass.record(cmd, hostImage(color, shaderRead), hostImage(depth, shaderRead), frame, nullptr, nullptr, &anaglyphTarget);
  sideBySidePass.record(cmd, hostImage(color, shaderRead), hostImage(depth, shaderRead), frame, nullptr, nullptr, &sideBySideTarget);
  S3D_VK_CHECK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  S3D_VK_CHECK(vkQueueSubmit(host.queue, 1, &submit, VK_NULL_HANDLE));
  S3D_VK_CHECK(vkQueueWaitIdle(host.queue));

  auto read = [&](const s3d::vk::Image& image) {
    s3d::ImageRGBA8 result(image.width, image.height);
    const std::vector<std::byte> bytes = s3d::vk::readbackImage(context, image, copiedOut);
    std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
    return result;
  };
  const s3d::ImageRGBA8 gpuAnaglyph = read(anaglyph), gpuSideBySide = read(sideBySide);
  writePpm("anaglyph.ppm", gpuAnaglyph);
  writePpm("side_by_side.ppm", gpuSideBySide);

  // s3d's C++ reference on the same colour and depth (the depth linearized by the same shared formula).
  const s3d::gpu::LinearDepthParams params =
      s3d::stereo::linearDepthParams(frame.projection, frame.weaponDepthOffset, frame.weaponDepthScale);
  s3d::DepthImage stereoDepth(kWidth, kHeight);
  for (std::size_t i = 0; i < stereoDepth.pixels.size(); ++i)
    stereoDepth.pixels[i] = s3d::gpu::stereoDepthFromDevice(params, scene.device[i]);
  const s3d::stereo::StereoPair eyes = s3d::stereo::synthesizeStereoReference(scene.color, stereoDepth, frame.stereo);
  const int anaglyphError = largestDifference(gpuAnaglyph, s3d::stereo::makeAnaglyphDubois(eyes.left, eyes.right));
  const int sideBySideError =
      largestDifference(gpuSideBySide, s3d::stereo::makeSideBySide(eyes.left, eyes.right, s3d::stereo::PackingMode::Half));
  std::printf("device %s: anaglyph %d, side-by-side %d levels from the C++ reference\n", context.deviceName().c_str(),
              anaglyphError, sideBySideError);
  // Eyes within 1 level of the reference; packing adds its own rounding, the anaglyph mixes both eyes' errors.
  return anaglyphError <= 3 && sideBySideError <= 2 ? 0 : 1;
} catch (const std::exception& error) {
  std::fprintf(stderr, "s3d_host: %s\n", error.what());
  return 1;
}
