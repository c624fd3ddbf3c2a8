// A game that is not s3d, using only the installed package: it makes its own Vulkan instance and device (s3d's
// requirements patched in), renders its own lit scene with a first-person object in its own depth range (its own
// pipeline and shaders, D32 depth), then per frame asks s3d's host comfort frame for the comfort state (the
// zero-parallax plane held at the nearest depth its GPU reduction saw last frame) and records it (the reduction and
// an anaglyph) and a second stereo pass (side by side) with the HUD drawn into the eyes before packing, all into its
// own command buffer on its own queue. It reads back its colour and depth and checks both targets against s3d's C++ reference
// on them; writes anaglyph.png and side_by_side.png (into the folder given, else the working directory).
// Exit status 0 when they agree and the validation layer (when installed) reported nothing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <s3d/comfort/host_comfort_frame.h>
#include <s3d/hud/hud_pass.h>
#include <s3d/io/image_io.h>
#include <s3d/stereo/host_stereo_pass.h>
#include <s3d/stereo/output_formats.h>
#include <s3d/stereo/stereo.h>
#include <s3d/vk/context.h>

#include "host_scene.h"
#include "host_vulkan.h"

namespace {

constexpr std::uint32_t kWidth = 320, kHeight = 192;

// The host's own HUD art: a compass rose, straight alpha, drawn once on the CPU and uploaded by the host.
s3d::ImageRGBA8 compassPixels() {
  s3d::ImageRGBA8 image(33, 33);
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const float dx = float(x) - 16.0f, dy = float(y) - 16.0f, r = std::sqrt(dx * dx + dy * dy);
      std::uint8_t* p = image.at(x, y);
      const bool ring = r > 13.0f && r <= 16.0f, needle = std::abs(dx) <= 1.0f && dy < 0.0f && dy > -12.0f;
      if (!ring && !needle) continue;
      p[0] = needle ? 230 : 240;
      p[1] = needle ? 40 : 240;
      p[2] = needle ? 40 : 240;
      p[3] = needle ? 255 : 170;  // a translucent ring: the blend, not just a copy
    }
  return image;
}

s3d::stereo::HostImage hostImage(const host::Image& image, VkImageLayout layout, VkPipelineStageFlags2 stage,
                                 VkAccessFlags2 access) {
  return {image.image, image.view, image.format, layout, stage, access};
}

int largestDifference(const s3d::ImageRGBA8& a, const s3d::ImageRGBA8& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (i % 4 != 3) largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
}

s3d::ImageRGBA8 readRgba8(const host::Buffer& buffer, std::uint32_t width, std::uint32_t height) {
  s3d::ImageRGBA8 image(width, height);
  std::memcpy(image.pixels.data(), buffer.mapped, image.pixels.size());
  return image;
}

// Written whole or not at all (s3d::io writes a temporary file, then renames it); throws naming the file.
void writePng(const std::string& path, s3d::ImageRGBA8 image) {
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;  // the packed alpha is no mask
  s3d::io::writePng(path, image);
}

}  // namespace

