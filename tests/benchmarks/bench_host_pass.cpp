// GPU time (Vulkan timestamps) of the host pass (stereo::HostStereoPass) and the host's stereo frame
// (stereo::StereoFrame, every method) against the bare kernel of the same method on the same synthetic 1920x1080
// view, in one run and one harness: what the input conversion and the output packing cost a host; and the HUD pass
// (hud::HudPass) on its own and inside the host pass. Each timed submission records the work kRecordsPerTiming
// times, so the GPU stays busy (a GPU that idles between short submissions lowers its clocks).
// Device: S3D_BENCH_DEVICE (default auto).
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <random>

#include <glm/gtc/packing.hpp>

#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/host_comfort_frame.h"
#include "s3d/hud/hud_pass.h"
#include "s3d/stereo/forward_pass.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/stereo/previous_fill_pass.h"
#include "s3d/stereo/reprojection.h"
#include "s3d/stereo/stereo_frame.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/stereo/synthesis.h"
#include "s3d/vk/timestamps.h"
#include "array_image.h"
#include "bench_context.h"
#include "depth_texels.h"

namespace {

using namespace s3d;

constexpr std::uint32_t kWidth = 1920, kHeight = 1080;

using bench::benchContext;

// Random colour over depth in 16x8 blocks between 1 and 50 m, a quarter sky; as colour bytes and as D32 device depth.
struct View {
  std::vector<std::uint8_t> color = std::vector<std::uint8_t>(std::size_t(kWidth) * kHeight * 4);
  std::vector<float> linear = std::vector<float>(std::size_t(kWidth) * kHeight);
  std::vector<float> device = std::vector<float>(std::size_t(kWidth) * kHeight);
  View() {
    std::mt19937 random(5);
    for (auto& c : color) c = std::uint8_t(random() & 255u);
    std::uniform_real_distribution<float> depth(1.0f, 50.0f);
    for (std::uint32_t by = 0; by < kHeight; by += 8)
      for (std::uint32_t bx = 0; bx < kWidth; bx += 16) {
        const float z = random() % 4 == 0 ? INFINITY : depth(random);
        for (std::uint32_t y = by; y < by + 8 && y < kHeight; ++y)
          for (std::uint32_t x = bx; x < bx + 16 && x < kWidth; ++x) {
            linear[std::size_t(y) * kWidth + x] = z;
            device[std::size_t(y) * kWidth + x] = std::isinf(z) ? 1.0f : 1000.0f / 999.9f - 100.0f / (999.9f * z);
          }
      }
  }
};

const View& view() {
  static const View v;
  return v;
}

stereo::HostFrame frame() {
  stereo::HostFrame f;
  f.stereo = stereo::makeStereoConstants(stereo::StereoParameters{}, kWidth, kHeight);
  f.projection.nearPlane = 0.1f;
  f.projection.farPlane = 1000.0f;
  return f;
}

constexpr int kRecordsPerTiming = 32;
// A GPU's clocks fall while it idles (the H200 to 345 MHz) and take about a second of load to come back.
constexpr std::chrono::milliseconds kWarmUp{1000};

// Every earlier command's writes before every later command: for steps that mix copies and compute.
void fullBarrier(VkCommandBuffer cmd) {
  constexpr VkAccessFlags2 memory = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, memory, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, memory);
}

template <typename Record>
void timeRecording(benchmark::State& state, const Record& record) {
  vk::Context& context = benchContext();
  const auto warmUpEnd = std::chrono::steady_clock::now() + kWarmUp;
  do {
    context.submitAndWait([&](VkCommandBuffer cmd) {
      for (int i = 0; i < kRecordsPerTiming; ++i) {
        if (i > 0) vk::computeStorageBarrier(cmd);  // the previous recording's writes before this one's
        record(cmd);
      }
    });
  } while (std::chrono::steady_clock::now() < warmUpEnd);
  vk::TimestampQueries timestamps(context, 2);
  for (auto _ : state) {
    context.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      for (int i = 0; i < kRecordsPerTiming; ++i) {
        if (i > 0) vk::computeStorageBarrier(cmd);  // the previous recording's writes before this one's
        record(cmd);
      }
      timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    });
    state.SetIterationTime(timestamps.elapsedMs(0, 1).value_or(0.0) * 1e-3 / kRecordsPerTiming);
  }
  state.SetLabel(context.deviceName());
}

