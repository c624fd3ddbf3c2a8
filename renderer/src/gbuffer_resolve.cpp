#include "gbuffer_resolve.h"

#include "compute_binding.h"


#include "s3d/renderer/renderer_shared.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/gbuffer_resolve_comp.h>
// clang-format on

namespace s3d::renderer::detail {
namespace {

using detail::computeBinding;

// The targets once resolved: sampled by compute (ambient occlusion does not read them; lighting does).
constexpr vk::ImageState kComputeSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

}  // namespace

GBufferResolve::GBufferResolve(vk::Context& context, bool counting) : context_(context) {
  constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  const VkDescriptorSetLayoutBinding bindings[] = {
      computeBinding(0, ubo),     computeBinding(1, sampled), computeBinding(2, sampled), computeBinding(3, ssbo),
      computeBinding(4, ssbo),    computeBinding(5, ssbo),    computeBinding(6, storage), computeBinding(7, storage),
      computeBinding(8, ssbo),    computeBinding(9, storage), computeBinding(10, ssbo),   computeBinding(11, ssbo),
      computeBinding(12, ssbo)};
  layout_ = vk::createPushDescriptorLayout(context_, bindings, 0, 0);
  pipelines_ = std::make_unique<TilePipelines>(context_, layout_.layout, spirv_gbuffer_resolve_comp, counting);
  nearest_ = vk::createNearestClampSampler(context_);
}

void GBufferResolve::record(VkCommandBuffer cmd, const Inputs& in, const vk::Image& normalGlossiness,
                            const vk::Image& material, const vk::ImageState& targets) {
  vk::transition(cmd, normalGlossiness, targets, vk::kComputeWrite);
  vk::transition(cmd, material, targets, vk::kComputeWrite);
  VkDescriptorBufferInfo frameInfo{in.frameConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo depthInfo{nearest_, in.depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo visibilityInfo{nearest_, in.visibility.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo objectInfo{in.objectConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo indexInfo{in.indices, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo vertexInfo{in.vertices, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo normalInfo{VK_NULL_HANDLE, normalGlossiness.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo materialInfo{VK_NULL_HANDLE, material.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorBufferInfo tileInfo{in.tiles, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo maskInfo = in.shadeMask;
  VkDescriptorBufferInfo surfaceInfo{in.surfaceVertices, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo tableInfo{in.textureTable, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo texelInfo{in.texels, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[] = {
      vk::uniformBufferWrite(0, &frameInfo),  vk::sampledImageWrite(1, &depthInfo), vk::sampledImageWrite(2, &visibilityInfo),
      vk::uniformBufferWrite(3, &objectInfo), vk::uniformBufferWrite(4, &indexInfo), vk::uniformBufferWrite(5, &vertexInfo),
      vk::storageImageWrite(6, &normalInfo),  vk::storageImageWrite(7, &materialInfo), vk::uniformBufferWrite(8, &tileInfo),
      vk::storageImageWrite(9, &maskInfo),    vk::uniformBufferWrite(10, &surfaceInfo), vk::uniformBufferWrite(11, &tableInfo),
      vk::uniformBufferWrite(12, &texelInfo)};
  for (std::uint32_t i : {1u, 2u}) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  for (std::uint32_t i : {3u, 4u, 5u, 8u, 10u, 11u, 12u}) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->get(in.masked, {in.surfaceMaterials}));
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, std::uint32_t(std::size(writes)),
                                writes);
  if (in.masked)
    vkCmdDispatchIndirect(cmd, in.tiles, TileLists::kMaskedTilesDispatch);
  else
    vkCmdDispatch(cmd, in.tilesX, in.tilesY, 1);
  vk::transition(cmd, normalGlossiness, vk::kComputeWrite, kComputeSampled);
  vk::transition(cmd, material, vk::kComputeWrite, kComputeSampled);
}

}  // namespace s3d::renderer::detail
