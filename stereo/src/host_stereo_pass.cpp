#include "s3d/stereo/host_stereo_pass.h"

#include <array>
#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "s3d/stereo/detail/host_barriers.h"
#include "s3d/vk/pipeline.h"

// clang-format off
#include <s3d_spirv/host_input_rgba8_comp.h>
#include <s3d_spirv/host_input_rgba16f_comp.h>
#include <s3d_spirv/host_pack_rgba8_comp.h>
#include <s3d_spirv/host_pack_rgba16f_comp.h>
#include <s3d_spirv/stereo_gather_host_comp.h>
#include <s3d_spirv/stereo_gather_host_half_comp.h>
#include <s3d_spirv/stereo_gather_host_hdr_comp.h>
#include <s3d_spirv/stereo_search_comp.h>
#include <s3d_spirv/stereo_search_hdr_comp.h>
#include <s3d_spirv/stereo_seed_comp.h>
#include <s3d_spirv/stereo_seed_hdr_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

constexpr std::uint32_t pushBytesFor(int tapCapacity) {
  return std::uint32_t(offsetof(gpu::StereoConstants, tapOffsetPx) + sizeof(int) * std::size_t(tapCapacity));
}
// The gather from the host's images: the stereo constants with the short tap array, then the input conversion's.
constexpr std::uint32_t kShortTapBytes = pushBytesFor(S3D_STEREO_SMALL_TAP_CAPACITY);
constexpr std::uint32_t kHostGatherBytes = kShortTapBytes + sizeof(gpu::HostInputConstants);
static_assert(kHostGatherBytes <= 128, "within the push constants every Vulkan device has");

bool isColorFormat(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8G8B8A8_UNORM: case VK_FORMAT_R8G8B8A8_SRGB: case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB: case VK_FORMAT_R16G16B16A16_SFLOAT: case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
      return true;
    default:
      return false;
  }
}
using detail::isHostDepthFormat;

gpu::vec2 layerRatio(float nearPlane, float farPlane, bool infinite, bool reversed, float begin, float end) {
  if (!infinite) return reversed ? gpu::reversedProjectionRatio(nearPlane, farPlane, begin, end)
                                 : gpu::projectionRatio(nearPlane, farPlane, begin, end);
  // The limits of Listing 4.2's ratio as far -> infinity: d = 1 - n/z (standard), d = n/z (reversed).
  const float x = reversed ? 0.0f : 1.0f, y = reversed ? nearPlane : -nearPlane;
  return {begin + x * (end - begin), y * (end - begin)};
}

detail::EyePairPipeline makePipeline(const vk::Context& context, std::span<const VkDescriptorSetLayoutBinding> bindings,
                                     std::span<const std::uint32_t> spirv, std::uint32_t pushBytes, int group,
                                     std::vector<std::uint32_t> specialization = {}) {
  detail::EyePairPipeline result;
  result.layout = vk::createPushDescriptorLayout(context, bindings, pushBytes, VK_SHADER_STAGE_COMPUTE_BIT);
  result.pipeline = vk::createComputePipeline(context, result.layout.layout, spirv,
                                              vk::SpecializationWords(std::move(specialization)));
  result.pushConstantBytes = pushBytes;
  result.groupWidth = group;
  result.groupHeight = group;
  return result;
}