const stereo::StereoMethod kMethods[] = {stereo::StereoMethod::Seed, stereo::StereoMethod::Search,
                                         stereo::StereoMethod::Iterative, stereo::StereoMethod::Forward};

// The harness's center camera: a perspective projection (reversed Z) that does not move from frame to frame.
glm::mat4 centerProjection() {
  glm::mat4 projection(0.0f);
  projection[0][0] = 1.0f;
  projection[1][1] = 1.7f;
  projection[2][3] = -1.0f;
  projection[3][2] = 0.1f;
  return projection;
}

// The forward kernel and the previous-frame fill, each recording a new frame of a camera that does not move (the
// fill's full work, as HostStereoFrame's).
void recordForwardWithFill(VkCommandBuffer cmd, const stereo::ForwardStereoPass& forward, stereo::PreviousFillPass& fill,
                           const vk::Image& color, const vk::Image& depth, const vk::Image& left, const vk::Image& right) {
  stereo::StereoParameters parameters;
  parameters.method = stereo::StereoMethod::Forward;
  const gpu::ForwardConstants constants = stereo::makeForwardConstants(parameters, kWidth, kHeight);
  forward.record(cmd, color, depth, left, right, constants);
  std::array<gpu::EyeMotion, 2> motion{};
  for (std::size_t e = 0; e < 2; ++e)
    motion[e] = stereo::staticEyeMotion(stereo::offAxisEyeCamera(glm::mat4(1.0f), centerProjection(),
                                                                  e == 0 ? stereo::Eye::Left : stereo::Eye::Right,
                                                                  parameters.maxSeparation, parameters.zeroParallaxDistance)
                                            .projection);
  fill.record(cmd, forward, left, right, constants, motion);
  fill.advance();
}

// The bare kernel of each method (argument: 0 seed, 1 search-4, 2 iterative-6, 3 forward, 4 forward with the
// previous-frame fill) on RGBA8 + R32F storage images, as the renderer hands them over.
void BareKernel(benchmark::State& state) {
  vk::Context& context = benchContext();
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image color = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, usage);
  vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, kWidth, kHeight, usage);
  vk::Image left = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, usage);
  vk::Image right = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, usage);
  vk::uploadImage(context, color, std::as_bytes(std::span(view().color)), vk::kComputeRead);
  vk::uploadImage(context, depth, std::as_bytes(std::span(view().linear)), vk::kComputeRead);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, left, vk::kUndefined, vk::kComputeWrite);
    vk::transition(cmd, right, vk::kUndefined, vk::kComputeWrite);
  });
  if (state.range(0) == 4) {
    const stereo::ForwardStereoPass forward(context, stereo::StereoKernel::Auto, stereo::ForwardKeys::Kept);
    stereo::PreviousFillPass fill(context);
    timeRecording(state, [&](VkCommandBuffer cmd) { recordForwardWithFill(cmd, forward, fill, color, depth, left, right); });
    state.SetLabel(context.deviceName() + ", forward + fill");
    return;
  }
  stereo::StereoParameters parameters;
  parameters.method = kMethods[state.range(0)];
  const stereo::DisplacementPass pass(context, parameters, kWidth, kHeight);
  timeRecording(state, [&](VkCommandBuffer cmd) { pass.record(cmd, color, depth, left, right); });
  state.SetLabel(context.deviceName() + ", " + stereo::methodName(parameters.method));
}

// An image the host synchronizes itself (stage NONE): the time is s3d's own work and barriers.
stereo::HostImage hostSynchronized(const vk::Image& image, VkImageLayout layout) {
  return stereo::HostImage{image.image, image.view, image.format, layout, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                           image.layer};
}

// A host's images for a stereo frame of `desc`: colour and depth uploaded from the synthetic view and sampled,
// the eyes and the packed target storage images in GENERAL, and the dispatch naming them with a perspective center
// camera that does not move (the fill's full work; the hybrid's eye cameras).
struct HostFrameImages {
  vk::Image color, depth, left, right, target;
  stereo::StereoFrameDispatch dispatch;

