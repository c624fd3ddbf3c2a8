#include "tile_lists.h"

#include <utility>

#include "compute_binding.h"

#include <cstring>
#include <vector>

// clang-format off
#include <cstdint>
#include <s3d_spirv/gbuffer_count_comp.h>
#include <s3d_spirv/mask_tiles_comp.h>
#include <s3d_spirv/tile_reset_comp.h>
// clang-format on

namespace s3d::renderer::detail {
namespace {

constexpr std::uint32_t groups(std::uint32_t size, std::uint32_t group) { return (size + group - 1) / group; }

using detail::computeBinding;

constexpr VkPipelineStageFlags2 kComputeAndIndirect =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
constexpr VkAccessFlags2 kStorageAndIndirect = VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                               VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                               VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;

}  // namespace

vk::Unique<VkPipeline> createTilePipeline(const vk::Context& context, VkPipelineLayout layout,
                                          std::span<const std::uint32_t> spirv, bool masked, bool counting,
                                          std::span<const bool> switches, std::span<const std::uint32_t> words) {
  std::vector<std::uint32_t> values = {masked ? VK_TRUE : VK_FALSE, counting ? VK_TRUE : VK_FALSE};
  for (bool on : switches) values.push_back(on ? VK_TRUE : VK_FALSE);
  values.insert(values.end(), words.begin(), words.end());
  return vk::createComputePipeline(context, layout, spirv, vk::SpecializationWords(std::move(values)));
}

VkPipeline TilePipelines::get(bool masked, std::initializer_list<bool> switches) {
  std::uint32_t key = masked ? 1u : 0u, bit = 2u;
  for (bool on : switches) {
    if (on) key |= bit;
    bit <<= 1;
  }
  vk::Unique<VkPipeline>& pipeline = pipelines_[key];
  if (!pipeline)
    pipeline = createTilePipeline(*context_, layout_, spirv_, masked, counting_,
                                  std::span<const bool>(switches.begin(), switches.size()), values_);
  return pipeline;
}

TileLists::TileLists(vk::Context& context, std::uint32_t renderWidth, std::uint32_t renderHeight)
    : context_(context),
      width_(renderWidth),
      height_(renderHeight),
      tilesX_(groups(renderWidth, S3D_TILE_SIZE)),
      tilesY_(groups(renderHeight, S3D_TILE_SIZE)) {
  const VkDeviceSize entries = S3D_TILE_LIST_WORDS * VkDeviceSize(tilesX_) * tilesY_ * sizeof(std::uint32_t);
  buffer_ = vk::createBuffer(context_, sizeof(gpu::TileHeader) + entries,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                             vk::MemoryLocation::Device);
  readback_ = vk::createBuffer(context_, sizeof(gpu::TileHeader), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               vk::MemoryLocation::HostVisible);
  placeholderMask_ = vk::createImage(context_, VK_FORMAT_R32_UINT, 1, 1,
                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  const std::uint32_t zero = 0;
  vk::uploadImage(context_, placeholderMask_, std::as_bytes(std::span(&zero, 1)), kShadeMaskRead);

  constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  const VkDescriptorSetLayoutBinding buildBindings[] = {computeBinding(0, ubo), computeBinding(1, ssbo),
                                                        computeBinding(2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)};
  buildLayout_ = vk::createPushDescriptorLayout(context_, buildBindings, 0, 0);
  build_ = createTilePipeline(context_, buildLayout_.layout, spirv_mask_tiles_comp, true, false);
  reset_ = createTilePipeline(context_, buildLayout_.layout, spirv_tile_reset_comp, false, false);
  resetMasked_ = createTilePipeline(context_, buildLayout_.layout, spirv_tile_reset_comp, true, false);
  const VkDescriptorSetLayoutBinding countBindings[] = {
      computeBinding(0, ubo), computeBinding(1, ssbo), computeBinding(2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)};
  countLayout_ = vk::createPushDescriptorLayout(context_, countBindings, 0, 0);
  count_ = createTilePipeline(context_, countLayout_.layout, spirv_gbuffer_count_comp, false, true);
}

// A pass of buildLayout_ (the reset and the listing): the frame constants, the tile buffer and the mask (or the
// placeholder) pushed, the pipeline bound.
void TileLists::bindBuildLayoutPass(VkCommandBuffer cmd, VkPipeline pipeline, VkBuffer frameBuffer,
                                    const vk::Image* mask) const {
  VkDescriptorBufferInfo frameInfo{frameBuffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo tileInfo = descriptor();
  VkDescriptorImageInfo maskInfo = maskDescriptor(mask);
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo), vk::uniformBufferWrite(1, &tileInfo),
                                   vk::storageImageWrite(2, &maskInfo)};
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, buildLayout_.layout, 0, 3, writes);
}