VkDescriptorSetLayoutBinding binding(std::uint32_t index, VkDescriptorType type) {
  return {index, type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
}

// Colour, depth and two outputs at most.
using BarrierList = detail::HostBarriers<4>;

// The layout s3d uses an input in, and whether it needs a barrier from the host's state.
VkImageLayout inputLayout(const HostImage& image, bool storage, const char* what) {
  if (storage) {
    if (image.stage == VK_PIPELINE_STAGE_2_NONE && image.layout != VK_IMAGE_LAYOUT_GENERAL)
      throw std::invalid_argument(std::string("HostStereoPass: the ") + what +
                                  " image must be in VK_IMAGE_LAYOUT_GENERAL when the host synchronizes it itself");
    return VK_IMAGE_LAYOUT_GENERAL;
  }
  return detail::sampledReadLayout(image.layout, image.stage, std::string("HostStereoPass: the ") + what + " image");
}

// What the gather from host images writes for an output, or -1 where the packing pass must run: HDR packings
// mix without the 8-bit eyes' encoding. (An overlay, the HUD, draws on the eyes before they are packed, so a
// packed frame with one never gathers from the host's images.)
int gatherOutputFor(HostOutput output, bool hdr) {
  if (output == HostOutput::TwoEyes) return S3D_HOST_GATHER_TWO_EYES;
  switch (output) {
    case HostOutput::Anaglyph: return hdr ? -1 : S3D_HOST_GATHER_ANAGLYPH;
    case HostOutput::SideBySideHalf: return hdr ? -1 : S3D_HOST_GATHER_SIDE_BY_SIDE_HALF;
    case HostOutput::TopBottomHalf: return hdr ? -1 : S3D_HOST_GATHER_TOP_BOTTOM_HALF;
    case HostOutput::SideBySideFull: return S3D_HOST_GATHER_SIDE_BY_SIDE_FULL;
    case HostOutput::TopBottomFull: return S3D_HOST_GATHER_TOP_BOTTOM_FULL;
    default: return -1;
  }
}

void requireImage(const HostImage* image, const char* what) {
  if (!image || !image->image || !image->view)
    throw std::invalid_argument(std::string("HostStereoPass: the ") + what + " image is missing");
}

}  // namespace

gpu::LinearDepthParams linearDepthParams(const HostProjection& p, float weaponDepthOffset, float weaponDepthScale) {
  const float split = p.firstPersonDepthRange;
  if (!(split >= 0.0f && split < 1.0f))
    throw std::invalid_argument("HostProjection: firstPersonDepthRange must be in [0, 1)");
  if (!(p.nearPlane > 0.0f) || (!p.infiniteFarPlane && !(p.farPlane > p.nearPlane)))
    throw std::invalid_argument("HostProjection: needs 0 < near < far (or an infinite far plane)");
  gpu::LinearDepthParams params =
      p.reversedZ ? gpu::makeReversedLinearDepthParams(p.nearPlane, p.infiniteFarPlane ? 2 * p.nearPlane : p.farPlane,
                                                       p.firstPersonNear, p.firstPersonFar, split)
                  : gpu::makeLinearDepthParams(p.nearPlane, p.infiniteFarPlane ? 2 * p.nearPlane : p.farPlane,
                                               p.firstPersonNear, p.firstPersonFar, split);
  params.worldRatio = p.reversedZ ? layerRatio(p.nearPlane, p.farPlane, p.infiniteFarPlane, true, 0.0f, 1.0f - split)
                                  : layerRatio(p.nearPlane, p.farPlane, p.infiniteFarPlane, false, split, 1.0f);
  if (split == 0.0f) {  // no first-person layer: no depth belongs to it
    params.firstPersonDeviceDepthMax = -1.0f;
    // Never selected, but the shaders' mix() still reads it: unset planes (0, 0) would give NaN ratios there.
    params.firstPersonRatio = params.worldRatio;
  }
  params.firstPersonDepthOffset = weaponDepthOffset;
  params.firstPersonDepthScale = weaponDepthScale;
  return params;
}