  // colorTexels, depthTexels: the view as stored in the description's formats (empty: RGBA8 colour, and D32 or R32F
  // depth).
  HostFrameImages(vk::Context& context, const stereo::StereoFrameDesc& desc, const stereo::StereoFrame& stereoFrame,
                  std::span<const std::byte> colorTexels = {}, std::span<const std::byte> depthTexels = {}) {
    const VkImageUsageFlags inputUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    color = vk::createImage(context, desc.colorFormat, kWidth, kHeight, inputUsage);
    depth = vk::createImage(context, desc.depthFormat, kWidth, kHeight, inputUsage);
    const bool linearDepth = desc.depthFormat == VK_FORMAT_R32_SFLOAT;  // the host's own linear depth, else D32
    if (colorTexels.empty()) colorTexels = std::as_bytes(std::span(view().color));
    if (depthTexels.empty()) depthTexels = std::as_bytes(std::span(linearDepth ? view().linear : view().device));
    vk::uploadImage(context, color, colorTexels, vk::kFragmentRead);
    vk::uploadImage(context, depth, depthTexels, vk::kFragmentRead);
    left = vk::createImage(context, stereoFrame.eyeFormat(), kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
    right = vk::createImage(context, stereoFrame.eyeFormat(), kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
    target = vk::createImage(context, stereoFrame.eyeFormat(), stereoFrame.packedWidth(), stereoFrame.packedHeight(),
                             VK_IMAGE_USAGE_STORAGE_BIT);
    context.submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* image : {&left, &right, &target}) vk::transition(cmd, *image, vk::kUndefined, vk::kComputeWrite);
    });
    dispatch.color = hostSynchronized(color, vk::kFragmentRead.layout);
    dispatch.depth = hostSynchronized(depth, vk::kFragmentRead.layout);
    dispatch.left = hostSynchronized(left, VK_IMAGE_LAYOUT_GENERAL);
    dispatch.right = hostSynchronized(right, VK_IMAGE_LAYOUT_GENERAL);
    dispatch.target = hostSynchronized(target, VK_IMAGE_LAYOUT_GENERAL);
    dispatch.projection = frame().projection;
    dispatch.centerProjection = centerProjection();
  }
};

// The host's stereo frame from colour and depth the host synchronizes itself. Arguments: the method as
// BareKernel's (4: forward with the previous-frame fill), the output (kFrameOutputs: 0 two eyes, 1 anaglyph, 2
// side-by-side half, 3 top-bottom half, 4 side-by-side full) and the colour's
// view (0 sRGB: the sampler decodes, the gather encodes again; 1 UNORM, as a host's UNORM view of an sRGB image
// made with VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT reads: the display values as stored) and the depth (0 D32, 1 the
// host's linear depth in R32F: no conversion per tap) and whether the host's projection gives a first-person layer
// its own depth range (0: no; 1: yes, with no weapon in the view; 2: yes, with a weapon over 9 % of the view, where
// the gather converts each tap).
const stereo::HostOutput kFrameOutputs[] = {stereo::HostOutput::TwoEyes, stereo::HostOutput::Anaglyph,
                                            stereo::HostOutput::SideBySideHalf, stereo::HostOutput::TopBottomHalf,
                                            stereo::HostOutput::SideBySideFull};

// The synthetic view's D32 depth with a weapon in the first-person range [0, 0.1]: the lower right 480x400 pixels
// (9 % of the view), in 16x8 blocks between 0.02 and 0.09.
std::vector<std::byte> weaponDepthTexels() {
  std::vector<std::byte> texels;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> weapon(0.02f, 0.09f);
  const std::size_t blocksPerRow = kWidth / 16 + 1;
  std::vector<float> blocks(blocksPerRow * (kHeight / 8 + 1));
  for (float& b : blocks) b = weapon(random);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const bool inWeapon = x >= kWidth - 480 && y >= kHeight - 400;
      test::appendBytes(texels, inWeapon ? blocks[std::size_t(y / 8) * blocksPerRow + x / 16]
                                         : view().device[std::size_t(y) * kWidth + x]);
    }
  return texels;
}

