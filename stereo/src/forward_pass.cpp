#include "s3d/stereo/forward_pass.h"

#include <stdexcept>

#include "s3d/stereo/detail/eye_pair_pipeline.h"

// clang-format off
#include <s3d_spirv/stereo_forward_clear_comp.h>
#include <s3d_spirv/stereo_forward_resolve_comp.h>
#include <s3d_spirv/stereo_forward_row_comp.h>
#include <s3d_spirv/stereo_forward_row_keys_comp.h>
#include <s3d_spirv/stereo_forward_splat_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

constexpr VkFormat kKeyFormat = VK_FORMAT_R32_UINT;
// The z-buffers between dispatches and for a following pass: atomics and stores write them, loads read them.
constexpr vk::ImageState kKeysReadWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
// Center color, linear depth, left eye, right eye, left and right keys splatted into, left and right keys the
// resolve empties for the next record.
constexpr std::uint32_t kBindings = 8;

int rowCapacity(int width) {
  return (width + S3D_FORWARD_ROW_CAPACITY_STEP - 1) / S3D_FORWARD_ROW_CAPACITY_STEP * S3D_FORWARD_ROW_CAPACITY_STEP;
}

std::uint32_t groupsFor(int size, int group) { return std::uint32_t((size + group - 1) / group); }

}  // namespace

std::uint32_t forwardRowSharedBytes(int width) {
  return std::uint32_t(rowCapacity(width)) * S3D_FORWARD_ROW_SHARED_BYTES_PER_COLUMN;
}

ForwardStereoPass::ForwardStereoPass(const vk::Context& context, StereoKernel kernel, ForwardKeys keys)
    : context_(&context), kernel_(kernel), keysWanted_(keys) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  // The row group's 128 invocations are Vulkan's guaranteed minimum; its shared arrays are what may not fit.
  static_assert(S3D_FORWARD_ROW_GROUP_SIZE <= 128);
  maxSharedBytes_ = properties.limits.maxComputeSharedMemorySize;
  VkDescriptorSetLayoutBinding bindings[kBindings];
  for (std::uint32_t i = 0; i < kBindings; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  layout_ = vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::ForwardConstants), VK_SHADER_STAGE_COMPUTE_BIT);
}

bool ForwardStereoPass::usesRowKernel(int width) const {
  // Opt-in: on an NVIDIA H200 at 1920x1080 the row kernel took 1.4-2.2x the key-image kernel (docs/RESULTS.md),
  // so Auto keeps the key-image dispatches, as the gather's row tiles stay opt-in.
  return kernel_ == StereoKernel::RowTiles && forwardRowSharedBytes(width) <= maxSharedBytes_;
}