HostStereoPass::HostStereoPass(vk::Context& context, const HostStereoPassDesc& desc) : context_(&context), desc_(desc) {
  if (desc.width == 0 || desc.height == 0) throw std::invalid_argument("HostStereoPass: zero image size");
  if (!isColorFormat(desc.colorFormat))
    throw std::invalid_argument("HostStereoPass: colour format " + std::to_string(int(desc.colorFormat)) +
                                " is not one of RGBA8/BGRA8 UNORM or SRGB, RGBA16F, B10G11R11");
  if (!isHostDepthFormat(desc.depthFormat) && desc.depthFormat != VK_FORMAT_R32_SFLOAT)
    throw std::invalid_argument("HostStereoPass: depth format " + std::to_string(int(desc.depthFormat)) +
                                " is not one of D32, D24S8, D16 or R32F linear depth");
  if (desc.inputsAreStorage && (desc.colorFormat != VK_FORMAT_R8G8B8A8_UNORM || desc.depthFormat != VK_FORMAT_R32_SFLOAT))
    throw std::invalid_argument("HostStereoPass: inputsAreStorage needs RGBA8 UNORM colour and R32F linear depth");
  const bool halfWidth = desc.output == HostOutput::SideBySideHalf, halfHeight = desc.output == HostOutput::TopBottomHalf;
  if ((halfWidth && desc.width < 2) || (halfHeight && desc.height < 2))
    throw std::invalid_argument("HostStereoPass: half packing needs eyes at least 2 pixels across");
  hdr_ = desc.colorFormat == VK_FORMAT_R16G16B16A16_SFLOAT || desc.colorFormat == VK_FORMAT_B10G11R11_UFLOAT_PACK32;
  if (desc.colorFormat == VK_FORMAT_R8G8B8A8_SRGB || desc.colorFormat == VK_FORMAT_B8G8R8A8_SRGB)
    colorTransfer_ = S3D_HOST_COLOR_ENCODE_SRGB;

  sampler_ = vk::createNearestClampSampler(context);

  const VkDescriptorSetLayoutBinding storage4[] = {
      binding(0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE), binding(1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
      binding(2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE), binding(3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)};
  if (convertsInputs()) {
    const VkDescriptorSetLayoutBinding bindings[] = {
        binding(0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER), binding(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
        binding(2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE), binding(3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)};
    input_ = makePipeline(context, bindings, hdr_ ? std::span<const std::uint32_t>(spirv_host_input_rgba16f_comp)
                                                  : std::span<const std::uint32_t>(spirv_host_input_rgba8_comp),
                          sizeof(gpu::HostInputConstants), S3D_HOST_GROUP_SIZE);
    const bool halfPacking = desc.output == HostOutput::SideBySideHalf || desc.output == HostOutput::TopBottomHalf;
    const bool mixedByGather = !hdr_ && (halfPacking || desc.output == HostOutput::Anaglyph);
    const bool direct = desc.inputRead == HostInputRead::Direct ||
                        (desc.inputRead == HostInputRead::Auto && (!context.isCpuDevice() || mixedByGather));
    using Spirv = std::span<const std::uint32_t>;
    const Spirv gather = hdr_          ? Spirv(spirv_stereo_gather_host_hdr_comp)
                         : halfPacking ? Spirv(spirv_stereo_gather_host_half_comp)
                                       : Spirv(spirv_stereo_gather_host_comp);
    // Specialization constants: how the depth reads (S3D_HOST_GATHER_DEPTH_*), where the gather writes and the
    // colour's transfer, so each pipeline compiles only its own paths (unused ones behind per-frame branches cost).
    const int gatherOutput = gatherOutputFor(desc.output, hdr_);
    const auto gatherFor = [&](std::uint32_t depthPath) {
      return makePipeline(context, bindings, gather, kHostGatherBytes, S3D_STEREO_GROUP_SIZE,
                          {depthPath, std::uint32_t(gatherOutput), std::uint32_t(colorTransfer_)});
    };
    if (direct && gatherOutput >= 0) {
      const bool linearDepth = desc.depthFormat == VK_FORMAT_R32_SFLOAT;
      hostGather_ = gatherFor(linearDepth ? S3D_HOST_GATHER_DEPTH_LINEAR : S3D_HOST_GATHER_DEPTH_ONE_LAYER);
      if (!linearDepth) hostGatherFirstPerson_ = gatherFor(S3D_HOST_GATHER_DEPTH_FIRST_PERSON);
    }
  }
  shortTaps_ = makePipeline(context, storage4, hdr_ ? std::span<const std::uint32_t>(spirv_stereo_seed_hdr_comp)
                                                    : std::span<const std::uint32_t>(spirv_stereo_seed_comp),
                            pushBytesFor(S3D_STEREO_SMALL_TAP_CAPACITY), S3D_STEREO_GROUP_SIZE);
  allTaps_ = makePipeline(context, storage4, hdr_ ? std::span<const std::uint32_t>(spirv_stereo_search_hdr_comp)
                                                  : std::span<const std::uint32_t>(spirv_stereo_search_comp),
                          pushBytesFor(S3D_STEREO_MAX_TAPS), S3D_STEREO_GROUP_SIZE);
  if (desc.output != HostOutput::TwoEyes)
    pack_ = makePipeline(context, std::span(storage4).first(3),
                         hdr_ ? std::span<const std::uint32_t>(spirv_host_pack_rgba16f_comp)
                              : std::span<const std::uint32_t>(spirv_host_pack_rgba8_comp),
                         sizeof(gpu::HostPackConstants), S3D_HOST_GROUP_SIZE);

  // Intermediates live in GENERAL from here on; each record() orders them after the previous frame's use.
  auto intermediate = [&](VkFormat format) {
    return vk::createImage(context, format, desc.width, desc.height, VK_IMAGE_USAGE_STORAGE_BIT);
  };
  if (convertsInputs()) {
    centerColor_ = intermediate(eyeFormat());
    linearDepth_ = intermediate(VK_FORMAT_R32_SFLOAT);
  }
  if (pack_) {
    leftEye_ = intermediate(eyeFormat());
    rightEye_ = intermediate(eyeFormat());
  }
  context.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* image : {&centerColor_, &linearDepth_, &leftEye_, &rightEye_})
      if (image->image) vk::transition(cmd, *image, vk::kUndefined, vk::kComputeWrite);
  });
}

