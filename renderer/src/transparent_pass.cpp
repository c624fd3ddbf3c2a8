#include "transparent_pass.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "compute_binding.h"
#include "s3d/renderer/renderer_shared.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/transparent_comp.h>
#include <s3d_spirv/transparent_frag.h>
// clang-format on

namespace s3d::renderer::detail {
namespace {

// RGBA8: storage-image writable without extended formats; as a raster target it was also faster than one byte
// (docs/RESULTS.md "What did not work").
constexpr VkFormat kCoverageFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// The HDR image and the coverage between two objects' dispatches: each reads what the one before wrote.
// Depth tested by the raster implementation, read-only.
constexpr vk::ImageState kDepthReadOnlyAttachment{VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                                                  VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT};
constexpr vk::ImageState kComputeSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
constexpr vk::ImageState kComputeReadWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                           VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};

std::uint32_t tilesFor(std::uint32_t pixels) { return (pixels + S3D_TILE_SIZE - 1) / S3D_TILE_SIZE; }

// The mesh's bounding box as the image of the cube [-1, 1]^3 (object space).
glm::mat4 boundingBoxOfCube(const Mesh& mesh) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const Vertex& vertex : mesh.vertices) {
    lo = glm::min(lo, vertex.position);
    hi = glm::max(hi, vertex.position);
  }
  if (mesh.vertices.empty()) lo = hi = glm::vec3(0.0f);
  return glm::scale(glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)), 0.5f * (hi - lo));
}

}  // namespace

