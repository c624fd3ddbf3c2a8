#include "s3d/renderer/raycast_visibility.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>

#include "compute_binding.h"
#include "s3d/renderer/renderer_shared.h"

// clang-format off
#include <s3d_spirv/raycast_bin_comp.h>
#include <s3d_spirv/raycast_setup_comp.h>
#include <s3d_spirv/raycast_visibility_comp.h>
// clang-format on

namespace s3d::renderer {

RaycastVisibility::RaycastVisibility(vk::Context& context) : context_(context) {
  using detail::computeBinding;
  const VkDescriptorSetLayoutBinding bindings[] = {
      computeBinding(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER), computeBinding(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), computeBinding(3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
      computeBinding(4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),  computeBinding(5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
      computeBinding(6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), computeBinding(7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),  computeBinding(9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), computeBinding(11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), computeBinding(13, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), computeBinding(15, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  layout_ = vk::createPushDescriptorLayout(context_, bindings, 0, 0);
  pipeline_ = vk::createComputePipeline(context_, layout_.layout, spirv_raycast_visibility_comp);  // no alpha test
  // The setup and the bins: a uniform buffer, four storage buffers and up to three words of push constants.
  const VkDescriptorSetLayoutBinding setupBindings[] = {
      computeBinding(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER), computeBinding(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), computeBinding(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      computeBinding(4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  setupLayout_ = vk::createPushDescriptorLayout(context_, setupBindings, 3 * sizeof(std::uint32_t),
                                                VK_SHADER_STAGE_COMPUTE_BIT);
  setupPipeline_ = vk::createComputePipeline(context_, setupLayout_.layout, spirv_raycast_setup_comp);
  binPipeline_ = vk::createComputePipeline(context_, setupLayout_.layout, spirv_raycast_bin_comp);
  largeBinPipeline_ = vk::createComputePipeline(context_, setupLayout_.layout, spirv_raycast_bin_comp,
                                                vk::SpecializationWords({VK_TRUE}));
  constants_ = vk::createBuffer(context_, sizeof(gpu::RaycastConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                vk::MemoryLocation::HostVisible);
}

void RaycastVisibility::setBvh(const SceneBvh& bvh) {
  if (bvh.visibilityPacking.y != 0)
    throw std::invalid_argument("the ray-cast visibility pass writes narrow visibility ids; this scene's objects and "
                                "largest mesh need wide ones");
  preparing_.reset();  // a view prepared for the former tree is not this one's
  prepared_.reset();
  auto upload = [this](vk::Buffer& buffer, std::span<const std::byte> bytes) {
    // An empty tree still binds a buffer (one placeholder element's size).
    buffer = vk::createBuffer(context_, std::max<VkDeviceSize>(bytes.size(), 48),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryLocation::Device);
    if (!bytes.empty()) vk::uploadBuffer(context_, buffer, bytes);
  };
  upload(nodes_, std::as_bytes(std::span(bvh.nodes)));
  upload(triangles_, std::as_bytes(std::span(bvh.triangles)));
  snapped_ = vk::createBuffer(context_, std::max<VkDeviceSize>(bvh.triangles.size(), 1) * sizeof(gpu::SnappedTriangle),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryLocation::Device);
  triangleCount_ = std::uint32_t(bvh.triangles.size());
  firstPersonFirst_ = bvh.firstPersonFirst;
  worldRoot_ = bvh.worldRoot;
  firstPersonRoot_ = bvh.firstPersonRoot;
  packing_ = bvh.visibilityPacking;
  binLarge_ = vk::createBuffer(context_, sizeof(gpu::RaycastBinLarge) + std::max<VkDeviceSize>(triangleCount_, 1) * 4,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                               vk::MemoryLocation::Device);
  hasCutouts_ = std::any_of(bvh.triangles.begin(), bvh.triangles.end(),
                            [](const gpu::BvhTriangle& t) { return (t.flags & S3D_BVH_CUTOUT) != 0; });
  hasBvh_ = true;
}

// The traversal with cut-outs' alpha test compiled in (kCutoutAlphaTest), made at the first tree that needs it;
// trees without cut-outs keep the plain traversal.
VkPipeline RaycastVisibility::alphaTestPipeline() {
  if (!alphaTestPipeline_)
    alphaTestPipeline_ = vk::createComputePipeline(context_, layout_.layout, spirv_raycast_visibility_comp,
                                                   vk::SpecializationWords({VK_TRUE}));
  return alphaTestPipeline_.get();
}

namespace {

constexpr VkAccessFlags2 kStorageAccess = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

// Bins of S3D_RAYCAST_BIN_SIZE pixels across and down an image.
glm::uvec2 binGrid(std::uint32_t width, std::uint32_t height) {
  return {(width + S3D_RAYCAST_BIN_SIZE - 1) / S3D_RAYCAST_BIN_SIZE, (height + S3D_RAYCAST_BIN_SIZE - 1) / S3D_RAYCAST_BIN_SIZE};
}

}  // namespace

// A pass of setupLayout_: the pipeline, the uniform constants at binding 0, four storage buffers at 1-4 and the
// push constants.
void RaycastVisibility::bindSetupLayoutPass(VkCommandBuffer cmd, VkPipeline pipeline, const VkDescriptorBufferInfo& constants,
                                            const std::array<VkDescriptorBufferInfo, 4>& buffers,
                                            std::span<const std::uint32_t> push) const {
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &constants), vk::uniformBufferWrite(1, &buffers[0]),
                                   vk::uniformBufferWrite(2, &buffers[1]), vk::uniformBufferWrite(3, &buffers[2]),
                                   vk::uniformBufferWrite(4, &buffers[3])};
  for (std::uint32_t i : {1u, 2u, 3u, 4u}) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, setupLayout_.layout, 0, 5, writes);
  vkCmdPushConstants(cmd, setupLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, std::uint32_t(push.size_bytes()),
                     push.data());
}

// Every triangle set up for the view, and the bins' counts zeroed; no barrier (the callers order it).
void RaycastVisibility::dispatchSetup(VkCommandBuffer cmd) const {
  if (triangleCount_ == 0) return;
  const VkDescriptorBufferInfo constantInfo{constants_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo triangleInfo{triangles_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo snappedInfo{snapped_.buffer, 0, VK_WHOLE_SIZE};
  const std::uint32_t binCount = binning_ ? 2 * binsPerLayer_ : 0;
  // Without bins the triangles stand in for their buffers (the shader does not write them then).
  const VkDescriptorBufferInfo countInfo{binning_ ? binCounts_.buffer : triangles_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo largeInfo{binning_ ? binLarge_.buffer : triangles_.buffer, 0, VK_WHOLE_SIZE};
  const std::uint32_t push[3] = {triangleCount_, firstPersonFirst_, binCount};
  bindSetupLayoutPass(cmd, setupPipeline_.get(), constantInfo, {triangleInfo, snappedInfo, countInfo, largeInfo}, push);
  vkCmdDispatch(cmd, (std::max(triangleCount_, binCount) + 63) / 64, 1, 1);
}

bool RaycastVisibility::usesBins(std::uint32_t width, std::uint32_t height) const {
  if (search_ != RaycastSearch::Automatic) return search_ == RaycastSearch::Bins;
  const glm::uvec2 grid = binGrid(width, height);
  return triangleCount_ <= std::uint64_t(grid.x) * grid.y * S3D_RAYCAST_BIN_AUTO_REFERENCES;
}

// Bins of S3D_RAYCAST_BIN_SIZE pixels for images of this size (made again only when the size changes).
void RaycastVisibility::sizeBins(std::uint32_t width, std::uint32_t height) {
  if (binsSize_ == glm::uvec2(width, height)) return;
  const glm::uvec2 grid = binGrid(width, height);
  binsX_ = grid.x;
  binsPerLayer_ = grid.x * grid.y;
  binCounts_ = vk::createBuffer(context_, VkDeviceSize(2) * binsPerLayer_ * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                vk::MemoryLocation::Device);
  binEntries_ = vk::createBuffer(context_, VkDeviceSize(2) * binsPerLayer_ * S3D_RAYCAST_BIN_CAPACITY * 4,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryLocation::Device);
  binsSize_ = {width, height};
}

// Every set-up triangle into the bins its pixel bounds touch, by its own thread, or queued when large; no barrier
// (the callers order it after the setup).
void RaycastVisibility::dispatchBins(VkCommandBuffer cmd) const {
  if (triangleCount_ == 0 || !binning_) return;
  bindBinPass(cmd, binPipeline_.get());
  vkCmdDispatch(cmd, (triangleCount_ + S3D_RAYCAST_BIN_GROUP - 1) / S3D_RAYCAST_BIN_GROUP, 1, 1);
}

// The queued large triangles into their bins by the indirect pass, after the binning pass's queue and dispatch
// arguments.
void RaycastVisibility::recordLargeBins(VkCommandBuffer cmd) const {
  if (triangleCount_ == 0 || !binning_) return;
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, kStorageAccess,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                    kStorageAccess | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  bindBinPass(cmd, largeBinPipeline_.get());
  vkCmdDispatchIndirect(cmd, binLarge_.buffer, 0);
}

void RaycastVisibility::bindBinPass(VkCommandBuffer cmd, VkPipeline pipeline) const {
  const VkDescriptorBufferInfo constantInfo{constants_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo snappedInfo{snapped_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo countInfo{binCounts_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo entryInfo{binEntries_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo largeInfo{binLarge_.buffer, 0, VK_WHOLE_SIZE};
  const std::uint32_t push[2] = {triangleCount_, firstPersonFirst_};
  bindSetupLayoutPass(cmd, pipeline, constantInfo, {snappedInfo, countInfo, entryInfo, largeInfo}, push);
}

// Whether a view of this size uses bins, and its bins.
void RaycastVisibility::sizeView(std::uint32_t width, std::uint32_t height) {
  binning_ = usesBins(width, height);
  if (binning_) sizeBins(width, height);
}

void RaycastVisibility::writeCameraConstants(gpu::RaycastConstants& constants, const RaycastCamera& camera,
                                             std::uint32_t width, std::uint32_t height) const {
  constants.clipToLayer[S3D_LAYER_WORLD] = clipToLayerOf(camera.worldViewProjection);
  constants.clipToLayer[S3D_LAYER_FIRST_PERSON] = clipToLayerOf(camera.firstPersonViewProjection);
  constants.viewProjection[S3D_LAYER_WORLD] = camera.worldViewProjection;
  constants.viewProjection[S3D_LAYER_FIRST_PERSON] = camera.firstPersonViewProjection;
  constants.depthRanges = glm::vec4(camera.worldDepthRange, camera.firstPersonDepthRange);
  constants.screen = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
  constants.roots = glm::uvec4(worldRoot_, firstPersonRoot_, 0u, 0u);
  constants.clearedDepth = glm::vec4(camera.clearedDepth, nearerOf(camera), 0.0f, 0.0f);
  constants.bins = glm::uvec4(binsX_, binsPerLayer_, binning_ ? 1u : 0u, 0u);
}

void RaycastVisibility::recordPreparation(VkCommandBuffer cmd, PreparationStep step, const RaycastCamera& camera,
                                          std::uint32_t width, std::uint32_t height) {
  if (!hasBvh_) throw std::invalid_argument("the ray-cast visibility pass was prepared before it had a BVH");
  const PreparedView view{camera, {width, height}};
  switch (step) {
    case PreparationStep::Setup: {
      sizeView(width, height);
      gpu::RaycastConstants constants{};  // the camera's fields: the setup and bins read no others
      writeCameraConstants(constants, camera, width, height);
      std::memcpy(constants_.mapped, &constants, sizeof(constants));
      preparing_ = view;
      prepared_.reset();
      dispatchSetup(cmd);
      return;
    }
    case PreparationStep::Bins:
      requirePreparing(view, "binned");
      dispatchBins(cmd);
      return;
    case PreparationStep::LargeBins:
      requirePreparing(view, "given its large triangles");
      recordLargeBins(cmd);
      prepared_ = preparing_;
      preparing_.reset();
      return;
  }
}

void RaycastVisibility::requirePreparing(const PreparedView& view, const char* what) const {
  if (preparing_ != view)
    throw std::logic_error(std::string("the ray-cast view was ") + what + " before its setup for the same camera and size");
}

void RaycastVisibility::record(VkCommandBuffer cmd, const RaycastCamera& camera, const ShadeMask& mask,
                               const vk::Image& visibilityIds, const vk::Image& deviceDepth,
                               const RaycastRegion& region, const RaycastCutouts& cutouts) {
  if (!hasBvh_) throw std::invalid_argument("the ray-cast visibility pass was recorded before it had a BVH");
  const std::uint32_t width = visibilityIds.width, height = visibilityIds.height;
  if (visibilityIds.format != VK_FORMAT_R32_UINT || deviceDepth.format != VK_FORMAT_R32_SFLOAT ||
      deviceDepth.width != width || deviceDepth.height != height)
    throw std::invalid_argument("the ray-cast visibility pass needs R32_UINT ids and R32_SFLOAT depth of one size");
  if (mask.image && (mask.image->format != VK_FORMAT_R32_UINT || mask.image->width != width || mask.image->height != height))
    throw std::invalid_argument("the ray-cast visibility pass's mask must be R32_UINT and the size of its targets");
  if (mask.uncastDepth && (mask.uncastDepth->format != VK_FORMAT_R32_SFLOAT || mask.uncastDepth->width != width ||
                           mask.uncastDepth->height != height))
    throw std::invalid_argument("the ray-cast visibility pass's uncast depth must be R32_SFLOAT and the size of its targets");
  // Prepared ahead for this camera and size (recordPreparation): its setup and bins stand.
  const bool prepared = isPrepared(camera, width, height);
  prepared_.reset();
  preparing_.reset();
  if (!prepared) sizeView(width, height);
  gpu::RaycastConstants constants{};
  writeCameraConstants(constants, camera, width, height);
  constants.options = glm::uvec4(mask.threshold, mask.image ? 1u : 0u, packing_.x, packing_.y);
  constants.region = glm::uvec4(region.tiles != VK_NULL_HANDLE ? 1u : 0u, region.tilesX,
                                 mask.image && mask.uncastDepth ? 1u : 0u, 0u);
  std::memcpy(constants_.mapped, &constants, sizeof(constants));
  if (!prepared) {  // after the previous recording's casts read the set-up triangles and bins
    vk::computeStorageBarrier(cmd);
    dispatchSetup(cmd);
    if (binning_) {
      vk::computeStorageBarrier(cmd);
      dispatchBins(cmd);
      recordLargeBins(cmd);
    }
  }
  vk::computeStorageBarrier(cmd);

  VkDescriptorBufferInfo constantInfo{constants_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo nodeInfo{nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo triangleInfo{triangles_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo snappedInfo{snapped_.buffer, 0, VK_WHOLE_SIZE};
  // Without a mask the ids image stands in for it (the shader does not read it then).
  VkDescriptorImageInfo maskInfo{VK_NULL_HANDLE, mask.image ? mask.image->view : visibilityIds.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo idInfo{VK_NULL_HANDLE, visibilityIds.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo depthInfo{VK_NULL_HANDLE, deviceDepth.view, VK_IMAGE_LAYOUT_GENERAL};
  // Without an uncast depth the depth target stands in for it (the shader does not read it then).
  VkDescriptorImageInfo uncastInfo{VK_NULL_HANDLE, mask.image && mask.uncastDepth ? mask.uncastDepth->view : deviceDepth.view,
                                   VK_IMAGE_LAYOUT_GENERAL};
  // Without a region the node buffer stands in for it (the shader does not read it then).
  VkDescriptorBufferInfo regionInfo{region.tiles != VK_NULL_HANDLE ? region.tiles : nodes_.buffer, 0, VK_WHOLE_SIZE};
  // Without cut-outs' alpha test the node buffer stands in for its buffers (the shader does not read them then).
  const bool alphaTest = cutouts.objects != VK_NULL_HANDLE && hasCutouts_;
  VkDescriptorBufferInfo objectInfo{alphaTest ? cutouts.objects : nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo indexInfo{alphaTest ? cutouts.indices : nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo surfaceInfo{alphaTest ? cutouts.surfaceVertices : nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo tableInfo{alphaTest ? cutouts.textureTable : nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo texelInfo{alphaTest ? cutouts.texels : nodes_.buffer, 0, VK_WHOLE_SIZE};
  // Without bins the node buffer stands in for theirs (the shader does not read them then).
  VkDescriptorBufferInfo binCountInfo{binning_ ? binCounts_.buffer : nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo binEntryInfo{binning_ ? binEntries_.buffer : nodes_.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &constantInfo), vk::uniformBufferWrite(1, &nodeInfo),
                                   vk::uniformBufferWrite(2, &triangleInfo), vk::storageImageWrite(3, &maskInfo),
                                   vk::storageImageWrite(4, &idInfo),        vk::storageImageWrite(5, &depthInfo),
                                   vk::uniformBufferWrite(6, &regionInfo),   vk::uniformBufferWrite(7, &snappedInfo),
                                   vk::storageImageWrite(8, &uncastInfo),    vk::uniformBufferWrite(9, &objectInfo),
                                   vk::uniformBufferWrite(10, &indexInfo),   vk::uniformBufferWrite(11, &surfaceInfo),
                                   vk::uniformBufferWrite(12, &tableInfo),   vk::uniformBufferWrite(13, &texelInfo),
                                   vk::uniformBufferWrite(14, &binCountInfo), vk::uniformBufferWrite(15, &binEntryInfo)};
  for (std::uint32_t i : {1u, 2u, 6u, 7u, 9u, 10u, 11u, 12u, 13u, 14u, 15u})
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, alphaTest ? alphaTestPipeline() : pipeline_.get());
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, std::uint32_t(std::size(writes)),
                                writes);
  const std::uint32_t group = S3D_RAYCAST_GROUP_SIZE;
  vkCmdDispatch(cmd, (width + group - 1) / group, (height + group - 1) / group, 1);
}

}  // namespace s3d::renderer