std::uint32_t HostStereoPass::packedWidth() const {
  return desc_.output == HostOutput::SideBySideFull ? 2 * desc_.width : desc_.width;
}
std::uint32_t HostStereoPass::packedHeight() const {
  return desc_.output == HostOutput::TopBottomFull ? 2 * desc_.height : desc_.height;
}

struct HostStereoPass::Recording {
  VkCommandBuffer cmd;
  const HostImage& color;
  const HostImage& depth;
  const HostFrame& frame;
  const HostImage* left;
  const HostImage* right;
  const HostImage* target;
  std::array<const HostImage*, 2> outputArray{};
  std::span<const HostImage* const> outputs;  // the eyes, or the packed target
  VkImageLayout colorLayout, depthLayout;
  VkAccessFlags2 inputRead;
  gpu::HostInputConstants input{};
  bool gatherFromHost = false, packedByGather = false;
  VkImageView centerView, depthView;  // what the kernel reads: the host's images or the converted intermediates
  VkImageView leftView, rightView;    // what the kernel writes: the eyes, the packing's intermediates or the target
};

HostStereoPass::Recording HostStereoPass::begin(VkCommandBuffer cmd, const HostImage& color, const HostImage& depth,
                                                const HostFrame& frame, const HostImage* left, const HostImage* right,
                                                const HostImage* target, bool overlay, bool kernel) const {
  const gpu::StereoConstants& constants = frame.stereo;
  if (constants.tapCount < 0 || constants.tapCount > S3D_STEREO_MAX_TAPS)
    throw std::invalid_argument("HostStereoPass: tap count out of range (use makeStereoConstants)");
  if (constants.width != int(desc_.width) || constants.height != int(desc_.height))
    throw std::invalid_argument("HostStereoPass: the stereo constants are for another image size");
  requireImage(&color, "colour");
  requireImage(&depth, "depth");
  if (color.format != desc_.colorFormat || depth.format != desc_.depthFormat)
    throw std::invalid_argument("HostStereoPass: the colour or depth format differs from the one the pass was made for");
  Recording r{cmd, color, depth, frame, left, right, target};
  if (desc_.output == HostOutput::TwoEyes) {
    requireImage(left, "left eye");
    requireImage(right, "right eye");
    r.outputArray = {left, right};
    r.outputs = std::span(r.outputArray);
  } else {
    requireImage(target, "packed target");
    r.outputArray = {target, nullptr};
    r.outputs = std::span(r.outputArray).first(1);
  }
  for (const HostImage* output : r.outputs) {
    if (output->format != eyeFormat())
      throw std::invalid_argument(std::string("HostStereoPass: output images must be ") +
                                  (hdr_ ? "RGBA16F" : "RGBA8 UNORM") + " storage images for this input");
    if (output->stage == VK_PIPELINE_STAGE_2_NONE && output->layout != VK_IMAGE_LAYOUT_GENERAL)
      throw std::invalid_argument("HostStereoPass: an output the host synchronizes itself must be in GENERAL");
  }
  if (r.outputs.size() == 2 && left->image == right->image && left->layer == right->layer)
    throw std::invalid_argument("HostStereoPass: the eyes name the same image and layer");

  const bool storageInputs = desc_.inputsAreStorage;
  r.colorLayout = inputLayout(color, storageInputs, "colour");
  r.depthLayout = inputLayout(depth, storageInputs, "depth");
  r.inputRead = storageInputs ? VK_ACCESS_2_SHADER_STORAGE_READ_BIT : VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
  r.input.depth = linearDepthParams(frame.projection, frame.weaponDepthOffset, frame.weaponDepthScale);
  r.input.width = int(desc_.width);
  r.input.height = int(desc_.height);
  r.input.colorTransfer = colorTransfer_;
  r.input.depthKind = isHostDepthFormat(desc_.depthFormat) ? S3D_HOST_DEPTH_DEVICE : S3D_HOST_DEPTH_LINEAR;
  // Seed and short searches read the host's images themselves and pack straight into the target, each packed
  // pixel gathering the eye pixels it holds: one dispatch instead of a conversion, a kernel and a packing pass.
  r.gatherFromHost =
      hostGather_ && !kernel && !(overlay && pack_) && constants.tapCount <= S3D_STEREO_SMALL_TAP_CAPACITY;
  r.packedByGather = r.gatherFromHost && pack_;
  r.centerView = color.view;
  r.depthView = depth.view;
  r.leftView = r.packedByGather ? target->view : pack_ ? leftEye_.view.get() : left->view;
  r.rightView = r.packedByGather ? target->view : pack_ ? rightEye_.view.get() : right->view;

  constexpr VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  BarrierList before;
  before.memory = true;
  for (auto [image, layout] : {std::pair{&color, r.colorLayout}, std::pair{&depth, r.depthLayout}})
    if (image->stage != VK_PIPELINE_STAGE_2_NONE)
      before.image(image->image, image->format, image->layout, image->stage, image->access, layout, compute, r.inputRead);
  for (const HostImage* output : r.outputs)
    if (output->stage != VK_PIPELINE_STAGE_2_NONE)
      before.image(output->image, output->format, output->layout, output->stage, output->access, VK_IMAGE_LAYOUT_GENERAL,
                   compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, output->layer);
  before.record(cmd);
  return r;
}

