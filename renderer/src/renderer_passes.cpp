// The recording of DeferredRenderer's passes: the frame constants, the geometry draws, the mask's depth fill, the
// G-buffer and its resolve, the ambient-occlusion depth, lighting, the transparent pass and the resolve.
#include <algorithm>
#include <cstring>
#include <optional>
#include <span>

#include <glm/gtc/matrix_transform.hpp>

#include "deferred_renderer_impl.h"

namespace s3d::renderer {
namespace {

// Descriptor binding of an object's base-color texture in the passes that draw geometry (normal map: the next).
constexpr std::uint32_t kGeometryTextureBinding = 2;

VkRenderingAttachmentInfo colorAttachment(const vk::Image& image, bool clear, VkClearColorValue clearValue = {}) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = image.view;
  info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  info.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  info.clearValue.color = clearValue;
  return info;
}

VkRenderingAttachmentInfo depthAttachment(const vk::Image& depth, VkAttachmentLoadOp load, float clearDepth) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = depth.view;
  info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  info.loadOp = load;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  info.clearValue.depthStencil = {clearDepth, 0};
  return info;
}

void beginRendering(VkCommandBuffer cmd, std::uint32_t width, std::uint32_t height,
                    std::span<const VkRenderingAttachmentInfo> colors, const VkRenderingAttachmentInfo* depth) {
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {width, height}};
  info.layerCount = 1;
  info.colorAttachmentCount = static_cast<std::uint32_t>(colors.size());
  info.pColorAttachments = colors.data();
  info.pDepthAttachment = depth;
  vkCmdBeginRendering(cmd, &info);
}

void setViewport(VkCommandBuffer cmd, std::uint32_t width, std::uint32_t height, float minDepth, float maxDepth) {
  VkViewport viewport{0.0f, 0.0f, float(width), float(height), minDepth, maxDepth};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
}

void setScissor(VkCommandBuffer cmd, VkRect2D rect) { vkCmdSetScissor(cmd, 0, 1, &rect); }

glm::vec4 projectionTerms(const glm::mat4& projection) {
  return {projection[0][0], projection[1][1], projection[2][0], projection[2][1]};
}

}  // namespace

glm::vec2 DeferredRenderer::Impl::layerDepthRange(Layer layer) const {
  const bool firstPerson = layer == Layer::FirstPerson;
  if (options.reversedZ)
    return {firstPerson ? 1.0f - kFirstPersonDeviceDepthMax : 0.0f, firstPerson ? 1.0f : 1.0f - kFirstPersonDeviceDepthMax};
  return {firstPerson ? 0.0f : kFirstPersonDeviceDepthMax, firstPerson ? kFirstPersonDeviceDepthMax : 1.0f};
}

void DeferredRenderer::Impl::setLayerViewport(VkCommandBuffer cmd, Layer layer) const {
  const glm::vec2 range = layerDepthRange(layer);
  setViewport(cmd, width, height, range.x, range.y);
}