void HostStereoFrame(benchmark::State& state) {
  vk::Context& context = benchContext();
  const bool fill = state.range(0) == 4;
  stereo::StereoFrameDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.colorFormat = state.range(2) == 0 ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  desc.depthFormat = state.range(3) == 0 ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_R32_SFLOAT;
  desc.method = kMethods[fill ? 3 : state.range(0)];
  desc.previousFrameFill = fill;
  desc.output = kFrameOutputs[state.range(1)];
  stereo::StereoFrame stereoFrame(context, desc);
  const std::vector<std::byte> depth = state.range(4) == 2 ? weaponDepthTexels() : std::vector<std::byte>{};
  HostFrameImages images(context, desc, stereoFrame, {}, depth);
  if (state.range(4) != 0) {  // the world's device depths stay in the world's range [0.1, 1]
    images.dispatch.projection.firstPersonDepthRange = 0.1f;
    images.dispatch.projection.firstPersonNear = 0.05f;
    images.dispatch.projection.firstPersonFar = 5.0f;
  }
  timeRecording(state, [&](VkCommandBuffer cmd) { stereoFrame.record(cmd, images.dispatch); });
  state.SetLabel(context.deviceName() + ", " + stereo::methodName(desc.method) + (fill ? " + fill" : "") +
                 (state.range(2) == 0 ? ", sRGB" : ", UNORM view") + (state.range(3) == 0 ? ", D32" : ", R32F") +
                 (state.range(4) == 1   ? ", first-person layer"
                  : state.range(4) == 2 ? ", first-person layer with a weapon"
                                        : ""));
}

// The colour formats and depth formats a host may hand over (HostStereoFrameFormats's arguments).
const VkFormat kColorFormats[] = {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_B10G11R11_UFLOAT_PACK32};
const VkFormat kDepthFormats[] = {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM,
                                  VK_FORMAT_R32_SFLOAT};

using test::appendBytes;

// The synthetic view's colour stored as `format` (the HDR formats hold the bytes over 255 as linear values).
std::vector<std::byte> colorTexels(VkFormat format) {
  const std::vector<std::uint8_t>& bytes = view().color;
  std::vector<std::byte> texels;
  for (std::size_t i = 0; i < bytes.size(); i += 4) {
    const glm::vec4 c = glm::vec4(bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]) / 255.0f;
    if (format == VK_FORMAT_R16G16B16A16_SFLOAT) appendBytes(texels, glm::packHalf4x16(c));
    else if (format == VK_FORMAT_B10G11R11_UFLOAT_PACK32) appendBytes(texels, glm::packF2x11_1x10(glm::vec3(c)));
    else appendBytes(texels, glm::packUnorm4x8(c));
  }
  return texels;
}

// The synthetic view's depth stored as `format`: its device depth in D32, D24S8 (24 bits, stencil 0) or D16, or
// its linear depth in R32F.
std::vector<std::byte> depthTexels(VkFormat format) {
  std::vector<std::byte> texels;
  for (std::size_t i = 0; i < view().device.size(); ++i) {
    if (format == VK_FORMAT_R32_SFLOAT) appendBytes(texels, view().linear[i]);
    else test::appendDepthTexel(texels, format, view().device[i]);
  }
  return texels;
}

// The host's stereo frame to two eyes from every input format, the eyes as two images or as the two layers of one
// array image (what an OpenXR swapchain or a multiview host hands over). Arguments: the method (0 seed, 1
// search-4), the colour (kColorFormats: 0 sRGB, 1 RGBA16F, 2 B10G11R11), the depth (kDepthFormats: 0 D32, 1
// D24S8, 2 D16, 3 R32F linear depth) and the eyes (0 two images, 1 one 2-layer array).
void HostStereoFrameFormats(benchmark::State& state) {
  vk::Context& context = benchContext();
  stereo::StereoFrameDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.method = kMethods[state.range(0)];
  desc.colorFormat = kColorFormats[state.range(1)];
  desc.depthFormat = kDepthFormats[state.range(2)];
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), desc.depthFormat, &properties);
  if ((properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) == 0) {
    state.SkipWithError("the device cannot sample this depth format");
    return;
  }
  stereo::StereoFrame stereoFrame(context, desc);
  HostFrameImages images(context, desc, stereoFrame, colorTexels(desc.colorFormat), depthTexels(desc.depthFormat));
  std::optional<test::ArrayImage> array;
  if (state.range(3) != 0) {
    array = test::createArrayImage(context, stereoFrame.eyeFormat(), kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
    for (std::uint32_t layer = 0; layer < 2; ++layer) {
      const vk::Image eye = array->layer(layer);
      context.submitAndWait([&](VkCommandBuffer cmd) { vk::transition(cmd, eye, vk::kUndefined, vk::kComputeWrite); });
      (layer == 0 ? images.dispatch.left : images.dispatch.right) = hostSynchronized(eye, VK_IMAGE_LAYOUT_GENERAL);
    }
  }
  timeRecording(state, [&](VkCommandBuffer cmd) { stereoFrame.record(cmd, images.dispatch); });
  static const char* const colorNames[] = {"sRGB", "RGBA16F", "B10G11R11"};
  static const char* const depthNames[] = {"D32", "D24S8", "D16", "R32F"};
  state.SetLabel(context.deviceName() + ", " + stereo::methodName(desc.method) + ", " + colorNames[state.range(1)] +
                 ", " + depthNames[state.range(2)] + (state.range(3) != 0 ? ", 2-layer array" : ", two images"));
}

