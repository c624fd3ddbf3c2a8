// DeferredRenderer's render targets, samplers, descriptor layouts and graphics pipelines: the G-buffer's per
// material variant and the depth-only ones made at first use.
#include <stdexcept>
#include <string>

#include "deferred_renderer_impl.h"
#include "s3d/vk/check.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/depth_cutout_frag.h>
#include <s3d_spirv/fullscreen_vert.h>
#include <s3d_spirv/gbuffer_cutout_frag.h>
#include <s3d_spirv/gbuffer_frag.h>
#include <s3d_spirv/gbuffer_marked_cutout_frag.h>
#include <s3d_spirv/gbuffer_marked_frag.h>
#include <s3d_spirv/geometry_vert.h>
#include <s3d_spirv/mask_fill_frag.h>
#include <s3d_spirv/shadow_depth_frag.h>
#include <s3d_spirv/visibility_frag.h>
#include <s3d_spirv/visibility_textured_frag.h>
// clang-format on

namespace s3d::renderer {
namespace {

// Material textures (section 4.3's "sRGB textures read as linear"): colour through an sRGB format, data not.
VkFormat textureFormat(Texture::Encoding encoding) {
  return encoding == Texture::Encoding::Srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
}

VkDescriptorSetLayoutBinding binding(std::uint32_t index, VkDescriptorType type, VkShaderStageFlags stages) {
  return {index, type, 1, stages, nullptr};
}

}  // namespace

DeferredRenderer::Impl::Impl(vk::Context& ctx, std::uint32_t w, std::uint32_t h, RendererOptions rendererOptions)
    : context(ctx),
      outputWidth(w),
      outputHeight(h),
      supersample(rendererOptions.supersample),
      width(w * rendererOptions.supersample),
      height(h * rendererOptions.supersample),
      options(rendererOptions),
      timestamps(ctx, kMaxPasses + 1) {
  if (options.supersample < 1 || options.supersample > 4)
    throw std::invalid_argument("renderer: supersample " + std::to_string(options.supersample) + " is outside 1..4");
  if (w == 0 || h == 0 || width > 16384 || height > 16384)
    throw std::invalid_argument("renderer: resolution " + std::to_string(w) + "x" + std::to_string(h) +
                                (supersample > 1 ? " at supersample " + std::to_string(supersample) : std::string()) +
                                " renders outside 1..16384");
  visibilityShading = options.gbufferShading == RendererOptions::GBufferShading::Visibility ||
                      (options.gbufferShading == RendererOptions::GBufferShading::Automatic && !context.isCpuDevice());
  surfaceTargetsBound = !visibilityShading;
  createTargets();
  createPipelines();
  shadows = std::make_unique<detail::ShadowMaps>(context, width, height);
  ambientOcclusion = std::make_unique<detail::AmbientOcclusion>(context, width, height, options.countShadedPixels);
  lighting = std::make_unique<detail::TiledLighting>(context, options.countShadedPixels);
  tiles = std::make_unique<detail::TileLists>(context, width, height);
  gbufferResolve = std::make_unique<detail::GBufferResolve>(context, options.countShadedPixels);
  vk::GraphicsPipelineDesc transparentGeometry = geometryDesc;
  transparentGeometry.depthCompare = nearer();
  transparentPass = std::make_unique<detail::TransparentPass>(context, width, height, options.transparentCompositing,
                                                              transparentGeometry, geometryLayout.layout);
  frameBuffer = vk::createBuffer(context, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                 vk::MemoryLocation::HostVisible);
}

void DeferredRenderer::Impl::createTargets() {
  const VkImageUsageFlags attachmentSampled =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  depth = vk::createImage(context, kDepthFormat, width, height,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  // Written by the raster pass (textured objects) and the G-buffer resolve (storage).
  normalGlossiness = vk::createImage(context, kNormalFormat, width, height, attachmentSampled | VK_IMAGE_USAGE_STORAGE_BIT);
  materialTarget = vk::createImage(context, kMaterialFormat, width, height, attachmentSampled | VK_IMAGE_USAGE_STORAGE_BIT);
  hdr = vk::createImage(context, kHdrFormat, width, height,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  const VkImageUsageFlags computeOutput = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  display = vk::createImage(context, kDisplayFormat, outputWidth, outputHeight, computeOutput);
  linearDepth = vk::createImage(context, kLinearDepthFormat, outputWidth, outputHeight, computeOutput);
  resolvedHdr = vk::createImage(context, kHdrFormat, outputWidth, outputHeight, computeOutput);

  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_NEAREST;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  samplerInfo.maxLod = 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateSampler(context.device(), &samplerInfo, nullptr, &sampler));
  nearestSampler = vk::Unique<VkSampler>(context.device(), sampler, vkDestroySampler);

  samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_LINEAR;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  S3D_VK_CHECK(vkCreateSampler(context.device(), &samplerInfo, nullptr, &sampler));
  textureSampler = vk::Unique<VkSampler>(context.device(), sampler, vkDestroySampler);
  whiteTexture = uploadTexture({1, 1, {255, 255, 255, 255}, Texture::Encoding::Srgb});
  flatNormalTexture = uploadTexture({1, 1, {128, 128, 255, 255}, Texture::Encoding::Linear});
}

vk::Image DeferredRenderer::Impl::uploadTexture(const Texture& texture) {
  vk::Image image = vk::createImage(context, textureFormat(texture.encoding), texture.width, texture.height,
                                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(context, image, std::as_bytes(std::span(texture.rgba)), vk::kFragmentRead);
  return image;
}

void DeferredRenderer::Impl::createPipelines() {
  constexpr VkShaderStageFlags graphics = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  constexpr VkDescriptorType ubo = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  constexpr VkShaderStageFlags fragment = VK_SHADER_STAGE_FRAGMENT_BIT;
  constexpr VkShaderStageFlags vertex = VK_SHADER_STAGE_VERTEX_BIT;
  const VkDescriptorSetLayoutBinding geometryBindings[] = {
      binding(0, ubo, graphics), binding(1, ssbo, graphics), binding(2, sampled, fragment), binding(3, sampled, fragment),
      binding(4, ssbo, vertex),  binding(5, ssbo, vertex),   binding(6, ssbo, vertex)};  // indices, vertices, surface
  geometryLayout = vk::createPushDescriptorLayout(context, geometryBindings, sizeof(std::uint32_t), graphics);
  const VkDescriptorSetLayoutBinding maskFillBindings[] = {binding(0, ubo, fragment), binding(1, storage, fragment)};
  maskFillLayout = vk::createPushDescriptorLayout(context, maskFillBindings, 0, 0);

  // Vertices are pulled from storage buffers (geometry.vert): no vertex input state.
  vk::GraphicsPipelineDesc geometry;
  geometry.vertexSpirv = spirv_geometry_vert;
  geometry.depthFormat = kDepthFormat;
  geometry.depthTest = true;
  geometry.cullMode = VK_CULL_MODE_BACK_BIT;
  geometryDesc = geometry;

  vk::GraphicsPipelineDesc depthOnly = geometry;  // the same vertex module: the same depth as the G-buffer
  depthOnly.fragmentSpirv = spirv_shadow_depth_frag;
  depthOnly.depthWrite = true;
  depthOnly.depthCompare = nearer();
  depthOnlyDesc = depthOnly;

  vk::GraphicsPipelineDesc maskFill;
  maskFill.vertexSpirv = spirv_fullscreen_vert;
  maskFill.fragmentSpirv = spirv_mask_fill_frag;
  maskFill.depthFormat = kDepthFormat;
  maskFill.depthTest = true;
  maskFill.depthWrite = true;
  maskFill.depthCompare = VK_COMPARE_OP_ALWAYS;
  maskFillPipeline = vk::createGraphicsPipeline(context, maskFillLayout.layout, maskFill);

  resolvePass = std::make_unique<detail::ResolvePass>(context, options.countShadedPixels);
}

std::vector<const vk::Image*> DeferredRenderer::Impl::gbufferAttachments() const {
  if (!visibilityShading) return {&normalGlossiness, &materialTarget};
  if (!surfaceTargetsBound) return {&visibility};
  return {&normalGlossiness, &materialTarget, &visibility};
}

VkPipeline DeferredRenderer::Impl::gbufferPipeline(std::size_t variant) {
  if (!gbufferPipelines[variant]) gbufferPipelines[variant] = createGBufferPipeline(variant);
  return gbufferPipelines[variant];
}

vk::Unique<VkPipeline> DeferredRenderer::Impl::createGBufferPipeline(std::size_t variant) const {
  vk::GraphicsPipelineDesc gbuffer = geometryDesc;
  gbuffer.depthWrite = true;
  gbuffer.depthCompare = nearer();
  gbuffer.colorFormats.clear();
  for (const vk::Image* image : gbufferAttachments()) gbuffer.colorFormats.push_back(image->format);
  if (variant == 0 && visibilityShading) {
    gbuffer.fragmentSpirv = surfaceTargetsBound ? std::span<const std::uint32_t>(spirv_visibility_textured_frag)
                                                : std::span<const std::uint32_t>(spirv_visibility_frag);
    return vk::createGraphicsPipeline(context, geometryLayout.layout, gbuffer);
  }
  const bool cutout = (variant & detail::kCutoutVariant) != 0;
  if ((variant & detail::kDoubleSidedVariant) != 0) gbuffer.cullMode = VK_CULL_MODE_NONE;
  if (visibilityShading)
    gbuffer.fragmentSpirv = cutout ? std::span<const std::uint32_t>(spirv_gbuffer_marked_cutout_frag)
                                   : std::span<const std::uint32_t>(spirv_gbuffer_marked_frag);
  else
    gbuffer.fragmentSpirv = cutout ? std::span<const std::uint32_t>(spirv_gbuffer_cutout_frag)
                                   : std::span<const std::uint32_t>(spirv_gbuffer_frag);
  auto on = [variant](std::size_t bit) -> VkBool32 { return (variant & bit) != 0 ? VK_TRUE : VK_FALSE; };
  const vk::SpecializationWords switches(
      {on(detail::kBaseColorVariant), on(detail::kNormalMapVariant), on(detail::kDoubleSidedVariant)});
  gbuffer.fragmentSpecialization = switches.info();
  return vk::createGraphicsPipeline(context, geometryLayout.layout, gbuffer);
}

VkPipeline DeferredRenderer::Impl::depthOnlyPipeline(std::size_t variant) {
  if (!depthOnlyPipelines[variant]) {
    vk::GraphicsPipelineDesc desc = depthOnlyDesc;
    if ((variant & 1) != 0) desc.fragmentSpirv = spirv_depth_cutout_frag;
    if ((variant & 2) != 0) desc.cullMode = VK_CULL_MODE_NONE;
    depthOnlyPipelines[variant] = vk::createGraphicsPipeline(context, geometryLayout.layout, desc);
  }
  return depthOnlyPipelines[variant];
}

}  // namespace s3d::renderer
