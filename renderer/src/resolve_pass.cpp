#include "resolve_pass.h"

#include "compute_binding.h"
#include "s3d/renderer/renderer_shared.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/resolve_comp.h>
// clang-format on

namespace s3d::renderer::detail {

ResolvePass::ResolvePass(vk::Context& context, bool counting) : context_(context) {
  constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  const VkDescriptorSetLayoutBinding bindings[] = {
      computeBinding(0, ubo),     computeBinding(1, storage), computeBinding(2, storage), computeBinding(3, storage),
      computeBinding(4, sampled), computeBinding(5, storage), computeBinding(6, ssbo),    computeBinding(7, storage)};
  layout_ = vk::createPushDescriptorLayout(context_, bindings, sizeof(gpu::ResolveConstants), VK_SHADER_STAGE_COMPUTE_BIT);
  pipelines_ = std::make_unique<TilePipelines>(context_, layout_.layout, spirv_resolve_comp, counting);
  nearest_ = vk::createNearestClampSampler(context_);
}

void ResolvePass::record(VkCommandBuffer cmd, const Inputs& in, const Outputs& out) {
  if (in.hdrJustWritten) vk::transition(cmd, in.hdr, vk::kComputeWrite, vk::kComputeRead);
  // The lighting pass earlier in the frame bound them for writing (its fused resolve), so they are ordered after it.
  for (const vk::Image* image : {&out.display, &out.linearDepth, &out.resolvedHdr})
    vk::transition(cmd, *image, vk::kComputeWrite, vk::kComputeWrite);
  const gpu::ResolveConstants resolve{int(in.supersample), int(in.outputWidth), int(in.outputHeight), 0};
  VkDescriptorBufferInfo frameInfo{in.frameConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo hdrInfo{VK_NULL_HANDLE, in.hdr.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo displayInfo{VK_NULL_HANDLE, out.display.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo resolvedHdrInfo{VK_NULL_HANDLE, out.resolvedHdr.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo depthInfo{nearest_, in.depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo linearInfo{VK_NULL_HANDLE, out.linearDepth.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorBufferInfo tileInfo{in.tiles, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo maskInfo = in.shadeMask;
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo),  vk::storageImageWrite(1, &hdrInfo),
                                   vk::storageImageWrite(2, &displayInfo), vk::storageImageWrite(3, &resolvedHdrInfo),
                                   vk::sampledImageWrite(4, &depthInfo),   vk::storageImageWrite(5, &linearInfo),
                                   vk::uniformBufferWrite(6, &tileInfo),   vk::storageImageWrite(7, &maskInfo)};
  writes[4].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[6].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->get(in.masked));
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 8, writes);
  vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(resolve), &resolve);
  // Masked: one workgroup per listed render tile (its output pixels); else one per 16x16 output pixels.
  if (in.masked)
    vkCmdDispatchIndirect(cmd, in.tiles, TileLists::kMaskedTilesDispatch);
  else
    vkCmdDispatch(cmd, (in.outputWidth + S3D_TILE_SIZE - 1) / S3D_TILE_SIZE,
                  (in.outputHeight + S3D_TILE_SIZE - 1) / S3D_TILE_SIZE, 1);
}

}  // namespace s3d::renderer::detail