// The host's stereo frame with its comfort rules (comfort::HostComfortFrame): the frame's depth reduction, then
// the search-4 stereo frame to two eyes, from sRGB colour and D32 depth, the disparity budget on for a 55" TV.
// Each recording of a submission has its own frame slot, so every slot's reduction has completed when update()
// reads it (the host's contract); update() is CPU work, outside the GPU time.
void HostComfortFrame(benchmark::State& state) {
  vk::Context& context = benchContext();
  comfort::HostComfortFrameDesc desc;
  desc.stereo.width = kWidth;
  desc.stereo.height = kHeight;
  desc.stereo.colorFormat = VK_FORMAT_R8G8B8A8_SRGB;
  desc.stereo.depthFormat = VK_FORMAT_D32_SFLOAT;
  desc.budget = comfort::disparityBudget(comfort::builtInDisplayProfile("tv55"));
  desc.framesInFlight = kRecordsPerTiming + 1;
  comfort::HostComfortFrame comfortFrame(context, desc);
  const HostFrameImages images(context, desc.stereo, comfortFrame.stereoFrame());
  std::uint32_t frame = 0;
  timeRecording(state, [&](VkCommandBuffer cmd) {
    comfort::HostComfortInput input;
    input.frameSlot = frame++ % desc.framesInFlight;
    input.parameters.maxSeparation = 0.02f;
    input.parameters.zeroParallaxDistance = 1.0f;
    comfortFrame.update(input);
    comfortFrame.record(cmd, images.dispatch);
  });
  state.SetLabel(context.deviceName() + ", search-4, budget on");
}

// The hybrid's first step for a host (StereoFrame::recordHybridMasks): the search into the eyes, the
// classification, threshold and masks, and both masks copied into the host's D32 depth images; from sRGB colour
// and D32 depth. Argument: the budget in percent. The synthetic view's 16x8 blocks of random depth put an edge
// every few pixels, far more than a rendered frame has: an upper bound of the classification's cost.
void HostHybridMasks(benchmark::State& state) {
  vk::Context& context = benchContext();
  stereo::StereoFrameDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.colorFormat = VK_FORMAT_R8G8B8A8_SRGB;
  desc.depthFormat = VK_FORMAT_D32_SFLOAT;
  desc.method = stereo::StereoMethod::Hybrid;
  desc.hybridBudget = float(state.range(0)) / 100.0f;
  stereo::StereoFrame stereoFrame(context, desc);
  HostFrameImages images(context, desc, stereoFrame);
  const VkImageUsageFlags maskUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image leftMask = vk::createImage(context, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, maskUsage);
  vk::Image rightMask = vk::createImage(context, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, maskUsage);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* image : {&leftMask, &rightMask})
      vk::transition(cmd, *image, vk::kUndefined, {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                   VK_ACCESS_2_TRANSFER_WRITE_BIT});
  });
  stereo::StereoFrameDispatch& dispatch = images.dispatch;
  dispatch.leftMask = hostSynchronized(leftMask, VK_IMAGE_LAYOUT_GENERAL);
  dispatch.rightMask = hostSynchronized(rightMask, VK_IMAGE_LAYOUT_GENERAL);
  timeRecording(state, [&](VkCommandBuffer cmd) {
    fullBarrier(cmd);  // the previous recording's mask copies before this one's buffer writes
    (void)stereoFrame.recordHybridMasks(cmd, dispatch);
  });
  state.SetLabel(context.deviceName() + ", hybrid budget " + std::to_string(state.range(0)) + " %");
}