void TileLists::recordMaskedResetAhead(VkCommandBuffer cmd, VkBuffer frameBuffer) const {
  bindBuildLayoutPass(cmd, resetMasked_, frameBuffer, nullptr);
  vkCmdDispatch(cmd, groups(tilesX_ * tilesY_, S3D_TILE_RESET_GROUP_SIZE), 1, 1);
}

void TileLists::recordReset(VkCommandBuffer cmd, VkBuffer frameBuffer, const vk::Image* mask, bool fragmentReads,
                            bool resetAhead) {
  if (!resetAhead || mask == nullptr) {
    // Earlier frames' compute reads, indirect reads and counter read-back finish before the reset overwrites it.
    vk::memoryBarrier(cmd, kComputeAndIndirect | VK_PIPELINE_STAGE_2_COPY_BIT, kStorageAndIndirect,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    bindBuildLayoutPass(cmd, mask != nullptr ? resetMasked_ : reset_, frameBuffer, mask);
    vkCmdDispatch(cmd, mask != nullptr ? groups(tilesX_ * tilesY_, S3D_TILE_RESET_GROUP_SIZE) : 1, 1, 1);
  }
  if (mask != nullptr)  // the host wrote the mask in an earlier submission (or earlier in its command buffer)
    vk::transition(cmd, *mask, {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT},
                   fragmentReads ? kShadeMaskRead : kShadeMaskComputeRead);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    kComputeAndIndirect, kStorageAndIndirect);
}

void TileLists::recordBuild(VkCommandBuffer cmd, VkBuffer frameBuffer, const vk::Image& mask) {
  bindBuildLayoutPass(cmd, build_, frameBuffer, &mask);
  vkCmdDispatch(cmd, tilesX_, tilesY_, 1);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kComputeAndIndirect,
                kStorageAndIndirect);
}

void TileLists::recordCountGBuffer(VkCommandBuffer cmd, VkBuffer frameBuffer, const vk::Image& material,
                                   VkSampler nearest) {
  VkDescriptorBufferInfo frameInfo{frameBuffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo tileInfo = descriptor();
  VkDescriptorImageInfo materialInfo{nearest, material.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo), vk::uniformBufferWrite(1, &tileInfo),
                                   vk::sampledImageWrite(2, &materialInfo)};
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[2].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, count_);
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, countLayout_.layout, 0, 3, writes);
  vkCmdDispatch(cmd, groups(width_, S3D_COMPUTE_GROUP_SIZE), groups(height_, S3D_COMPUTE_GROUP_SIZE), 1);
}

void TileLists::recordListsVisible(VkCommandBuffer cmd) {
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kComputeAndIndirect,
                kStorageAndIndirect);
}

void TileLists::recordCountReadback(VkCommandBuffer cmd) {
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferCopy region{0, 0, sizeof(gpu::TileHeader)};
  vkCmdCopyBuffer(cmd, buffer_.buffer, readback_.buffer, 1, &region);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_HOST_READ_BIT);
}

std::array<std::uint32_t, S3D_COUNT_SLOTS> TileLists::readCounts() const {
  gpu::TileHeader header{};
  std::memcpy(&header, readback_.mapped, sizeof(header));
  std::array<std::uint32_t, S3D_COUNT_SLOTS> counts{};
  std::memcpy(counts.data(), header.shadedPixels, sizeof(header.shadedPixels));
  return counts;
}

VkDescriptorImageInfo TileLists::maskDescriptor(const vk::Image* mask) const {
  return {VK_NULL_HANDLE, (mask != nullptr ? *mask : placeholderMask_).view, VK_IMAGE_LAYOUT_GENERAL};
}

}  // namespace s3d::renderer::detail
