#include "s3d/stereo/host_hybrid_pass.h"

#include "s3d/stereo/host_hybrid_shared.h"

// clang-format off
#include <s3d_spirv/stereo_hybrid_mask_depth_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

// The buffer between the mask-depth dispatch and the copies into the host's images.
void bufferBarrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.buffer = buffer;
  barrier.size = VK_WHOLE_SIZE;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.bufferMemoryBarrierCount = 1;
  dependency.pBufferMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

vk::PipelineLayout depthLayout(const vk::Context& context) {
  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  return vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::HostHybridDepthConstants),
                                        VK_SHADER_STAGE_COMPUTE_BIT);
}

std::uint32_t groups(std::uint32_t size) { return (size + S3D_HOST_HYBRID_GROUP_SIZE - 1) / S3D_HOST_HYBRID_GROUP_SIZE; }

}  // namespace

HostHybridPass::HostHybridPass(vk::Context& context, std::uint32_t width, std::uint32_t height, StereoKernel kernel,
                               int cell)
    : context_(&context),
      width_(width),
      height_(height),
      displacement_(context, kernel),
      hybrid_(context),
      images_(hybrid_.createImages(width, height, cell)),
      depths_(vk::createBuffer(context, VkDeviceSize(width) * height * 2 * sizeof(float),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               vk::MemoryLocation::Device)),
      depthLayout_(depthLayout(context)),
      depthPipeline_(vk::createComputePipeline(context, depthLayout_.layout, spirv_stereo_hybrid_mask_depth_comp)) {}

void HostHybridPass::recordKernel(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                                  const vk::Image& leftEye, const vk::Image& rightEye,
                                  const StereoParameters& parameters, bool reversedZ) {
  const StereoParameters base = displacementParameters(parameters);
  displacement_.record(cmd, centerColor, linearDepth, leftEye, rightEye, makeStereoConstants(base, width_, height_));
  hybrid_.recordMasks(cmd, linearDepth, images_, makeHybridConstants(parameters, width_, height_));
  for (const vk::Image* mask : {&images_.leftMask, &images_.rightMask})
    vk::transition(cmd, *mask, vk::kComputeWrite, vk::kComputeRead);
  // The previous frame's copies read the buffer this dispatch overwrites.
  bufferBarrier(cmd, depths_.buffer, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const VkDescriptorImageInfo masks[] = {{VK_NULL_HANDLE, images_.leftMask.view, VK_IMAGE_LAYOUT_GENERAL},
                                         {VK_NULL_HANDLE, images_.rightMask.view, VK_IMAGE_LAYOUT_GENERAL}};
  const VkDescriptorBufferInfo buffer{depths_.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[3] = {vk::storageImageWrite(0, &masks[0]), vk::storageImageWrite(1, &masks[1]),
                                    {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  writes[2].dstBinding = 2;
  writes[2].descriptorCount = 1;
  writes[2].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[2].pBufferInfo = &buffer;
  const gpu::HostHybridDepthConstants push{int(width_), int(height_), reversedZ ? 0.0f : 1.0f, reversedZ ? 1.0f : 0.0f};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, depthPipeline_.get());
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, depthLayout_.layout, 0, 3, writes);
  vkCmdPushConstants(cmd, depthLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
  vkCmdDispatch(cmd, groups(width_), groups(height_), 1);
  bufferBarrier(cmd, depths_.buffer, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
}

void HostHybridPass::recordMaskCopies(VkCommandBuffer cmd, const HostImage& leftMask, const HostImage& rightMask) const {
  const HostImage* masks[] = {&leftMask, &rightMask};
  for (std::size_t eye = 0; eye < 2; ++eye) {
    const HostImage& mask = *masks[eye];
    const vk::Image image = vk::borrowImage(mask.image, mask.view, mask.format, width_, height_, mask.layer);
    const bool synchronize = mask.stage != VK_PIPELINE_STAGE_2_NONE;
    const vk::ImageState host{mask.layout, mask.stage, mask.access};
    if (synchronize) vk::transition(cmd, image, host, vk::kTransferDestination);
    VkBufferImageCopy region{};
    region.bufferOffset = VkDeviceSize(eye) * width_ * height_ * sizeof(float);
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, mask.layer, 1};
    region.imageExtent = {width_, height_, 1};
    const VkImageLayout layout = synchronize ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : mask.layout;
    vkCmdCopyBufferToImage(cmd, depths_.buffer, image.image, layout, 1, &region);
    if (synchronize) vk::transition(cmd, image, vk::kTransferDestination, host);
  }
}

}  // namespace s3d::stereo