// s3d's built-in HUD (health and ammo panels, crosshair) at 1920x1080, with parallax and the fade on.
hud::HudPassDesc builtInHud(std::size_t extraHostLayerSide) {
  hud::HudPassDesc desc{kWidth, kHeight, {}};
  for (const hud::HudLayer& layer : hud::builtInHudLayers(kWidth, kHeight))
    desc.elements.push_back(hud::HudPassElement::uploaded(layer));
  if (extraHostLayerSide > 0)
    desc.elements.push_back(hud::HudPassElement::hostLayer("minimap", std::uint32_t(extraHostLayerSide),
                                                           std::uint32_t(extraHostLayerSide), {64.0f, 64.0f, 0, 0}));
  return desc;
}
std::vector<hud::HudElementFrame> hudFrames(std::size_t count) {
  std::vector<hud::HudElementFrame> frames(count, hud::HudElementFrame{6.4f, true, false});
  return frames;
}

const stereo::HostInputRead kInputReads[] = {stereo::HostInputRead::Auto, stereo::HostInputRead::Direct,
                                             stereo::HostInputRead::Convert};

// Argument: 0 sRGB colour + D32 depth -> two eyes; 1 RGBA8 + R32F storage inputs (no conversion) -> two eyes;
// 2 sRGB + D32 -> anaglyph; 3 sRGB + D32 -> side-by-side half; 4 RGBA16F + D32 -> two half-float eyes;
// 5 sRGB + D32 -> anaglyph with the built-in HUD drawn into the eyes before packing (hud::HudOverlay). Second
// argument, how the host's images are read (kInputReads: 0 Auto, 1 Direct, 2 Convert), so a device's run shows
// which read Auto should pick there.
void HostPass(benchmark::State& state) {
  vk::Context& context = benchContext();
  const int variant = int(state.range(0));
  const bool storage = variant == 1, hdr = variant == 4;
  const VkFormat colorFormat = storage ? VK_FORMAT_R8G8B8A8_UNORM : hdr ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R8G8B8A8_SRGB;
  const VkFormat depthFormat = storage ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_D32_SFLOAT;
  const stereo::HostOutput output = variant == 2 || variant == 5 ? stereo::HostOutput::Anaglyph
                                    : variant == 3 ? stereo::HostOutput::SideBySideHalf
                                                   : stereo::HostOutput::TwoEyes;
  const VkImageUsageFlags inputUsage =
      (storage ? VK_IMAGE_USAGE_STORAGE_BIT : VK_IMAGE_USAGE_SAMPLED_BIT) | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  const vk::ImageState readable = storage ? vk::kComputeRead : vk::kFragmentRead;
  vk::Image color = vk::createImage(context, colorFormat, kWidth, kHeight, inputUsage);
  vk::Image depth = vk::createImage(context, depthFormat, kWidth, kHeight, inputUsage);
  if (hdr) {
    std::vector<std::uint16_t> half(view().color.size(), 0x3c00);  // 1.0: the cost does not depend on the values
    vk::uploadImage(context, color, std::as_bytes(std::span(half)), readable);
  } else {
    vk::uploadImage(context, color, std::as_bytes(std::span(view().color)), readable);
  }
  vk::uploadImage(context, depth, std::as_bytes(std::span(storage ? view().linear : view().device)), readable);
  const stereo::HostStereoPass pass(context, {kWidth, kHeight, colorFormat, depthFormat, output, storage,
                                              kInputReads[state.range(1)]});
  const VkImageUsageFlags outputUsage = VK_IMAGE_USAGE_STORAGE_BIT;
  vk::Image left = vk::createImage(context, pass.eyeFormat(), kWidth, kHeight, outputUsage);
  vk::Image right = vk::createImage(context, pass.eyeFormat(), kWidth, kHeight, outputUsage);
  vk::Image target = vk::createImage(context, pass.eyeFormat(), pass.packedWidth(), pass.packedHeight(), outputUsage);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* image : {&left, &right, &target}) vk::transition(cmd, *image, vk::kUndefined, vk::kComputeWrite);
  });
  // The host synchronizes its images itself (stage NONE): the time is the pass's own work and barriers.
  const stereo::HostImage l = hostSynchronized(left, VK_IMAGE_LAYOUT_GENERAL),
                          r = hostSynchronized(right, VK_IMAGE_LAYOUT_GENERAL),
                          t = hostSynchronized(target, VK_IMAGE_LAYOUT_GENERAL);
  const stereo::HostFrame f = frame();
  const bool eyes = output == stereo::HostOutput::TwoEyes;
  std::optional<hud::HudPass> hudPass;
  if (variant == 5) hudPass.emplace(context, builtInHud(0));
  const std::vector<hud::HudElementFrame> hudFrame = hudFrames(hudPass ? hudPass->desc().elements.size() : 0);
  const std::optional<hud::HudOverlay> overlay =
      hudPass ? std::optional<hud::HudOverlay>(hudPass->overlay(hudFrame)) : std::nullopt;
  timeRecording(state, [&](VkCommandBuffer cmd) {
    pass.record(cmd, hostSynchronized(color, readable.layout), hostSynchronized(depth, readable.layout), f, eyes ? &l : nullptr,
                eyes ? &r : nullptr, eyes ? nullptr : &t, overlay ? &*overlay : nullptr);
  });
}