TransparentPass::TransparentPass(vk::Context& context, std::uint32_t width, std::uint32_t height,
                                 RendererOptions::TransparentCompositing compositing,
                                 const vk::GraphicsPipelineDesc& geometry, VkPipelineLayout geometryLayout)
    : context_(context), width_(width), height_(height) {
  using Compositing = RendererOptions::TransparentCompositing;
  if (compositing == Compositing::Raster || (compositing == Compositing::Automatic && context_.isCpuDevice())) {
    vk::GraphicsPipelineDesc transparent = geometry;
    transparent.fragmentSpirv = spirv_transparent_frag;
    transparent.colorFormats = {kHdrFormat, kCoverageFormat};  // coverage blends to 1 - prod(1 - opacity)
    transparent.depthTest = true;
    transparent.depthWrite = false;  // behind opaque surfaces is hidden; no depth write
    transparent.cullMode = VK_CULL_MODE_NONE;
    transparent.blend = vk::GraphicsPipelineDesc::Blend::Alpha;
    rasterPipeline_ = vk::createGraphicsPipeline(context_, geometryLayout, transparent);
    coverage_ = vk::createImage(context_, kCoverageFormat, width, height,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    return;
  }
  constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  const VkDescriptorSetLayoutBinding bindings[] = {
      computeBinding(0, ubo),     computeBinding(1, ssbo),    computeBinding(2, ssbo),    computeBinding(3, ssbo),
      computeBinding(4, ssbo),    computeBinding(5, sampled), computeBinding(6, storage), computeBinding(7, storage),
      computeBinding(8, sampled), computeBinding(9, sampled), computeBinding(10, storage)};
  layout_ = vk::createPushDescriptorLayout(context_, bindings, sizeof(gpu::TransparentConstants), VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context_, layout_.layout, spirv_transparent_comp);
  nearest_ = vk::createNearestClampSampler(context_);
  coverage_ = vk::createImage(context_, kCoverageFormat, width, height,
                              VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
}

void TransparentPass::setScene(const Scene& scene, std::span<const std::uint32_t> meshTriangleCounts,
                               std::span<const vk::Image> textures, const vk::Image& white, const vk::Image& flatNormal) {
  auto textureView = [&textures](std::int32_t index, const vk::Image& fallback) -> VkImageView {
    return index == kNoTexture ? fallback.view : textures[std::size_t(index)].view;
  };
  objects_.clear();
  for (std::uint32_t i = 0; i < scene.objects.size(); ++i) {
    const renderer::Object& object = scene.objects[i];
    if (!object.material.isTransparent()) continue;
    objects_.push_back({i, meshTriangleCounts[object.mesh], object.transform * boundingBoxOfCube(scene.meshes[object.mesh]),
                        object.transform[3], textureView(object.material.baseColorTexture, white),
                        textureView(object.material.normalTexture, flatNormal)});
  }
}

glm::uvec4 TransparentPass::tileRect(const glm::mat4& viewProjection, const glm::mat4& boxToWorld, std::uint32_t width,
                                     std::uint32_t height) {
  const glm::uvec4 all(0, 0, tilesFor(width), tilesFor(height));
  const glm::mat4 boxToClip = viewProjection * boxToWorld;
  glm::vec4 clip[8];
  for (int corner = 0; corner < 8; ++corner)
    clip[corner] = boxToClip * glm::vec4((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f,
                                         (corner & 4) ? 1.0f : -1.0f, 1.0f);
  // Outside the view volume: every corner beyond one of its planes (w +- x >= 0, w +- y >= 0, z >= 0, w - z >= 0).
  auto allBeyond = [&clip](auto distance) {
    return std::all_of(clip, clip + 8, [&distance](const glm::vec4& c) { return distance(c) < 0.0f; });
  };
  if (allBeyond([](glm::vec4 c) { return c.w + c.x; }) || allBeyond([](glm::vec4 c) { return c.w - c.x; }) ||
      allBeyond([](glm::vec4 c) { return c.w + c.y; }) || allBeyond([](glm::vec4 c) { return c.w - c.y; }) ||
      allBeyond([](glm::vec4 c) { return c.z; }) || allBeyond([](glm::vec4 c) { return c.w - c.z; }))
    return glm::uvec4(0);
  // The box's projection: the hull of its corners' projections while all lie ahead of the eye.
  glm::vec2 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec4& c : clip) {
    if (!(c.w > 1e-6f)) return all;  // reaches the eye plane: unbounded on screen
    const glm::vec2 pixel = (glm::vec2(c) / c.w * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
    lo = glm::min(lo, pixel);
    hi = glm::max(hi, pixel);
  }
  // A pixel of slack each side for rounding; tiles whose pixel centres fall in [lo, hi].
  auto tile = [](float pixel, std::uint32_t tiles) {
    return std::uint32_t(std::clamp(std::floor(pixel / float(S3D_TILE_SIZE)), 0.0f, float(tiles)));
  };
  const glm::uvec2 first(tile(lo.x - 1.0f, all.z), tile(lo.y - 1.0f, all.w));
  const glm::uvec2 last(tile(hi.x + 1.0f, all.z - 1) + 1, tile(hi.y + 1.0f, all.w - 1) + 1);
  if (hi.x + 1.0f < 0.0f || hi.y + 1.0f < 0.0f || lo.x - 1.0f > float(width) || lo.y - 1.0f > float(height))
    return glm::uvec4(0);
  return {first, glm::max(first, last)};
}

void TransparentPass::record(VkCommandBuffer cmd, const Inputs& in) {
  if (objects_.empty()) throw std::logic_error("transparent pass: recorded without transparent objects");
  // Back to front by the view depth of each object's origin (most negative view z = farthest).
  sorted_.clear();
  for (std::size_t i = 0; i < objects_.size(); ++i) sorted_.push_back({(in.worldView * objects_[i].origin).z, i});
  std::sort(sorted_.begin(), sorted_.end());
  if (usesCompute()) return recordCompute(cmd, in);
  drawOrder_.clear();
  for (const auto& entry : sorted_) drawOrder_.push_back(objects_[entry.second].index);
  recordRaster(cmd, in);
}

void TransparentPass::recordCompute(VkCommandBuffer cmd, const Inputs& in) {
  vk::transition(cmd, in.hdr, vk::kComputeWrite, kComputeReadWrite);
  vk::transition(cmd, coverage_, vk::kUndefined, kComputeReadWrite);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  VkDescriptorBufferInfo frameInfo{in.frameConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo objectInfo{in.objectConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo indexInfo{in.indices, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo vertexInfo{in.vertices, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo surfaceInfo{in.surfaces, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo depthInfo{nearest_, in.depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo hdrInfo{VK_NULL_HANDLE, in.hdr.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo coverageInfo{VK_NULL_HANDLE, coverage_.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo maskInfo{VK_NULL_HANDLE, in.shadeMask, VK_IMAGE_LAYOUT_GENERAL};
  const glm::uvec2 tiles(tilesFor(width_), tilesFor(height_));
  for (std::size_t i = 0; i < sorted_.size(); ++i) {
    const Object& object = objects_[sorted_[i].second];
    gpu::TransparentConstants constants{};
    constants.tileRect = tileRect(in.worldViewProjection, object.boxToWorld, width_, height_);
    constants.depthRange = in.depthRange;
    constants.objectIndex = object.index;
    constants.triangleCount = object.triangleCount;
    constants.reversedZ = in.reversedZ ? 1u : 0u;
    constants.initializesCoverage = i == 0 ? 1u : 0u;  // the farthest object's dispatch covers the whole image
    constants.masked = in.masked ? 1u : 0u;
    const glm::uvec2 groups = i == 0 ? tiles : glm::uvec2(constants.tileRect.z - constants.tileRect.x,
                                                          constants.tileRect.w - constants.tileRect.y);
    if (groups.x == 0 || groups.y == 0) continue;  // off screen
    if (i > 0) {
      vk::transition(cmd, in.hdr, kComputeReadWrite, kComputeReadWrite);
      vk::transition(cmd, coverage_, kComputeReadWrite, kComputeReadWrite);
    }
    VkDescriptorImageInfo baseColorInfo{in.textureSampler, object.baseColor, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo normalMapInfo{in.textureSampler, object.normalMap, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet writes[] = {
        vk::uniformBufferWrite(0, &frameInfo),   vk::uniformBufferWrite(1, &objectInfo),
        vk::uniformBufferWrite(2, &indexInfo),   vk::uniformBufferWrite(3, &vertexInfo),
        vk::uniformBufferWrite(4, &surfaceInfo), vk::sampledImageWrite(5, &depthInfo),
        vk::storageImageWrite(6, &hdrInfo),      vk::storageImageWrite(7, &coverageInfo),
        vk::sampledImageWrite(8, &baseColorInfo), vk::sampledImageWrite(9, &normalMapInfo),
        vk::storageImageWrite(10, &maskInfo)};
    for (std::uint32_t b : {1u, 2u, 3u, 4u}) writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    for (std::uint32_t b : {5u, 8u, 9u}) writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 11, writes);
    vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    vkCmdDispatch(cmd, groups.x, groups.y, 1);
  }
  vk::transition(cmd, in.hdr, kComputeReadWrite, vk::kComputeRead);
  vk::transition(cmd, coverage_, kComputeReadWrite, vk::kComputeWrite);
}

void TransparentPass::recordRaster(VkCommandBuffer cmd, const Inputs& in) {
  vk::transition(cmd, in.hdr, vk::kComputeWrite, vk::kColorAttachment);
  vk::transition(cmd, in.depth, kComputeSampled, kDepthReadOnlyAttachment);
  vk::transition(cmd, coverage_, vk::kUndefined, vk::kColorAttachment);
  VkRenderingAttachmentInfo colors[2]{};
  for (VkRenderingAttachmentInfo& color : colors) {
    color.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  }
  colors[0].imageView = in.hdr.view;
  colors[0].loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  colors[1].imageView = coverage_.view;
  colors[1].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // zero: no coverage
  VkRenderingAttachmentInfo depthInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthInfo.imageView = in.depth.view;
  depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  depthInfo.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {width_, height_}};
  info.layerCount = 1;
  info.colorAttachmentCount = 2;
  info.pColorAttachments = colors;
  info.pDepthAttachment = &depthInfo;
  vkCmdBeginRendering(cmd, &info);
  const VkRect2D scissor{{0, 0}, {width_, height_}};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, rasterPipeline_);
  in.drawObjects(cmd, drawOrder_);  // sets each layer's viewport
  vkCmdEndRendering(cmd);
  vk::transition(cmd, in.hdr, vk::kColorAttachment, vk::kComputeRead);
  vk::transition(cmd, in.depth, kDepthReadOnlyAttachment, kComputeSampled);
}

}  // namespace s3d::renderer::detail