void DeferredRenderer::Impl::writeFrameConstants(const ViewMatrices& view, const ShadeMask& mask) {
  gpu::FrameConstants frame{};
  gpu::LayerConstants& world = frame.layers[S3D_LAYER_WORLD];
  // Reversed-Z swaps near and far in both layers' projections (the caller's matrices stay standard).
  const glm::mat4 worldProjection =
      options.reversedZ ? reversedDepthProjection(view.worldProjection, scene.camera.nearPlane, scene.camera.farPlane)
                        : view.worldProjection;
  const glm::mat4 firstPersonProjection =
      options.reversedZ ? reversedDepthProjection(view.firstPersonProjection, scene.firstPerson.nearPlane,
                                                  scene.firstPerson.farPlane)
                        : view.firstPersonProjection;
  world.viewProjection = worldProjection * view.worldView;
  world.worldFromView = glm::inverse(view.worldView);
  world.projection = projectionTerms(worldProjection);
  gpu::LayerConstants& firstPerson = frame.layers[S3D_LAYER_FIRST_PERSON];
  firstPerson.viewProjection = firstPersonProjection * view.firstPersonView;
  firstPerson.worldFromView = view.worldFromCamera * glm::inverse(view.firstPersonView);
  firstPerson.projection = projectionTerms(firstPersonProjection);
  frame.linearDepth = (options.reversedZ ? gpu::makeReversedLinearDepthParams : gpu::makeLinearDepthParams)(
      scene.camera.nearPlane, scene.camera.farPlane, scene.firstPerson.nearPlane, scene.firstPerson.farPlane,
      kFirstPersonDeviceDepthMax);
  frame.linearDepth.firstPersonDepthOffset = view.firstPersonDepthPush.offset;
  frame.linearDepth.firstPersonDepthScale = view.firstPersonDepthPush.scale;
  frame.directionToSun = glm::vec4(glm::normalize(scene.sun.directionToSun), 0.0f);
  frame.sunColor = glm::vec4(scene.sun.color, 0.0f);
  frame.ambientColor = glm::vec4(scene.ambientColor, 0.0f);
  frame.skyZenith = glm::vec4(scene.sky.zenithColor, 0.0f);
  frame.skyHorizon = glm::vec4(scene.sky.horizonColor, 0.0f);
  frame.skyGround = glm::vec4(scene.sky.groundColor, 0.0f);
  frame.screen = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
  frame.exposure = glm::vec4(scene.exposure, 0.0f, 0.0f, 0.0f);
  frame.ambientOcclusion = glm::vec4(scene.ambientOcclusionRadius, float(ambientOcclusion->width()),
                                     float(ambientOcclusion->height()), 0.0f);
  frame.worldViewDepth = -glm::vec4(view.worldView[0][2], view.worldView[1][2], view.worldView[2][2], view.worldView[3][2]);
  frame.tiles = glm::uvec4(tiles->tilesX(), tiles->tilesY(), mask.threshold, 0u);
  frame.options = glm::uvec4(supersample, scene.ambientOcclusion ? 1u : 0u, visibilityPacking.x, visibilityPacking.y);
  std::memcpy(frameBuffer.mapped, &frame, sizeof(frame));

  auto* objects = static_cast<gpu::ObjectConstants*>(objectBuffer.mapped);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    gpu::ObjectConstants& constants = objects[i];
    constants = {};
    constants.objectToLayer = object.transform;
    constants.objectToWorld = object.layer == Layer::FirstPerson ? view.worldFromCamera * object.transform : object.transform;
    constants.normalToWorld = glm::transpose(glm::inverse(constants.objectToWorld));
    const Material& material = object.material;
    constants.albedo = glm::vec4(material.albedo, material.isCutout() ? material.cutoutAlpha : material.opacity);
    constants.specular = glm::vec4(object.material.specularColor, object.material.glossiness);
    constants.layer = object.layer == Layer::FirstPerson ? S3D_LAYER_FIRST_PERSON : S3D_LAYER_WORLD;
    constants.normalScale = object.material.normalTexture == kNoTexture ? 0.0f : object.material.normalScale;
    constants.firstIndex = meshRanges[object.mesh].firstIndex;
    constants.vertexOffset = std::uint32_t(meshRanges[object.mesh].vertexOffset);
    const glm::mat3 base = material.baseColorTransform.matrix(), normal = material.normalTransform.matrix();
    constants.baseColorUv = glm::vec4(base[0][0], base[1][0], base[0][1], base[1][1]);  // rows of the 2x2 part
    constants.normalUv = glm::vec4(normal[0][0], normal[1][0], normal[0][1], normal[1][1]);
    constants.uvOffsets = glm::vec4(base[2][0], base[2][1], normal[2][0], normal[2][1]);
    constants.emissive = glm::vec4(material.emissive, material.alphaCutoff);
    auto textureSlot = [](std::int32_t index) { return index == kNoTexture ? S3D_NO_TEXTURE : std::uint32_t(index); };
    constants.surfaceTextures = glm::uvec4(textureSlot(material.baseColorTexture), textureSlot(material.normalTexture),
                                           material.doubleSided ? 1u : 0u, 0u);
  }
}