// Back to the host's layouts, ordered before the stage and access it named.
void HostStereoPass::end(const Recording& r) const {
  constexpr VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  BarrierList after;
  for (auto [image, layout] : {std::pair{&r.color, r.colorLayout}, std::pair{&r.depth, r.depthLayout}})
    if (image->stage != VK_PIPELINE_STAGE_2_NONE)
      after.image(image->image, image->format, layout, compute, r.inputRead, image->layout, image->stage, image->access);
  for (const HostImage* output : r.outputs)
    if (output->stage != VK_PIPELINE_STAGE_2_NONE)
      after.image(output->image, output->format, VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  output->layout, output->stage, output->access, output->layer);
  after.record(r.cmd);
}

void HostStereoPass::dispatch(VkCommandBuffer cmd, const detail::EyePairPipeline& pass,
                              std::span<const VkWriteDescriptorSet> writes, const void* push, std::uint32_t width,
                              std::uint32_t height) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.pipeline);
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass.layout.layout, 0,
                                 std::uint32_t(writes.size()), writes.data());
  vkCmdPushConstants(cmd, pass.layout.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass.pushConstantBytes, push);
  vkCmdDispatch(cmd, (width + pass.groupWidth - 1) / pass.groupWidth, (height + pass.groupHeight - 1) / pass.groupHeight, 1);
}