// One frame in a host's order, top to bottom (set up, record, submit, check, write): longer than 80 lines so that the
// example reads as a walkthrough without jumping between helpers.
int main(int argc, char** argv) try {
  const std::string outputFolder = argc > 1 ? argv[1] : ".";
  host::Device device(/*validation, when the layer is installed*/ true);
  s3d::vk::HostDevice adopted;
  adopted.instance = device.instance;
  adopted.physicalDevice = device.physicalDevice;
  adopted.device = device.device;
  adopted.queueFamily = device.queueFamily;
  adopted.queue = device.queue;
  s3d::vk::Context context(adopted);
  host::Scene scene(device, kWidth, kHeight);
  const host::Camera& camera = scene.camera();

  // The host's frame images and the buffers it reads them back through.
  const VkImageUsageFlags inputUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  host::Image color(device, VK_FORMAT_R8G8B8A8_SRGB, kWidth, kHeight, inputUsage | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
  host::Image depth(device, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, inputUsage | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
  using s3d::stereo::HostOutput;
  // The anaglyph through the host comfort frame (one frame in flight: the host waits for each frame's submission).
  s3d::comfort::HostComfortFrameDesc comfortDesc;
  comfortDesc.stereo = {kWidth, kHeight, color.format, depth.format, HostOutput::Anaglyph};
  comfortDesc.framesInFlight = 1;
  s3d::comfort::HostComfortFrame anaglyphFrame(context, comfortDesc);
  const s3d::stereo::StereoFrame& anaglyphPass = anaglyphFrame.stereoFrame();
  const s3d::stereo::HostStereoPass sideBySidePass(context, {kWidth, kHeight, color.format, depth.format,
                                                             HostOutput::SideBySideHalf});
  const VkImageUsageFlags targetUsage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  host::Image anaglyph(device, anaglyphPass.eyeFormat(), anaglyphPass.packedWidth(), anaglyphPass.packedHeight(), targetUsage);
  host::Image sideBySide(device, sideBySidePass.eyeFormat(), sideBySidePass.packedWidth(), sideBySidePass.packedHeight(),
                         targetUsage);
  const host::Buffer colorBytes(device, kWidth * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  const host::Buffer depthBytes(device, kWidth * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  const host::Buffer anaglyphBytes(device, kWidth * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  const host::Buffer sideBySideBytes(device, kWidth * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);

  // The HUD: s3d's panels and crosshair (uploaded once by s3d) and the host's compass image (its own upload).
  const s3d::ImageRGBA8 compass = compassPixels();
  std::vector<s3d::hud::HudLayer> hudLayers = s3d::hud::builtInHudLayers(kWidth, kHeight);  // health, ammo, crosshair
  hudLayers.push_back({"compass", compass, {0.5f * float(kWidth - 1), 8.0f, 16, 0}});        // top center
  s3d::hud::HudPassDesc hudDesc{kWidth, kHeight, {}};
  for (std::size_t i = 0; i < 3; ++i) hudDesc.elements.push_back(s3d::hud::HudPassElement::uploaded(hudLayers[i]));
  hudDesc.elements.push_back(s3d::hud::HudPassElement::hostLayer("compass", compass.width, compass.height,
                                                                 hudLayers[3].placement));
  const s3d::hud::HudPass hud(context, hudDesc);
  host::Image compassImage(device, VK_FORMAT_R8G8B8A8_UNORM, compass.width, compass.height,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  {
    const host::Buffer staging(device, compass.pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::memcpy(staging.mapped, compass.pixels.data(), compass.pixels.size());
    device.submitAndWait([&](VkCommandBuffer cmd) {
      host::imageBarrier(cmd, compassImage, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT);
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {compass.width, compass.height, 1};
      vkCmdCopyBufferToImage(cmd, staging.buffer, compassImage.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
      host::imageBarrier(cmd, compassImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                         VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
  }
  // Uploaded and waited for above, then only read: the host has synchronized it (stage NONE).
  const s3d::stereo::HostImage compassLayer =
      hostImage(compassImage, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);

  s3d::stereo::HostFrame frame;
  frame.projection = {camera.nearPlane, camera.farPlane, false, false, camera.firstPersonDepthRange,
                      camera.weaponNear, camera.weaponFar};
  std::vector<s3d::hud::HudElementFrame> hudFrames;
  for (int frameIndex = 0; frameIndex < 2; ++frameIndex) {
    // The frame's comfort state from what the host knows: its camera, its physics, its weapon, its HUD depths; the
    // nearest depth is the reduction's of the previous frame.
    s3d::comfort::HostComfortInput comfortInput;
    comfortInput.frameSlot = 0;
    comfortInput.camera = {camera.position, camera.forward, camera.nearPlane};
    comfortInput.rayCast = [&scene](glm::vec3 origin, glm::vec3 direction, float maxDistance) {
      return scene.rayCast(origin, direction, maxDistance);
    };
    comfortInput.parameters.maxSeparation = 0.025f;
    comfortInput.parameters.zeroParallaxDistance = 6.0f;
    const glm::vec2 weaponDepths = scene.weaponDepthRange();
    comfortInput.weapon = {1, weaponDepths.x, weaponDepths.y};
    comfortInput.hud = {{"health", 2.0f}, {"ammo", 2.0f}, {"compass", 4.0f}};
    const s3d::comfort::FrameComfortState& comfort = anaglyphFrame.update(comfortInput);
    auto hudFrame = [](const s3d::comfort::HudElementState& state) {
      return s3d::hud::HudElementFrame{state.parallaxPx, state.fadesBehindWeapon, false};
    };
    hudFrames = {hudFrame(comfort.hud[0]), hudFrame(comfort.hud[1]), hudFrame(comfort.crosshair), hudFrame(comfort.hud[2])};
    frame.stereo = s3d::stereo::makeStereoConstants(comfort.parameters, kWidth, kHeight);
    frame.weaponDepthOffset = comfort.parameters.weaponDepthOffset;
    frame.weaponDepthScale = comfort.parameters.weaponDepthScale;
    std::printf("frame %d: zero parallax %.2f m%s, weapon push %.2f + %.2f d, crosshair %.2f m (%+.2f px)\n", frameIndex,
                comfort.parameters.zeroParallaxDistance, comfort.zeroParallaxLimited ? " (held at the nearest depth)" : "",
                comfort.parameters.weaponDepthOffset, comfort.parameters.weaponDepthScale, comfort.crosshairDepth,
                comfort.crosshair.parallaxPx);

    // One command buffer: the scene, s3d's passes (they add their own barriers from the stated accesses), copies.
    device.submitAndWait([&](VkCommandBuffer cmd) {
      host::imageBarrier(cmd, color, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
      const VkPipelineStageFlags2 depthStages =
          VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
      host::imageBarrier(cmd, depth, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, depthStages,
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
      for (const host::Image* target : {&anaglyph, &sideBySide})
        host::imageBarrier(cmd, *target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                           VK_ACCESS_2_TRANSFER_READ_BIT);
      scene.record(cmd, color, depth);

      const s3d::stereo::HostImage colorIn =
          hostImage(color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
      const s3d::stereo::HostImage depthIn = hostImage(depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depthStages,
                                                       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
      const s3d::stereo::HostImage anaglyphOut = hostImage(anaglyph, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                           VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      const s3d::stereo::HostImage sideBySideOut = hostImage(sideBySide, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      const s3d::hud::HudOverlay overlay = hud.overlay(hudFrames, std::span(&compassLayer, 1));
      s3d::stereo::StereoFrameDispatch dispatch;  // the separation, plane and weapon push come from the state
      dispatch.color = colorIn;
      dispatch.depth = depthIn;
      dispatch.target = anaglyphOut;
      dispatch.projection = frame.projection;
      dispatch.overlay = &overlay;
      anaglyphFrame.record(cmd, dispatch);
      sideBySidePass.record(cmd, colorIn, depthIn, frame, nullptr, nullptr, &sideBySideOut, &overlay);

      host::imageBarrier(cmd, color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      host::imageBarrier(cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         depthStages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_READ_BIT);
      host::copyImageToBuffer(cmd, color, colorBytes);
      host::copyImageToBuffer(cmd, depth, depthBytes);
      host::copyImageToBuffer(cmd, anaglyph, anaglyphBytes);
      host::copyImageToBuffer(cmd, sideBySide, sideBySideBytes);
    });
  }

  // s3d's C++ reference on the same colour and depth: linear depth by the shared formula, eyes, HUD, packing.
  const s3d::ImageRGBA8 center = readRgba8(colorBytes, kWidth, kHeight);
  const s3d::gpu::LinearDepthParams params =
      s3d::stereo::linearDepthParams(frame.projection, frame.weaponDepthOffset, frame.weaponDepthScale);
  s3d::DepthImage stereoDepth(kWidth, kHeight);
  const auto* deviceDepth = static_cast<const float*>(depthBytes.mapped);
  for (std::size_t i = 0; i < stereoDepth.pixels.size(); ++i)
    stereoDepth.pixels[i] = s3d::gpu::stereoDepthFromDevice(params, deviceDepth[i]);
  s3d::stereo::StereoPair eyes = s3d::stereo::synthesizeStereoReference(center, stereoDepth, frame.stereo);
  s3d::hud::compositeHud(eyes.left, s3d::stereo::Eye::Left, hudLayers, hudFrames);
  s3d::hud::compositeHud(eyes.right, s3d::stereo::Eye::Right, hudLayers, hudFrames);
  const s3d::ImageRGBA8 gpuAnaglyph = readRgba8(anaglyphBytes, anaglyph.width, anaglyph.height);
  const s3d::ImageRGBA8 gpuSideBySide = readRgba8(sideBySideBytes, sideBySide.width, sideBySide.height);
  const int anaglyphError = largestDifference(gpuAnaglyph, s3d::stereo::makeAnaglyphDubois(eyes.left, eyes.right));
  const int sideBySideError = largestDifference(
      gpuSideBySide, s3d::stereo::makeSideBySide(eyes.left, eyes.right, s3d::stereo::PackingMode::Half));

  writePng(outputFolder + "/anaglyph.png", gpuAnaglyph);
  writePng(outputFolder + "/side_by_side.png", gpuSideBySide);
  std::printf("device %s: anaglyph %d, side-by-side %d levels from the C++ reference; validation layer %s, %d messages\n",
              device.name.c_str(), anaglyphError, sideBySideError, device.validation ? "on" : "not installed",
              device.validationMessages);
  // Eyes within 1 level of the reference (its rounding) and the HUD's 1 level (a float division an ulp apart);
  // half packing filters pixel pairs, the anaglyph mixes both eyes' differences through its matrix.
  const bool agrees = anaglyphError <= 3 && sideBySideError <= 2;
  if (!agrees) std::fprintf(stderr, "s3d_host: the GPU output differs from the C++ reference\n");
  return agrees && device.validationMessages == 0 ? 0 : 1;
} catch (const std::exception& error) {
  std::fprintf(stderr, "s3d_host: %s\n", error.what());
  return 1;
}