void DeferredRenderer::Impl::pushGeometryDescriptors(VkCommandBuffer cmd, const Material& material) {
  const VkPipelineLayout layout = geometryLayout.layout;
  const std::uint32_t textureBinding = kGeometryTextureBinding;
  VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo objectInfo{objectBuffer.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo indexInfo{indexBuffer.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo vertexInfo{vertexBuffer.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorBufferInfo surfaceInfo{surfaceBuffer.buffer, 0, VK_WHOLE_SIZE};
  std::vector<VkWriteDescriptorSet> writes = {vk::uniformBufferWrite(0, &frameInfo), vk::uniformBufferWrite(1, &objectInfo),
                                              vk::uniformBufferWrite(4, &indexInfo), vk::uniformBufferWrite(5, &vertexInfo),
                                              vk::uniformBufferWrite(6, &surfaceInfo)};
  for (VkWriteDescriptorSet& write : writes)
    if (write.dstBinding != 0) write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  auto view = [this](std::int32_t index, const vk::Image& fallback) -> VkImageView {
    return index == kNoTexture ? fallback.view : textures[std::size_t(index)].view;
  };
  VkDescriptorImageInfo baseColorInfo{textureSampler, view(material.baseColorTexture, whiteTexture),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorImageInfo normalInfo{textureSampler, view(material.normalTexture, flatNormalTexture),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  for (const VkDescriptorImageInfo* info : {&baseColorInfo, &normalInfo}) {
    writes.push_back(vk::sampledImageWrite(textureBinding + std::uint32_t(info == &normalInfo), info));
    writes.back().descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, std::uint32_t(writes.size()), writes.data());
}

void DeferredRenderer::Impl::drawObjects(VkCommandBuffer cmd, const std::vector<std::uint32_t>& objects, Pipelines pipelines) {
  std::optional<Layer> currentLayer;
  std::optional<std::size_t> currentVariant;
  for (std::uint32_t objectIndex : objects) {
    const Object& object = scene.objects[objectIndex];
    if (pipelines != Pipelines::Bound) {
      const bool gbuffer = pipelines == Pipelines::GBuffer;
      const std::size_t variant = gbuffer ? detail::materialVariant(object.material) : detail::depthVariant(object.material);
      if (currentVariant != variant)
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gbuffer ? gbufferPipeline(variant) : depthOnlyPipeline(variant));
      currentVariant = variant;
    }
    if (currentLayer != object.layer) {
      setLayerViewport(cmd, object.layer);
      currentLayer = object.layer;
    }
    pushGeometryDescriptors(cmd, object.material);  // per object: its textures
    vkCmdPushConstants(cmd, geometryLayout.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(std::uint32_t), &objectIndex);
    // Non-indexed: geometry.vert reads the index itself (gl_VertexIndex runs over the mesh's index range).
    const MeshRange& range = meshRanges[object.mesh];
    vkCmdDraw(cmd, range.indexCount, 1, range.firstIndex, 0);
  }
}

void DeferredRenderer::Impl::sortFrontToBack(const ViewMatrices& view) {
  drawKeys.clear();
  for (std::size_t i = 0; i < drawOrder.size(); ++i) {
    const bool world = scene.objects[drawOrder[i]].layer == Layer::World;
    const glm::vec4 center = (world ? view.worldView : view.firstPersonView) * glm::vec4(drawBounds[i].center, 1.0f);
    drawKeys.push_back({world, glm::length(glm::vec3(center)) - drawBounds[i].radius, drawOrder[i]});
  }
  std::sort(drawKeys.begin(), drawKeys.end(), [](const DrawKey& a, const DrawKey& b) {
    return a.world != b.world ? b.world : a.distance != b.distance ? a.distance < b.distance : a.object < b.object;
  });
  frontToBack.clear();
  for (const DrawKey& key : drawKeys) frontToBack.push_back(key.object);
}

void DeferredRenderer::Impl::recordMaskDepthFill(VkCommandBuffer cmd, const ShadeMask& mask, VkAttachmentLoadOp loadOp) {
  const VkRenderingAttachmentInfo fillDepth = depthAttachment(depth, loadOp, clearedDepth());
  beginRendering(cmd, width, height, {}, &fillDepth);
  setViewport(cmd, width, height, nearestDepth(), nearestDepth());
  setScissor(cmd, {{0, 0}, {width, height}});
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, maskFillPipeline);
  VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo maskInfo = tiles->maskDescriptor(mask.image);
  VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo), vk::storageImageWrite(1, &maskInfo)};
  context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, maskFillLayout.layout, 0, 2, writes);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRendering(cmd);
  vk::transition(cmd, depth, vk::kDepthAttachment, vk::kDepthAttachment);
}