void ForwardStereoPass::record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                               const vk::Image& leftEye, const vk::Image& rightEye,
                               const gpu::ForwardConstants& c) const {
  for (const vk::Image* image : {&centerColor, &linearDepth, &leftEye, &rightEye})
    if (int(image->width) != c.width || int(image->height) != c.height)
      throw std::invalid_argument("ForwardStereoPass: image size does not match the constants");
  const bool rows = usesRowKernel(c.width);
  const bool keyImages = !rows || keysWanted_ == ForwardKeys::Kept;
  const bool fresh = keyImages && (!zBuffers_ || int((*zBuffers_)[0].left.width) != c.width ||
                                   int((*zBuffers_)[0].left.height) != c.height);
  if (fresh) {
    auto keys = [&] {
      return vk::createImage(*context_, kKeyFormat, std::uint32_t(c.width), std::uint32_t(c.height),
                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);  // read back in tests
    };
    // Built whole: clang does not default-construct a nested aggregate with a member initializer here.
    zBuffers_ = std::array<KeyPair, 2>{KeyPair{keys(), keys(), false}, KeyPair{keys(), keys(), false}};
    current_ = 0;
  } else if (keyImages) {
    current_ = 1 - current_;  // the pair the previous record's resolve emptied (if it ran the key-image kernel)
  }
  KeyPair* splatInto = keyImages ? &(*zBuffers_)[std::size_t(current_)] : nullptr;
  KeyPair* emptied = keyImages ? &(*zBuffers_)[std::size_t(1 - current_)] : nullptr;
  VkDescriptorImageInfo infos[kBindings] = {{VK_NULL_HANDLE, centerColor.view, VK_IMAGE_LAYOUT_GENERAL},
                                            {VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                            {VK_NULL_HANDLE, leftEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                            {VK_NULL_HANDLE, rightEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                            {},
                                            {},
                                            {},
                                            {}};
  if (keyImages) {
    // Undefined first time (or after a resize), else after an earlier record (or a pass after it) used them.
    for (const KeyPair* pair : {splatInto, emptied})
      for (const vk::Image* keys : {&pair->left, &pair->right})
        vk::transition(cmd, *keys, fresh ? vk::kUndefined : kKeysReadWrite, kKeysReadWrite);
    infos[4] = {VK_NULL_HANDLE, splatInto->left.view, VK_IMAGE_LAYOUT_GENERAL};
    infos[5] = {VK_NULL_HANDLE, splatInto->right.view, VK_IMAGE_LAYOUT_GENERAL};
    infos[6] = {VK_NULL_HANDLE, emptied->left.view, VK_IMAGE_LAYOUT_GENERAL};
    infos[7] = {VK_NULL_HANDLE, emptied->right.view, VK_IMAGE_LAYOUT_GENERAL};
  }
  // The row kernel declares four bindings, or six when it stores its z-buffers; the key-image dispatches all eight.
  const std::uint32_t bound = !keyImages ? 4 : rows ? 6 : kBindings;
  VkWriteDescriptorSet writes[kBindings];
  for (std::uint32_t i = 0; i < bound; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  auto dispatch = [&](VkPipeline pipeline, std::uint32_t groupsX, std::uint32_t groupsY) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, bound, writes);
    vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
  };
  keysWritten_ = keyImages;
  if (rows) {
    dispatch(rowPipeline(rowCapacity(c.width)).pipeline, 1, std::uint32_t(c.height));  // one workgroup per row
    if (splatInto) splatInto->empty = false;  // it stores every key; the other pair is as it was
    return;
  }
  makeKeyImagePipelines();
  const std::uint32_t groupsX = groupsFor(c.width, S3D_FORWARD_GROUP_SIZE);
  const std::uint32_t groupsY = groupsFor(c.height, S3D_FORWARD_GROUP_SIZE);
  auto keysBarrier = [&] {
    for (const vk::Image* keys : {&splatInto->left, &splatInto->right}) vk::transition(cmd, *keys, kKeysReadWrite, kKeysReadWrite);
  };
  if (!splatInto->empty) {  // first use (or after a row-kernel record): the previous resolve did not empty it
    dispatch(clear_.get(), groupsX, groupsY);
    keysBarrier();
  }
  dispatch(splat_.get(), groupsX, groupsY);
  keysBarrier();
  dispatch(resolve_.get(), groupsX, groupsY);
  splatInto->empty = false;
  emptied->empty = true;
}

const ForwardStereoPass::RowPipeline& ForwardStereoPass::rowPipeline(int capacity) const {
  if (!row_ || row_->capacity != capacity) {
    const std::span<const std::uint32_t> code = keysWanted_ == ForwardKeys::Kept
                                                    ? std::span<const std::uint32_t>(spirv_stereo_forward_row_keys_comp)
                                                    : std::span<const std::uint32_t>(spirv_stereo_forward_row_comp);
    row_ = RowPipeline{capacity, vk::createComputePipeline(*context_, layout_.layout, code,
                                                           vk::SpecializationWords({std::uint32_t(capacity)}))};
  }
  return *row_;
}

void ForwardStereoPass::makeKeyImagePipelines() const {
  if (clear_) return;  // the row kernel needs none of them
  clear_ = vk::createComputePipeline(*context_, layout_.layout, spirv_stereo_forward_clear_comp);
  splat_ = vk::createComputePipeline(*context_, layout_.layout, spirv_stereo_forward_splat_comp);
  resolve_ = vk::createComputePipeline(*context_, layout_.layout, spirv_stereo_forward_resolve_comp);
}

const vk::Image& ForwardStereoPass::keys(Eye eye) const {
  if (!zBuffers_) throw std::logic_error("ForwardStereoPass::keys: nothing recorded yet");
  if (!keysWritten_)
    throw std::logic_error("ForwardStereoPass::keys: the row kernel keeps its z-buffers in shared memory; construct "
                           "the pass with ForwardKeys::Kept to have them stored");
  const KeyPair& pair = (*zBuffers_)[std::size_t(current_)];
  return eye == Eye::Left ? pair.left : pair.right;
}

StereoPair synthesizeForwardOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                  const gpu::ForwardConstants& constants, StereoKernel kernel) {
  return detail::runOnCpuImages(context, ForwardStereoPass(context, kernel), center, linearDepth, constants);
}

}  // namespace s3d::stereo