// The HUD pass alone on two 1920x1080 RGBA8 eyes the host synchronizes. Argument: 0 the built-in HUD; N > 0 the
// built-in HUD plus a host layer N x N pixels (the cost follows the layers' area, not the eyes').
void HudPass(benchmark::State& state) {
  vk::Context& context = benchContext();
  const std::size_t side = std::size_t(state.range(0));
  const hud::HudPass pass(context, builtInHud(side));
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image left = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, usage);
  vk::Image right = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, usage);
  vk::uploadImage(context, left, std::as_bytes(std::span(view().color)), vk::kComputeWrite);
  vk::uploadImage(context, right, std::as_bytes(std::span(view().color)), vk::kComputeWrite);
  std::optional<vk::Image> layer;
  std::vector<stereo::HostImage> hostLayers;
  if (side > 0) {
    layer = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, std::uint32_t(side), std::uint32_t(side),
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    std::vector<std::uint8_t> pixels(side * side * 4, 200);
    const vk::ImageState sampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
    vk::uploadImage(context, *layer, std::as_bytes(std::span(pixels)), sampled);
    hostLayers.push_back({layer->image, layer->view, layer->format, sampled.layout, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE});
  }
  const std::vector<hud::HudElementFrame> frames = hudFrames(pass.desc().elements.size());
  const stereo::HostImage l{left.image, left.view, left.format, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE,
                            VK_ACCESS_2_NONE};
  const stereo::HostImage r{right.image, right.view, right.format, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE,
                            VK_ACCESS_2_NONE};
  timeRecording(state, [&](VkCommandBuffer cmd) { pass.record(cmd, frames, hostLayers, l, r); });
}

BENCHMARK(BareKernel)->DenseRange(0, 4)->ArgName("method")->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.05);
BENCHMARK(HostStereoFrame)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}, {0}, {0}, {0}})
    ->ArgsProduct({{0, 1}, {2, 3, 4}, {0}, {0}, {0}})
    ->ArgsProduct({{0, 1}, {0, 1}, {1}, {0}, {0}})
    ->ArgsProduct({{0, 1}, {0, 1}, {0}, {1}, {0}})
    ->ArgsProduct({{0, 1}, {0, 1}, {0}, {0}, {1, 2}})
    ->ArgNames({"method", "output", "unormView", "linearDepth", "firstPersonLayer"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.05);
BENCHMARK(HostStereoFrameFormats)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1, 2, 3}, {0}})
    ->ArgsProduct({{0, 1}, {0}, {0}, {1}})
    ->ArgNames({"method", "color", "depth", "arrayEyes"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.05);
BENCHMARK(HostComfortFrame)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.05);
BENCHMARK(HostHybridMasks)->Arg(20)->Arg(60)->ArgName("budgetPercent")->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.05);
BENCHMARK(HostPass)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0}})
    ->ArgsProduct({{0, 2, 3}, {1, 2}})
    ->ArgNames({"variant", "read"})->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.05);
BENCHMARK(HudPass)->Arg(0)->Arg(256)->Arg(512)->ArgName("hostLayer")->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.05);

}  // namespace

BENCHMARK_MAIN();