namespace {

// The host's two inputs as the conversion and the gather from host images sample them, then two storage images.
struct SamplingWrites {
  VkDescriptorImageInfo infos[4];
  VkWriteDescriptorSet writes[4];

  SamplingWrites(VkSampler sampler, VkImageView color, VkImageLayout colorLayout, VkImageView depth,
                 VkImageLayout depthLayout, VkImageView out0, VkImageView out1) {
    infos[0] = {sampler, color, colorLayout};
    infos[1] = {sampler, depth, depthLayout};
    infos[2] = {VK_NULL_HANDLE, out0, VK_IMAGE_LAYOUT_GENERAL};
    infos[3] = {VK_NULL_HANDLE, out1, VK_IMAGE_LAYOUT_GENERAL};
    for (std::uint32_t i = 0; i < 4; ++i)
      writes[i] = i < 2 ? vk::sampledImageWrite(i, &infos[i]) : vk::storageImageWrite(i, &infos[i]);
    for (std::uint32_t i = 0; i < 2; ++i) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  SamplingWrites(const SamplingWrites&) = delete;  // the writes point into infos
};

// Compute -> compute for the pass's own images between its dispatches.
void recordBetween(VkCommandBuffer cmd) {
  BarrierList between;
  between.memory = true;
  between.record(cmd);
}

}  // namespace

void HostStereoPass::recordGatherFromHost(const Recording& r) const {
  std::array<std::byte, kHostGatherBytes> push{};
  std::memcpy(push.data(), &r.frame.stereo, kShortTapBytes);
  std::memcpy(push.data() + kShortTapBytes, &r.input, sizeof r.input);
  const SamplingWrites w(sampler_, r.color.view, r.colorLayout, r.depth.view, r.depthLayout, r.leftView, r.rightView);
  const bool firstPerson = hostGatherFirstPerson_ && !gpu::hasNoFirstPersonLayer(r.input.depth);
  dispatch(r.cmd, firstPerson ? *hostGatherFirstPerson_ : *hostGather_, w.writes, push.data(), desc_.width,
           desc_.height);
}

void HostStereoPass::recordConversion(Recording& r) const {
  const SamplingWrites w(sampler_, r.color.view, r.colorLayout, r.depth.view, r.depthLayout, centerColor_.view,
                         linearDepth_.view);
  dispatch(r.cmd, *input_, w.writes, &r.input, desc_.width, desc_.height);
  recordBetween(r.cmd);
  r.centerView = centerColor_.view;
  r.depthView = linearDepth_.view;
}

void HostStereoPass::recordStorageKernel(const Recording& r) const {
  const VkDescriptorImageInfo infos[4] = {{VK_NULL_HANDLE, r.centerView, VK_IMAGE_LAYOUT_GENERAL},
                                          {VK_NULL_HANDLE, r.depthView, VK_IMAGE_LAYOUT_GENERAL},
                                          {VK_NULL_HANDLE, r.leftView, VK_IMAGE_LAYOUT_GENERAL},
                                          {VK_NULL_HANDLE, r.rightView, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[4];
  for (std::uint32_t i = 0; i < 4; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  const gpu::StereoConstants& constants = r.frame.stereo;
  dispatch(r.cmd, constants.tapCount <= S3D_STEREO_SMALL_TAP_CAPACITY ? *shortTaps_ : *allTaps_, writes, &constants,
           desc_.width, desc_.height);
}

// On the finished eyes, before packing (the HUD).
void HostStereoPass::recordOverlay(const Recording& r, const EyeOverlay& overlay) const {
  recordBetween(r.cmd);
  auto eye = [&](const vk::Image& own, const HostImage* host) {
    return pack_ ? HostImage{own.image, own.view, eyeFormat(), VK_IMAGE_LAYOUT_GENERAL}
                 : HostImage{host->image, host->view, host->format, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE,
                             VK_ACCESS_2_NONE, host->layer};
  };
  overlay.recordOnEyes(r.cmd, eye(leftEye_, r.left), eye(rightEye_, r.right));
}

void HostStereoPass::recordPacking(const Recording& r) const {
  recordBetween(r.cmd);
  gpu::HostPackConstants push{};
  const HostOutput o = desc_.output;
  push.mode = o == HostOutput::SideBySideHalf   ? S3D_HOST_PACK_SIDE_BY_SIDE_HALF
              : o == HostOutput::SideBySideFull ? S3D_HOST_PACK_SIDE_BY_SIDE_FULL
              : o == HostOutput::TopBottomHalf  ? S3D_HOST_PACK_TOP_BOTTOM_HALF
              : o == HostOutput::TopBottomFull  ? S3D_HOST_PACK_TOP_BOTTOM_FULL
                                                : S3D_HOST_PACK_ANAGLYPH;
  push.eyeWidth = int(desc_.width);
  push.eyeHeight = int(desc_.height);
  push.eyesEncoded = hdr_ ? 0 : 1;
  const VkDescriptorImageInfo infos[3] = {{VK_NULL_HANDLE, leftEye_.view, VK_IMAGE_LAYOUT_GENERAL},
                                          {VK_NULL_HANDLE, rightEye_.view, VK_IMAGE_LAYOUT_GENERAL},
                                          {VK_NULL_HANDLE, r.target->view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[3];
  for (std::uint32_t i = 0; i < 3; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  dispatch(r.cmd, *pack_, writes, &push, packedWidth(), packedHeight());
}

void HostStereoPass::record(VkCommandBuffer cmd, const HostImage& color, const HostImage& depth, const HostFrame& frame,
                            const HostImage* left, const HostImage* right, const HostImage* target,
                            const EyeOverlay* overlay, const EyeKernel* kernel) const {
  Recording r = begin(cmd, color, depth, frame, left, right, target, overlay != nullptr, kernel != nullptr);
  if (input_ && !r.gatherFromHost) recordConversion(r);
  if (r.gatherFromHost) {
    recordGatherFromHost(r);
  } else if (kernel) {  // the passes it runs take Images: the host's are borrowed (their layer kept for barriers)
    const auto borrowed = [&](const vk::Image& own, const HostImage* host, VkFormat format) {
      return own.image ? vk::borrowImage(own.image, own.view, format, desc_.width, desc_.height)
                       : vk::borrowImage(host->image, host->view, format, desc_.width, desc_.height, host->layer);
    };
    kernel->recordKernel(cmd, borrowed(centerColor_, &color, eyeFormat()),
                         borrowed(linearDepth_, &depth, VK_FORMAT_R32_SFLOAT), borrowed(leftEye_, left, eyeFormat()),
                         borrowed(rightEye_, right, eyeFormat()));
  } else {
    recordStorageKernel(r);
  }
  if (overlay) recordOverlay(r, *overlay);
  if (pack_ && !r.packedByGather) recordPacking(r);
  end(r);
}

}  // namespace s3d::stereo