void DeferredRenderer::Impl::recordGBuffer(VkCommandBuffer cmd, const ShadeMask& mask) {
  vk::transition(cmd, depth, vk::kUndefined, vk::kDepthAttachment);
  const bool filled = mask.image != nullptr && !maskedGBufferWritesEveryPixel();
  if (filled) recordMaskDepthFill(cmd, mask, VK_ATTACHMENT_LOAD_OP_CLEAR);
  // Raster shading clears normal and material (sky and masked-out pixels keep the cleared values); under
  // visibility shading the G-buffer resolve writes every pixel later passes read, so nothing is cleared.
  const VkClearColorValue noMaterial{.uint32 = {0, S3D_NO_OBJECT << 16, 0, 0}};
  std::vector<VkRenderingAttachmentInfo> colors;
  for (const vk::Image* image : gbufferAttachments()) {
    colors.push_back(colorAttachment(*image, !visibilityShading, image == &materialTarget ? noMaterial : VkClearColorValue{}));
    if (visibilityShading) colors.back().loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    vk::transition(cmd, *image, vk::kUndefined, vk::kColorAttachment);
  }
  const VkRenderingAttachmentInfo depthInfo =
      depthAttachment(depth, filled ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR, clearedDepth());
  beginRendering(cmd, width, height, colors, &depthInfo);
  setScissor(cmd, {{0, 0}, {width, height}});
  drawObjects(cmd, frontToBack, Pipelines::GBuffer);
  vkCmdEndRendering(cmd);
  // Ambient occlusion, lighting and the resolve read depth; the G-buffer resolve reads the ids, lighting (and
  // the counting pass) the targets the raster pass wrote.
  vk::transition(cmd, depth, vk::kDepthAttachment, kComputeSampled);
  if (visibilityShading) {
    vk::transition(cmd, visibility, vk::kColorAttachment, kComputeSampled);
  } else {
    vk::transition(cmd, normalGlossiness, vk::kColorAttachment, kComputeSampled);
    vk::transition(cmd, materialTarget, vk::kColorAttachment, kComputeSampled);
  }
}

void DeferredRenderer::Impl::recordGBufferResolve(VkCommandBuffer cmd, const ShadeMask& mask) {
  const detail::GBufferResolve::Inputs inputs{frameDepth(),
                                              frameVisibility(),
                                              frameBuffer.buffer,
                                              objectBuffer.buffer,
                                              indexBuffer.buffer,
                                              vertexBuffer.buffer,
                                              tiles->buffer(),
                                              tiles->maskDescriptor(mask.image),
                                              mask.image != nullptr,
                                              tiles->tilesX(),
                                              tiles->tilesY(),
                                              surfaceBuffer.buffer,
                                              raycastFrame ? surfaceTextureTable.buffer : objectBuffer.buffer,
                                              raycastFrame ? surfaceTexels.buffer : objectBuffer.buffer,
                                              raycastFrame && surfaceTargetsBound};
  // Ray-cast surfaces run no raster pass: the resolve shades textured and double-sided objects itself.
  gbufferResolve->record(cmd, inputs, normalGlossiness, materialTarget,
                         surfaceTargetsBound && !raycastFrame ? vk::kColorAttachment : vk::kUndefined);
}

