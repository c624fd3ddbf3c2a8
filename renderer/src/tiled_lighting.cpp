#include "tiled_lighting.h"

#include "compute_binding.h"


#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "s3d/renderer/renderer_shared.h"
#include "s3d/renderer/shadows.h"
#include "s3d/vk/check.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/light_tiles_comp.h>
#include <s3d_spirv/lighting_comp.h>
// clang-format on

namespace s3d::renderer::detail {
namespace {

static_assert(S3D_MAX_LIGHTS <= 256, "a tile's light list holds each light's index in one byte");
constexpr std::uint32_t kCpuClassifyThreads = 8, kGpuClassifyThreads = 64;
static_assert(S3D_TILE_SIZE * S3D_TILE_SIZE / kCpuClassifyThreads <= 32,
              "light_tiles.comp: a thread's pixels fit a bit mask");

using detail::computeBinding;

}  // namespace

TiledLighting::TiledLighting(vk::Context& context, bool counting) : context_(context) {
  constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  const VkDescriptorSetLayoutBinding bindings[] = {
      computeBinding(0, ubo),      computeBinding(1, sampled),  computeBinding(2, sampled), computeBinding(3, sampled),
      computeBinding(4, sampled),  computeBinding(5, sampled),  computeBinding(6, sampled), computeBinding(7, ubo),
      computeBinding(8, ssbo),     computeBinding(9, ssbo),     computeBinding(10, storage), computeBinding(11, ssbo),
      computeBinding(12, storage), computeBinding(13, storage), computeBinding(14, storage), computeBinding(15, storage)};
  layout_ = vk::createPushDescriptorLayout(context_, bindings, sizeof(gpu::LightingConstants), VK_SHADER_STAGE_COMPUTE_BIT);
  pipelines_ = std::make_unique<TilePipelines>(context_, layout_.layout, spirv_lighting_comp, counting);
  const VkDescriptorSetLayoutBinding classifyBindings[] = {computeBinding(0, ubo), computeBinding(1, sampled),
                                                           computeBinding(2, ssbo), computeBinding(3, ssbo),
                                                           computeBinding(4, storage)};
  classifyLayout_ = vk::createPushDescriptorLayout(context_, classifyBindings, sizeof(gpu::LightingConstants),
                                                   VK_SHADER_STAGE_COMPUTE_BIT);
  // The classification's threads per tile: on a CPU rasterizer one SIMD vector (it pays per invocation and per
  // barrier, and runs shared atomics lane by lane), on a GPU enough to fill its wide warps.
  const std::uint32_t classifyThreads = context_.isCpuDevice() ? kCpuClassifyThreads : kGpuClassifyThreads;
  classifyPipelines_ = std::make_unique<TilePipelines>(context_, classifyLayout_.layout, spirv_light_tiles_comp, false,
                                                       std::vector<std::uint32_t>{classifyThreads});
  nearest_ = vk::createNearestClampSampler(context_);
  setScene(Scene{});
}

void TiledLighting::setScene(const Scene& scene) {
  const std::size_t count = scene.pointLights.size() + scene.spotLights.size();
  if (count > S3D_MAX_LIGHTS)
    throw std::invalid_argument("scene '" + scene.name + "' has " + std::to_string(count) +
                                " point and spot lights, more than " + std::to_string(S3D_MAX_LIGHTS));
  const VkDeviceSize bytes = std::max<std::size_t>(1, count) * sizeof(gpu::LightConstants);
  if (lights_.size < bytes)
    lights_ = vk::createBuffer(context_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryLocation::HostVisible);
}

void TiledLighting::prepareFrame(const Scene& scene, const ViewMatrices& view, const ShadowMaps& shadows) {
  const glm::mat4 viewProjection = view.worldProjection * view.worldView;
  std::vector<gpu::LightConstants> shadowed, unshadowed;
  auto add = [&](const glm::vec3& position, const glm::vec3& color, float radius, std::uint32_t kind, int shadowView)
      -> gpu::LightConstants* {
    if (!sphereTouchesFrustum(viewProjection, {position, radius})) return nullptr;
    gpu::LightConstants light{};
    light.positionRadius = glm::vec4(position, radius);
    light.viewPosition = view.worldView * glm::vec4(position, 1.0f);
    light.color = glm::vec4(color, 0.0f);
    light.kind = kind;
    light.shadowView = shadowView;
    std::vector<gpu::LightConstants>& list = shadowView >= 0 ? shadowed : unshadowed;
    list.push_back(light);
    return &list.back();
  };
  for (std::size_t i = 0; i < scene.pointLights.size(); ++i) {
    const PointLight& point = scene.pointLights[i];
    add(point.position, point.color, point.radius, S3D_LIGHT_POINT, shadows.pointLightShadowView(i));
  }
  for (std::size_t i = 0; i < scene.spotLights.size(); ++i) {
    const SpotLight& spot = scene.spotLights[i];
    if (gpu::LightConstants* light =
            add(spot.position, spot.color, spot.radius, S3D_LIGHT_SPOT, shadows.spotLightShadowView(i))) {
      light->spotDirection = glm::vec4(glm::normalize(spot.direction), 0.0f);
      light->spotCone = glm::vec4(std::cos(spot.outerConeRadians), std::cos(spot.innerConeRadians), 0.0f, 0.0f);
    }
  }
  auto* out = static_cast<gpu::LightConstants*>(lights_.mapped);
  std::copy(shadowed.begin(), shadowed.end(), out);
  std::copy(unshadowed.begin(), unshadowed.end(), out + shadowed.size());
  shadowedLightCount_ = std::uint32_t(shadowed.size());
  lightCount_ = std::uint32_t(shadowed.size() + unshadowed.size());
  sunShadowed_ = shadows.sunShadowed();
}

void TiledLighting::record(VkCommandBuffer cmd, const Inputs& in, const ShadowMaps& shadows, const Outputs& out) {
  for (const vk::Image* image : {&out.hdr, &out.resolvedHdr, &out.linearDepth})
    vk::transition(cmd, *image, vk::kUndefined, vk::kComputeWrite);
  vk::transition(cmd, out.display, out.displayKeepsUnshaded ? vk::kComputeWrite : vk::kUndefined, vk::kComputeWrite);
  VkDescriptorBufferInfo frameInfo{in.frameConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo depthInfo{nearest_, in.depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo normalInfo{nearest_, in.normalGlossiness.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo materialInfo{nearest_, in.material.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo occlusionInfo = in.ambientOcclusion;
  VkDescriptorImageInfo sunInfo = shadows.sunAtlasDescriptor();
  VkDescriptorImageInfo localInfo = shadows.localAtlasDescriptor();
  VkDescriptorBufferInfo shadowInfo = shadows.constantsDescriptor();
  VkDescriptorBufferInfo objectInfo{in.objectConstants, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo lightInfo{lights_.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo hdrInfo{VK_NULL_HANDLE, out.hdr.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo displayInfo{VK_NULL_HANDLE, out.display.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo resolvedInfo{VK_NULL_HANDLE, out.resolvedHdr.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorImageInfo linearInfo{VK_NULL_HANDLE, out.linearDepth.view, VK_IMAGE_LAYOUT_GENERAL};
  VkDescriptorBufferInfo tileInfo{in.tiles, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo maskInfo = in.shadeMask;
  VkWriteDescriptorSet writes[] = {
      vk::uniformBufferWrite(0, &frameInfo), vk::sampledImageWrite(1, &depthInfo),  vk::sampledImageWrite(2, &normalInfo),
      vk::sampledImageWrite(3, &materialInfo), vk::sampledImageWrite(4, &occlusionInfo), vk::sampledImageWrite(5, &sunInfo),
      vk::sampledImageWrite(6, &localInfo),  vk::uniformBufferWrite(7, &shadowInfo), vk::uniformBufferWrite(8, &objectInfo),
      vk::uniformBufferWrite(9, &lightInfo), vk::storageImageWrite(10, &hdrInfo),  vk::uniformBufferWrite(11, &tileInfo),
      vk::storageImageWrite(12, &maskInfo),  vk::storageImageWrite(13, &displayInfo), vk::storageImageWrite(14, &resolvedInfo),
      vk::storageImageWrite(15, &linearInfo)};
  for (std::uint32_t i = 1; i <= 6; ++i) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  for (std::uint32_t i : {8u, 9u, 11u}) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  const gpu::LightingConstants constants{lightCount_, shadowedLightCount_, 0, 0};

  // Classification: each tile's light list and class list (a masked render: its listed tiles).
  VkWriteDescriptorSet classifyWrites[] = {vk::uniformBufferWrite(0, &frameInfo), vk::sampledImageWrite(1, &depthInfo),
                                           vk::uniformBufferWrite(2, &lightInfo), vk::uniformBufferWrite(3, &tileInfo),
                                           vk::storageImageWrite(4, &maskInfo)};
  classifyWrites[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  for (std::uint32_t i : {2u, 3u}) classifyWrites[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyPipelines_->get(in.masked));
  context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyLayout_.layout, 0, 5, classifyWrites);
  vkCmdPushConstants(cmd, classifyLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
  if (in.masked)
    vkCmdDispatchIndirect(cmd, in.tiles, TileLists::kMaskedTilesDispatch);
  else
    vkCmdDispatch(cmd, in.tilesX, in.tilesY, 1);
  TileLists::recordListsVisible(cmd);

  // Shading: one variant per class over the class's tiles (the variants share the layout, so the descriptors
  // and constants pushed once serve them all).
  for (std::uint32_t tileClass = 0; tileClass < S3D_TILE_CLASSES; ++tileClass) {
    const bool shadowedLights = tileClass == S3D_TILE_LIT_SHADOWED;
    if (shadowedLights && shadowedLightCount_ == 0) continue;  // no tile can be in that class this frame
    const bool sky = tileClass == S3D_TILE_SKY, lit = tileClass == S3D_TILE_LIT || shadowedLights;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                      pipelines_->get(in.masked, {sunShadowed_, shadowedLights, out.resolveInPlace, sky, lit}));
    if (tileClass == 0) {
      context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 16, writes);
      vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    }
    vkCmdDispatchIndirect(cmd, in.tiles, TileLists::tileClassDispatch(tileClass));
  }
}

}  // namespace s3d::renderer::detail
