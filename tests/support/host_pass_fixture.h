#pragma once
// The host-pass tests' fixture: a TestHost device (synchronization validation on), a synthetic block view, the
// host's formats uploaded as a renderer would leave them, eyes read back; shared by the host pass and the stereo
// frame tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>

#include "depth_texels.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "stereo_test_views.h"
#include "test_host.h"

namespace s3d::test {
namespace {
using stereo::HostImage;
using stereo::HostOutput;
using stereo::HostProjection;

constexpr std::uint32_t kWidth = 48, kHeight = 32;
constexpr vk::ImageState kShaderRead{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
constexpr vk::ImageState kDepthWritten{VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                                       VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
// Eyes the host copies out next (to a swapchain, here to the test's readback).
constexpr vk::ImageState kCopiedOut{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                    VK_ACCESS_2_TRANSFER_READ_BIT};

HostImage hostImage(const vk::Image& image, const vk::ImageState& state) {
  return {image.image, image.view, image.format, state.layout, state.stage, state.access};
}

// The device depth the host's projection writes for linear depth z (Vulkan's 0..1 depth, +inf: the cleared sky).
float deviceDepth(const HostProjection& p, float z) {
  const bool weapon = p.firstPersonDepthRange > 0.0f && z < 2.0f;  // the test's nearest blocks are the weapon
  const float n = weapon ? p.firstPersonNear : p.nearPlane, f = weapon ? p.firstPersonFar : p.farPlane;
  float d;
  if (std::isinf(z)) d = 1.0f;
  else if (p.infiniteFarPlane && !weapon) d = 1.0f - n / z;
  else d = f / (f - n) - f * n / ((f - n) * z);
  if (p.reversedZ) d = 1.0f - d;  // the reversed projection: near at 1, far at 0 (exact for these linear maps)
  const float split = p.firstPersonDepthRange;  // the layer's slice of the depth range
  if (split > 0.0f) {
    const float begin = p.reversedZ ? (weapon ? 1.0f - split : 0.0f) : (weapon ? 0.0f : split);
    const float end = p.reversedZ ? (weapon ? 1.0f : 1.0f - split) : (weapon ? split : 1.0f);
    d = begin + d * (end - begin);
  }
  return d;
}

struct DepthUpload {
  std::vector<std::byte> bytes;
  DepthImage expectedLinear;
};

// The device depth stored as `format` stores it, and the linear depth the pass must see for it.
DepthUpload hardwareDepth(const DepthImage& linear, VkFormat format, const stereo::HostFrame& frame) {
  const gpu::LinearDepthParams params =
      stereo::linearDepthParams(frame.projection, frame.weaponDepthOffset, frame.weaponDepthScale);
  DepthUpload upload{{}, DepthImage(linear.width, linear.height)};
  for (std::size_t i = 0; i < linear.pixels.size(); ++i) {
    const float d =
        appendDepthTexel(upload.bytes, format, std::clamp(deviceDepth(frame.projection, linear.pixels[i]), 0.0f, 1.0f));
    upload.expectedLinear.pixels[i] = gpu::stereoDepthFromDevice(params, d);
  }
  return upload;
}

std::vector<std::byte> colorBytes(const ImageRGBA8& center, VkFormat format) {
  std::vector<std::byte> bytes(center.pixels.size());
  std::memcpy(bytes.data(), center.pixels.data(), bytes.size());
  if (format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB)
    for (std::size_t i = 0; i < bytes.size(); i += 4) std::swap(bytes[i], bytes[i + 2]);
  return bytes;
}

ImageRGBA8 toImage(const std::vector<std::byte>& bytes, std::uint32_t width, std::uint32_t height) {
  ImageRGBA8 image(width, height);
  std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
  return image;
}

class HostStereoPassTest : public HostContextTest {
 public:
  void SetUp() override {
    HostContextTest::SetUp();
    view_ = makeBlockView(kWidth, kHeight, 11, 0.6f, 7, 5, false);
    parameters_.maxSeparation = 0.06f;
    parameters_.zeroParallaxDistance = 3.0f;
    frame_.stereo = stereo::makeStereoConstants(parameters_, kWidth, kHeight);
    frame_.projection.nearPlane = 0.5f;
    frame_.projection.farPlane = 100.0f;
  }
  bool supports(VkFormat format, VkFormatFeatureFlags features) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(host().physicalDevice, format, &properties);
    return (properties.optimalTilingFeatures & features) == features;
  }
  vk::Image uploaded(VkFormat format, const std::vector<std::byte>& bytes, const vk::ImageState& state,
                     VkImageUsageFlags extraUsage = 0) {
    vk::Image image = vk::createImage(*context_, format, kWidth, kHeight,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | extraUsage);
    vk::uploadImage(*context_, image, bytes, state);
    return image;
  }
  vk::Image output(VkFormat format, std::uint32_t width, std::uint32_t height) {
    vk::Image image = vk::createImage(*context_, format, width, height,
                                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    context_->submitAndWait([&](VkCommandBuffer cmd) { vk::transition(cmd, image, vk::kUndefined, kCopiedOut); });
    return image;
  }
  // Runs the pass once in a command buffer of the host's pool, submitted on the host's queue.
  void runOnHostQueue(const std::function<void(VkCommandBuffer)>& record) { test::runOnHostQueue(host(), record); }

  // The view's depth as `depthFormat` stores it (hardware depth of frame_'s projection, or R32F linear), and the
  // linear depth the pass must see for it.
  DepthUpload depthUpload(VkFormat depthFormat) const {
    if (depthFormat != VK_FORMAT_R32_SFLOAT) return hardwareDepth(view_.depth, depthFormat, frame_);
    DepthUpload depth{{}, view_.depth};
    depth.bytes.resize(view_.depth.pixels.size() * 4);
    std::memcpy(depth.bytes.data(), view_.depth.pixels.data(), depth.bytes.size());
    return depth;
  }

  // Both eyes of the pass for the given colour and depth formats (8-bit eyes).
  stereo::StereoPair eyes(VkFormat colorFormat, VkFormat depthFormat, DepthImage* expectedLinear,
                          stereo::HostInputRead inputRead = stereo::HostInputRead::Auto) {
    const stereo::HostStereoPass pass(*context_,
                                      {kWidth, kHeight, colorFormat, depthFormat, HostOutput::TwoEyes, false, inputRead});
    return eyesOf(pass, expectedLinear);
  }
  // Both eyes of frame_ recorded by an existing pass (to two eyes), from view_ in the pass's formats.
  stereo::StereoPair eyesOf(const stereo::HostStereoPass& pass, DepthImage* expectedLinear) {
    const VkFormat colorFormat = pass.desc().colorFormat, depthFormat = pass.desc().depthFormat;
    DepthUpload depth = depthUpload(depthFormat);
    if (editDepth_) editDepth_(depth);
    *expectedLinear = depth.expectedLinear;
    const bool hardware = depthFormat != VK_FORMAT_R32_SFLOAT;
    vk::Image color = uploaded(colorFormat, colorBytes(view_.color, colorFormat), kShaderRead);
    vk::Image depthImage = uploaded(depthFormat, depth.bytes, hardware ? kDepthWritten : kShaderRead,
                                    hardware ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : 0);
    vk::Image left = output(pass.eyeFormat(), kWidth, kHeight), right = output(pass.eyeFormat(), kWidth, kHeight);
    const HostImage leftHost = hostImage(left, kCopiedOut), rightHost = hostImage(right, kCopiedOut);
    runOnHostQueue([&](VkCommandBuffer cmd) {
      pass.record(cmd, hostImage(color, kShaderRead), hostImage(depthImage, hardware ? kDepthWritten : kShaderRead),
                  frame_, &leftHost, &rightHost, nullptr);
    });
    return {toImage(vk::readbackImage(*context_, left, kCopiedOut), kWidth, kHeight),
            toImage(vk::readbackImage(*context_, right, kCopiedOut), kWidth, kHeight)};
  }

  // Both ways of reading the host's images: the gather sampling them, and the conversion pass first.
  void expectReferenceEyes(VkFormat colorFormat, VkFormat depthFormat) {
    for (stereo::HostInputRead read : {stereo::HostInputRead::Direct, stereo::HostInputRead::Convert}) {
      DepthImage expectedLinear;
      const stereo::StereoPair gpu = eyes(colorFormat, depthFormat, &expectedLinear, read);
      const stereo::StereoPair cpu = stereo::synthesizeStereoReference(view_.color, expectedLinear, frame_.stereo);
      // 1 level: the reference's rounding (test_stereo_pass); D16/D24 quantization is in the data both sides see.
      EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << (read == stereo::HostInputRead::Direct ? "direct" : "converted");
      EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << (read == stereo::HostInputRead::Direct ? "direct" : "converted");
    }
  }

  friend void expectHdrEyes(HostStereoPassTest&, VkFormat);
  friend void expectFramesInFlight(HostStereoPassTest&, int, bool);
  SyntheticView view_;
  std::function<void(DepthUpload&)> editDepth_;  // a test's own texels in the uploaded depth, after hardwareDepth
  stereo::StereoParameters parameters_;
  stereo::HostFrame frame_;
};
}  // namespace
}  // namespace s3d::test