void DeferredRenderer::Impl::recordAmbientDepth(VkCommandBuffer cmd) {
  if (ambientDepth.width == 0)  // first use; kept for later frames
    ambientDepth = vk::createImage(context, kDepthFormat, width, height,
                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  vk::transition(cmd, ambientDepth, vk::kUndefined, vk::kDepthAttachment);
  const VkRenderingAttachmentInfo depthInfo = depthAttachment(ambientDepth, VK_ATTACHMENT_LOAD_OP_CLEAR, clearedDepth());
  beginRendering(cmd, width, height, {}, &depthInfo);
  setScissor(cmd, {{0, 0}, {width, height}});
  drawObjects(cmd, frontToBack, Pipelines::DepthOnly);
  vkCmdEndRendering(cmd);
  vk::transition(cmd, ambientDepth, vk::kDepthAttachment, kComputeSampled);
}

void DeferredRenderer::Impl::recordLighting(VkCommandBuffer cmd, const ShadeMask& mask, const detail::ShadowMaps& frameShadows) {
  if (&frameShadows == shadows.get()) shadows->recordReadableForLighting(cmd);
  if (!scene.ambientOcclusion) ambientOcclusion->recordUnused(cmd);
  const detail::TiledLighting::Inputs inputs{frameDepth(),
                                             normalGlossiness,
                                             materialTarget,
                                             ambientOcclusion->result(),
                                             frameBuffer.buffer,
                                             objectBuffer.buffer,
                                             tiles->buffer(),
                                             tiles->maskDescriptor(mask.image),
                                             mask.image != nullptr,
                                             tiles->tilesX(),
                                             tiles->tilesY()};
  const bool keepsUnshaded = mask.displayTarget != nullptr;
  lighting->record(cmd, inputs, frameShadows,
                   {hdr, displayOutput(mask), resolvedHdr, linearDepth, resolveInLighting(), keepsUnshaded});
}

void DeferredRenderer::Impl::recordTransparent(VkCommandBuffer cmd, const ViewMatrices& view, const ShadeMask& mask) {
  const detail::TransparentPass::Inputs inputs{
      frameDepth(), hdr, frameBuffer.buffer, objectBuffer.buffer, indexBuffer.buffer, vertexBuffer.buffer, surfaceBuffer.buffer,
      textureSampler, view.worldView, view.worldProjection * view.worldView, layerDepthRange(Layer::World),
      options.reversedZ, tiles->maskDescriptor(mask.image).imageView, mask.image != nullptr,
      [this](VkCommandBuffer drawCmd, const std::vector<std::uint32_t>& objects) { drawObjects(drawCmd, objects); }};
  transparentPass->record(cmd, inputs);
}

void DeferredRenderer::Impl::recordResolve(VkCommandBuffer cmd, const ShadeMask& mask, bool afterTransparent) {
  const detail::ResolvePass::Inputs inputs{hdr,
                                           !afterTransparent,
                                           frameDepth(),
                                           frameBuffer.buffer,
                                           tiles->buffer(),
                                           tiles->maskDescriptor(mask.image),
                                           mask.image != nullptr,
                                           supersample,
                                           outputWidth,
                                           outputHeight};
  resolvePass->record(cmd, inputs, {displayOutput(mask), resolvedHdr, linearDepth});
}

}  // namespace s3d::renderer
