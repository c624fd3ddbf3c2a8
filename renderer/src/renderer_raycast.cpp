// DeferredRenderer's ray-cast surfaces (ShadeMask::Surfaces::RayCast): the BVH upload, when the path is refused,
// and the pass that stands in for the G-buffer's raster pass.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "deferred_renderer_impl.h"
#include "s3d/renderer/scene_bvh.h"

namespace s3d::renderer {

void DeferredRenderer::setSurfaceBvh(const SceneBvh& bvh) {
  Impl& r = *impl_;
  if (r.meshRanges.empty()) throw std::logic_error("DeferredRenderer::setSurfaceBvh called before setScene");
  if (!r.raycast) {
    r.raycast = std::make_unique<RaycastVisibility>(r.context);
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    r.raycastIds = vk::createImage(r.context, kNarrowVisibilityFormat, r.width, r.height, usage);
    r.raycastDepth = vk::createImage(r.context, VK_FORMAT_R32_SFLOAT, r.width, r.height, usage);
  }
  // A tree whose ids are packed otherwise than the scene's (wide ids, another scene) is not kept: renders refuse.
  r.raycastBvhCurrent = false;
  if (bvh.visibilityPacking != r.visibilityPacking) return;
  r.raycast->setBvh(bvh);
  r.raycastBvhCurrent = true;
  if (r.surfaceTexels.buffer == VK_NULL_HANDLE) r.uploadSurfaceTexels();
}

void DeferredRenderer::Impl::uploadSurfaceTexels() {
  std::vector<glm::uvec4> table;
  std::vector<std::uint8_t> texels;
  for (const Texture& texture : scene.textures) {
    table.push_back({std::uint32_t(texels.size() / 4), texture.width, texture.height,
                     texture.encoding == Texture::Encoding::Srgb ? 1u : 0u});
    texels.insert(texels.end(), texture.rgba.begin(), texture.rgba.end());
  }
  if (table.empty()) table.emplace_back(0u);  // buffers are never empty
  if (texels.empty()) texels.assign(4, 0);
  constexpr VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  surfaceTextureTable = vk::createBuffer(context, table.size() * sizeof(glm::uvec4), usage, vk::MemoryLocation::Device);
  vk::uploadBuffer(context, surfaceTextureTable, std::as_bytes(std::span(table)));
  surfaceTexels = vk::createBuffer(context, texels.size(), usage, vk::MemoryLocation::Device);
  vk::uploadBuffer(context, surfaceTexels, std::as_bytes(std::span(texels)));
}

void DeferredRenderer::recordRaycastPreparation(VkCommandBuffer cmd, const ViewMatrices& view,
                                                RaycastVisibility::PreparationStep step) {
  Impl& r = *impl_;
  if (!hasSurfaceBvh()) throw std::invalid_argument("ray-cast surfaces were prepared before the renderer had a BVH");
  r.raycast->recordPreparation(cmd, step, raycastCamera(r.scene, view, r.options.reversedZ), r.width, r.height);
  if (step == RaycastVisibility::PreparationStep::Setup) {  // the next masked render's tile reset (it reads the tile
    r.writeFrameConstants(view, ShadeMask{});                // grid from the frame constants, which it rewrites)
    r.tiles->recordMaskedResetAhead(cmd, r.frameBuffer.buffer);
    r.tilesResetAhead = true;
  }
}

std::optional<std::string> DeferredRenderer::raycastSurfacesRefusal() const { return impl_->raycastRefusal(); }
bool DeferredRenderer::hasSurfaceBvh() const { return impl_->raycast && impl_->raycastBvhCurrent; }

std::optional<std::string> DeferredRenderer::Impl::raycastRefusal() const {
  if (!visibilityShading) return "ray-cast surfaces need visibility G-buffer shading (the resolve shades them)";
  if (visibilityPacking.y != 0) return "ray-cast surfaces need narrow visibility ids; this scene needs wide ones";
  // Every texture's texels lie in one storage buffer (surface_texels.glsl), which one binding must span.
  std::uint64_t texelBytes = 0;
  for (const Texture& texture : scene.textures) texelBytes += texture.rgba.size();
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  if (texelBytes > properties.limits.maxStorageBufferRange)
    return "scene '" + scene.name + "' has " + std::to_string(texelBytes >> 20) + " MiB of texels, more than the " +
           std::to_string(properties.limits.maxStorageBufferRange >> 20) +
           " MiB storage buffer the ray-cast surfaces sample them from on this device";
  if (supersample != 1) return "ray-cast surfaces cast one ray per output pixel: no supersampling";
  if (transparentPass->hasObjects() && !transparentPass->usesCompute())
    return "scene '" + scene.name + "' has transparent objects that the raster pass blends (it needs the depth buffer)";
  return std::nullopt;
}

void DeferredRenderer::Impl::recordRaycastSurfaces(VkCommandBuffer cmd, const ViewMatrices& view, const ShadeMask& mask) {
  vk::transition(cmd, raycastIds, vk::kUndefined, vk::kComputeWrite);
  vk::transition(cmd, raycastDepth, vk::kUndefined, vk::kComputeWrite);
  // Ambient occlusion samples depth around the pixels it shades: with it, every pixel of its region (the masked
  // tiles and their neighbours, flagged by the mask-tiles pass) gets a surface, cast or (with an uncast depth, for
  // the unmasked ones) given, and samples beyond see no surface.
  const bool region = scene.ambientOcclusion && mask.image != nullptr;
  ShadeMask cast = mask;
  if (!scene.ambientOcclusion) cast.uncastDepth = nullptr;
  else if (mask.uncastDepth == nullptr) cast = ShadeMask{};
  raycast->record(cmd, raycastCamera(scene, view, options.reversedZ), cast, raycastIds, raycastDepth,
                  region ? RaycastRegion{tiles->buffer(), tiles->tilesX()} : RaycastRegion{},
                  RaycastCutouts{objectBuffer.buffer, indexBuffer.buffer, surfaceBuffer.buffer, surfaceTextureTable.buffer,
                                 surfaceTexels.buffer});
  vk::transition(cmd, raycastIds, vk::kComputeWrite, kComputeSampled);
  vk::transition(cmd, raycastDepth, vk::kComputeWrite, kComputeSampled);
}

}  // namespace s3d::renderer
