#include "s3d/renderer/deferred_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "s3d/renderer/renderer_shared.h"
#include "ambient_occlusion.h"
#include "gbuffer_resolve.h"
#include "material_variants.h"
#include "resolve_pass.h"
#include "s3d/vk/check.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/timestamps.h"
#include "shadow_maps.h"
#include "tile_lists.h"
#include "tiled_lighting.h"
#include "transparent_pass.h"

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

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // world normal + glossiness
constexpr VkFormat kMaterialFormat = VK_FORMAT_R32G32_UINT;        // packed albedo (gpu::packAlbedo), object index
constexpr VkFormat kNarrowVisibilityFormat = VK_FORMAT_R32_UINT;   // gpu::packVisibility, narrow ids
constexpr VkFormat kWideVisibilityFormat = VK_FORMAT_R32G32_UINT;  // wide ids: object, triangle
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;     // sRGB-encoded by the tone-map pass
constexpr VkFormat kLinearDepthFormat = VK_FORMAT_R32_SFLOAT;

// Material textures (section 4.3's "sRGB textures read as linear"): colour through an sRGB format, data not.
VkFormat textureFormat(Texture::Encoding encoding) {
  return encoding == Texture::Encoding::Srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
}
// Descriptor binding of an object's base-color texture in the passes that draw geometry (normal map: the next).
constexpr std::uint32_t kGeometryTextureBinding = 2;

// The G-buffer's targets once drawn: sampled by compute (ambient occlusion, lighting, resolve, counting).
constexpr vk::ImageState kComputeSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

// Timestamps: one before the first pass and one after each (shadow maps: up to 52 passes, the rest up to 9).
constexpr std::uint32_t kMaxPasses = 64;

VkDescriptorSetLayoutBinding binding(std::uint32_t index, VkDescriptorType type, VkShaderStageFlags stages) {
  return {index, type, 1, stages, nullptr};
}

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

struct MeshRange {
  std::uint32_t firstIndex = 0;
  std::uint32_t indexCount = 0;
  std::int32_t vertexOffset = 0;
};

}  // namespace

struct DeferredRenderer::Impl {
  vk::Context& context;
  std::uint32_t outputWidth;   // display colour, linear depth, resolved HDR
  std::uint32_t outputHeight;
  std::uint32_t supersample;   // every pass before the resolve runs at supersample x the output size
  std::uint32_t width;         // render size of those passes
  std::uint32_t height;
  RendererOptions options;

  // Render targets (render size), then the resolve's outputs (output size).
  vk::Image depth, normalGlossiness, materialTarget, hdr;
  vk::Image visibility;           // the G-buffer pass's ids (gpu::packVisibility), sized with the scene's ids
  vk::Image ambientDepth;         // masked renders with ambient occlusion: depth of every pixel (made at first use)
  vk::Image display, linearDepth, resolvedHdr;
  vk::Unique<VkSampler> nearestSampler;
  vk::Unique<VkSampler> textureSampler;  // bilinear, repeating, no mipmaps
  vk::Image whiteTexture, flatNormalTexture;  // what untextured objects sample: albedo x 1, normal (0, 0, 1)

  // Passes: layouts and pipelines (the compute passes own theirs: detail::AmbientOcclusion, TiledLighting,
  // TileLists, ShadowMaps).
  vk::PipelineLayout geometryLayout, maskFillLayout;
  // G-buffer: one pipeline per material variant (detail::materialVariant), made at first use for the scene's
  // visibility format and whether it has objects the raster pass shades (then the pass also binds normal and
  // material); dropped when those change.
  std::array<vk::Unique<VkPipeline>, detail::kMaterialVariants> gbufferPipelines;
  vk::GraphicsPipelineDesc geometryDesc;  // what every pipeline drawing the scene's objects shares
  glm::uvec2 visibilityPacking{0, 0};      // gpu::FrameConstants::options z, w
  bool visibilityShading = false;          // RendererOptions::gbufferShading, Automatic resolved for the device
  bool surfaceTargetsBound = false;        // the G-buffer pass writes normal and material for some objects
  bool gbufferPipelinesValid = false;
  vk::Unique<VkPipeline> maskFillPipeline;
  vk::GraphicsPipelineDesc depthOnlyDesc;  // depth-only passes, per detail::depthVariant (made at first use)
  std::array<vk::Unique<VkPipeline>, detail::kDepthVariants> depthOnlyPipelines;

  // Scene data.
  Scene scene;
  vk::Buffer vertexBuffer, surfaceBuffer, indexBuffer, objectBuffer, frameBuffer;
  std::vector<vk::Image> textures;  // Scene::textures, uploaded
  std::vector<MeshRange> meshRanges;
  std::vector<std::uint32_t> drawOrder;          // opaque object indices, first-person layer first
  std::vector<BoundingSphere> drawBounds;        // their bounds in their layer's space, same order
  struct DrawKey {
    bool world;      // first-person objects first
    float distance;  // from the layer's eye to the nearest point of the object's bounds
    std::uint32_t object;
  };
  std::vector<DrawKey> drawKeys;             // per frame, kept for its capacity
  std::vector<std::uint32_t> frontToBack;    // per frame: drawOrder sorted nearest first

  vk::TimestampQueries timestamps;
  std::unique_ptr<detail::ShadowMaps> shadows;  // sun cascades, point/spot shadow maps (shadow_maps.cpp)
  std::unique_ptr<detail::AmbientOcclusion> ambientOcclusion;
  std::unique_ptr<detail::TiledLighting> lighting;
  std::unique_ptr<detail::TileLists> tiles;
  std::unique_ptr<detail::GBufferResolve> gbufferResolve;
  std::unique_ptr<detail::ResolvePass> resolvePass;
  std::unique_ptr<detail::TransparentPass> transparentPass;

  Impl(vk::Context& ctx, std::uint32_t w, std::uint32_t h, RendererOptions rendererOptions)
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

  void createTargets() {
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

  vk::Image uploadTexture(const Texture& texture) {
    vk::Image image = vk::createImage(context, textureFormat(texture.encoding), texture.width, texture.height,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(context, image, std::as_bytes(std::span(texture.rgba)), vk::kFragmentRead);
    return image;
  }

  void createPipelines() {
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

  // The G-buffer pass's colour attachments (0 normal/glossiness, 1 material, 2 visibility ids): raster shading
  // binds the first two; visibility shading the ids alone, or all three for a scene with textured objects, which
  // write normal and material in the raster pass (gbuffer_marked.frag) while the others write zeros there
  // (visibility_textured.frag) that the G-buffer resolve overwrites.
  std::vector<const vk::Image*> gbufferAttachments() const {
    if (!visibilityShading) return {&normalGlossiness, &materialTarget};
    if (!surfaceTargetsBound) return {&visibility};
    return {&normalGlossiness, &materialTarget, &visibility};
  }

  // The G-buffer pipeline of a material variant (detail::materialVariant), made at first use.
  VkPipeline gbufferPipeline(std::size_t variant) {
    if (!gbufferPipelines[variant]) gbufferPipelines[variant] = createGBufferPipeline(variant);
    return gbufferPipelines[variant];
  }

  vk::Unique<VkPipeline> createGBufferPipeline(std::size_t variant) const {
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
    const VkSpecializationMapEntry switches[] = {{0, 0, sizeof(VkBool32)},
                                                 {1, sizeof(VkBool32), sizeof(VkBool32)},
                                                 {2, 2 * sizeof(VkBool32), sizeof(VkBool32)}};
    auto on = [variant](std::size_t bit) -> VkBool32 { return (variant & bit) != 0 ? VK_TRUE : VK_FALSE; };
    const VkBool32 values[] = {on(detail::kBaseColorVariant), on(detail::kNormalMapVariant), on(detail::kDoubleSidedVariant)};
    const VkSpecializationInfo specialization{3, switches, sizeof(values), values};
    gbuffer.fragmentSpecialization = &specialization;
    return vk::createGraphicsPipeline(context, geometryLayout.layout, gbuffer);
  }

  // The depth-only pipeline of a detail::depthVariant (bit 0 cut-out, bit 1 double-sided), made at first use.
  VkPipeline depthOnlyPipeline(std::size_t variant) {
    if (!depthOnlyPipelines[variant]) {
      vk::GraphicsPipelineDesc desc = depthOnlyDesc;
      if ((variant & 1) != 0) desc.fragmentSpirv = spirv_depth_cutout_frag;
      if ((variant & 2) != 0) desc.cullMode = VK_CULL_MODE_NONE;
      depthOnlyPipelines[variant] = vk::createGraphicsPipeline(context, geometryLayout.layout, desc);
    }
    return depthOnlyPipelines[variant];
  }

  static glm::uvec2 visibilityPackingFor(const Scene& scene) {
    std::uint64_t mostTriangles = 0;
    for (const Mesh& mesh : scene.meshes) mostTriangles = std::max<std::uint64_t>(mostTriangles, mesh.indices.size() / 3);
    return gpu::visibilityPacking(scene.objects.size(), mostTriangles);
  }

  // Reversed-Z: nearer surfaces have greater device depth.
  VkCompareOp nearer() const { return options.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS; }
  float clearedDepth() const { return options.reversedZ ? 0.0f : 1.0f; }  // the far plane: sky
  float nearestDepth() const { return options.reversedZ ? 1.0f : 0.0f; }  // nothing passes a depth test here

  // A layer's viewport depth range (Listing 4.3): first-person in [0, split], the world in [split, 1]; reversed-Z
  // mirrors both (the world in [0, 1 - split], first-person in [1 - split, 1]).
  glm::vec2 layerDepthRange(Layer layer) const {
    const bool firstPerson = layer == Layer::FirstPerson;
    if (options.reversedZ)
      return {firstPerson ? 1.0f - kFirstPersonDeviceDepthMax : 0.0f, firstPerson ? 1.0f : 1.0f - kFirstPersonDeviceDepthMax};
    return {firstPerson ? 0.0f : kFirstPersonDeviceDepthMax, firstPerson ? kFirstPersonDeviceDepthMax : 1.0f};
  }
  void setLayerViewport(VkCommandBuffer cmd, Layer layer) const {
    const glm::vec2 range = layerDepthRange(layer);
    setViewport(cmd, width, height, range.x, range.y);
  }

  void setScene(const Scene& newScene) {
    std::vector<Vertex> vertices;
    std::vector<gpu::SurfaceVertex> surface;
    std::vector<std::uint32_t> indices;
    meshRanges.clear();
    for (const Mesh& mesh : newScene.meshes) {
      if (mesh.indices.size() % 3 != 0)
        throw std::invalid_argument("scene '" + newScene.name + "': a mesh's index count " +
                                    std::to_string(mesh.indices.size()) + " is not a multiple of 3 (triangles)");
      meshRanges.push_back({std::uint32_t(indices.size()), std::uint32_t(mesh.indices.size()), std::int32_t(vertices.size())});
      for (std::uint32_t index : mesh.indices)
        if (index >= mesh.vertices.size()) throw std::invalid_argument("scene '" + newScene.name + "': mesh index out of range");
      appendSurfaceVertices(newScene, mesh, surface);
      vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
      indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    }
    for (const Object& object : newScene.objects) {
      if (object.mesh >= newScene.meshes.size())
        throw std::invalid_argument("scene '" + newScene.name + "': object refers to missing mesh " + std::to_string(object.mesh));
      validateTextures(newScene, object);
    }
    if (vertices.empty() || indices.empty()) throw std::invalid_argument("scene '" + newScene.name + "' has no geometry");
    if (newScene.objects.size() >= S3D_NO_OBJECT)  // the G-buffer holds 16-bit object indices (packMaterial)
      throw std::invalid_argument("scene '" + newScene.name + "' has " + std::to_string(newScene.objects.size()) +
                                  " objects, more than " + std::to_string(S3D_NO_OBJECT - 1));
    if (newScene.ambientOcclusion && !(newScene.ambientOcclusionRadius > 0.0f && newScene.ambientOcclusionRadius < 1e4f))
      throw std::invalid_argument("scene '" + newScene.name + "': ambient-occlusion radius must be in (0, 1e4) world units");

    // Vertex and index buffers for the shadow maps' vertex input, storage buffers for geometry.vert and the
    // G-buffer resolve.
    constexpr VkBufferUsageFlags pulled = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    vertexBuffer = vk::createBuffer(context, vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | pulled,
                                    vk::MemoryLocation::Device);
    vk::uploadBuffer(context, vertexBuffer, std::as_bytes(std::span(vertices)));
    // Also a vertex buffer: cut-out shadow casters read their texture coordinates from it.
    surfaceBuffer = vk::createBuffer(context, surface.size() * sizeof(gpu::SurfaceVertex),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | pulled, vk::MemoryLocation::Device);
    vk::uploadBuffer(context, surfaceBuffer, std::as_bytes(std::span(surface)));
    textures.clear();
    for (const Texture& texture : newScene.textures) textures.push_back(uploadTexture(texture));
    indexBuffer = vk::createBuffer(context, indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT | pulled,
                                   vk::MemoryLocation::Device);
    vk::uploadBuffer(context, indexBuffer, std::as_bytes(std::span(indices)));
    objectBuffer = vk::createBuffer(context, std::max<std::size_t>(1, newScene.objects.size()) * sizeof(gpu::ObjectConstants),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryLocation::HostVisible);
    drawOrder.clear();
    for (std::uint32_t i = 0; i < newScene.objects.size(); ++i) {
      const float opacity = newScene.objects[i].material.opacity;
      if (!(opacity > 0.0f && opacity <= 1.0f))
        throw std::invalid_argument("scene '" + newScene.name + "': object " + std::to_string(i) + " has opacity " +
                                    std::to_string(opacity) + " outside (0, 1]");
      if (newScene.objects[i].material.isTransparent() && newScene.objects[i].layer == Layer::FirstPerson)
        throw std::invalid_argument("scene '" + newScene.name + "': transparent first-person objects are not supported");
      validateMaterialExtras(newScene, i);
    }
    // First-person objects first: they are nearest, so their depth rejects the world behind them early.
    for (Layer layer : {Layer::FirstPerson, Layer::World})
      for (std::uint32_t i = 0; i < newScene.objects.size(); ++i)
        if (newScene.objects[i].layer == layer && !newScene.objects[i].material.isTransparent()) drawOrder.push_back(i);
    drawBounds.clear();
    bool textured = false;
    for (std::uint32_t i : drawOrder) {
      const Object& object = newScene.objects[i];
      drawBounds.push_back(objectBounds(newScene.meshes[object.mesh], object.transform));
      textured = textured || detail::materialVariant(object.material) != 0;
    }
    const glm::uvec2 packing = visibilityShading ? visibilityPackingFor(newScene) : glm::uvec2(0);
    const VkFormat visibilityFormat = packing.y != 0 ? kWideVisibilityFormat : kNarrowVisibilityFormat;
    const bool newFormat = visibilityShading && (visibility.width == 0 || visibility.format != visibilityFormat);
    if (newFormat)
      visibility = vk::createImage(context, visibilityFormat, width, height,
                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    const bool surfaceTargets = textured || !visibilityShading;
    const bool newAttachments = surfaceTargets != surfaceTargetsBound;
    visibilityPacking = packing;
    surfaceTargetsBound = surfaceTargets;
    if (!gbufferPipelinesValid || newFormat || newAttachments) {
      for (vk::Unique<VkPipeline>& pipeline : gbufferPipelines) pipeline.reset();
      gbufferPipelinesValid = true;
    }
    std::vector<std::uint32_t> meshTriangles;
    for (const MeshRange& range : meshRanges) meshTriangles.push_back(range.indexCount / 3);
    transparentPass->setScene(newScene, meshTriangles, textures, whiteTexture, flatNormalTexture);
    std::vector<detail::ShadowMeshRange> shadowRanges;
    for (const MeshRange& range : meshRanges) shadowRanges.push_back({range.firstIndex, range.indexCount, range.vertexOffset});
    shadows->setScene(newScene, vertexBuffer.buffer, indexBuffer.buffer, std::move(shadowRanges), shadowTextures());
    lighting->setScene(newScene);
    scene = newScene;
  }

  // What cut-out shadow casters sample: the uploaded surface stream and textures.
  detail::ShadowTextures shadowTextures() const {
    detail::ShadowTextures shadowTextures{surfaceBuffer.buffer, textureSampler, {}, whiteTexture.view};
    for (const vk::Image& texture : textures) shadowTextures.views.push_back(texture.view);
    return shadowTextures;
  }

  // A new pose of the scene last set (scene_animation.h): vertices, tangents and object transforms replace the old
  // ones in place; textures, indices and pipelines stay. Everything else must be as setScene left it.
  void updateGeometry(const Scene& newScene) {
    requireSameTopology(newScene);
    std::vector<Vertex> vertices;
    std::vector<gpu::SurfaceVertex> surface;
    for (const Mesh& mesh : newScene.meshes) {
      appendSurfaceVertices(newScene, mesh, surface);
      vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
    }
    vk::uploadBuffer(context, vertexBuffer, std::as_bytes(std::span(vertices)));
    vk::uploadBuffer(context, surfaceBuffer, std::as_bytes(std::span(surface)));
    drawBounds.clear();
    for (std::uint32_t i : drawOrder) drawBounds.push_back(objectBounds(newScene.meshes[newScene.objects[i].mesh], newScene.objects[i].transform));
    std::vector<std::uint32_t> meshTriangles;
    std::vector<detail::ShadowMeshRange> shadowRanges;
    for (const MeshRange& range : meshRanges) {
      meshTriangles.push_back(range.indexCount / 3);
      shadowRanges.push_back({range.firstIndex, range.indexCount, range.vertexOffset});
    }
    transparentPass->setScene(newScene, meshTriangles, textures, whiteTexture, flatNormalTexture);
    shadows->setScene(newScene, vertexBuffer.buffer, indexBuffer.buffer, std::move(shadowRanges),
                      shadowTextures());  // local maps redrawn
    scene.meshes = newScene.meshes;  // not a whole copy: that would copy every texture's pixels again
    scene.objects = newScene.objects;
  }

  void requireSameTopology(const Scene& newScene) const {
    auto sameMesh = [](const Mesh& a, const Mesh& b) {
      return a.vertices.size() == b.vertices.size() && a.indices == b.indices && a.texCoords.size() == b.texCoords.size() &&
             a.tangents.size() == b.tangents.size();
    };
    auto sameObject = [](const Object& a, const Object& b) {
      return a.mesh == b.mesh && a.layer == b.layer && a.castsShadow == b.castsShadow &&
             a.material.baseColorTexture == b.material.baseColorTexture &&
             a.material.normalTexture == b.material.normalTexture && a.material.isTransparent() == b.material.isTransparent();
    };
    bool same = !meshRanges.empty() && newScene.meshes.size() == scene.meshes.size() &&
                newScene.objects.size() == scene.objects.size() && newScene.textures.size() == scene.textures.size();
    for (std::size_t i = 0; same && i < newScene.meshes.size(); ++i) same = sameMesh(newScene.meshes[i], scene.meshes[i]);
    for (std::size_t i = 0; same && i < newScene.objects.size(); ++i) same = sameObject(newScene.objects[i], scene.objects[i]);
    if (!same)
      throw std::invalid_argument("scene '" + newScene.name + "': updateGeometry needs the meshes, objects and textures of "
                                  "the scene last set (only vertices and transforms may change); call setScene");
  }

  // The mesh's texture coordinates and tangents as the second vertex stream (zeros where it has none).
  static void appendSurfaceVertices(const Scene& scene, const Mesh& mesh, std::vector<gpu::SurfaceVertex>& surface) {
    const std::size_t count = mesh.vertices.size();
    if ((!mesh.texCoords.empty() && mesh.texCoords.size() != count) || (!mesh.tangents.empty() && mesh.tangents.size() != count))
      throw std::invalid_argument("scene '" + scene.name + "': a mesh's texture coordinates or tangents do not match its " +
                                  std::to_string(count) + " vertices");
    for (std::size_t v = 0; v < count; ++v)
      surface.push_back({mesh.texCoords.empty() ? glm::vec2(0.0f) : mesh.texCoords[v],
                         mesh.tangents.empty() ? glm::vec4(0.0f) : mesh.tangents[v]});
  }

  // Cut-out, emission and texture transforms within their ranges (scene.h).
  static void validateMaterialExtras(const Scene& scene, std::uint32_t objectIndex) {
    const Material& m = scene.objects[objectIndex].material;
    const std::string where = "scene '" + scene.name + "': object " + std::to_string(objectIndex) + " has ";
    if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f) || !(m.cutoutAlpha >= 0.0f && m.cutoutAlpha <= 1.0f))
      throw std::invalid_argument(where + "an alpha cutoff or cut-out alpha outside 0..1");
    if (m.isCutout() && m.isTransparent())
      throw std::invalid_argument(where + "a cut-out material that is also transparent (opacity < 1 or alpha blending)");
    for (int c = 0; c < 3; ++c)
      if (!(m.emissive[c] >= 0.0f && std::isfinite(m.emissive[c])))
        throw std::invalid_argument(where + "an emissive colour that is negative or not finite");
    for (const TextureTransform* t : {&m.baseColorTransform, &m.normalTransform})
      if (!std::isfinite(t->offset.x) || !std::isfinite(t->offset.y) || !std::isfinite(t->rotation) ||
          !std::isfinite(t->scale.x) || !std::isfinite(t->scale.y))
        throw std::invalid_argument(where + "a texture transform that is not finite");
  }

  // A texture reference must name a texture of the right encoding, on a mesh that can place it.
  static void validateTextures(const Scene& scene, const Object& object) {
    const Mesh& mesh = scene.meshes[object.mesh];
    auto check = [&](std::int32_t index, Texture::Encoding encoding, const char* role, bool needsTangents) {
      if (index == kNoTexture) return;
      const std::string where = "scene '" + scene.name + "': " + role + " texture " + std::to_string(index);
      if (index < 0 || std::size_t(index) >= scene.textures.size())
        throw std::invalid_argument(where + " does not exist (" + std::to_string(scene.textures.size()) + " textures)");
      const Texture& texture = scene.textures[std::size_t(index)];
      if (texture.width == 0 || texture.height == 0 || texture.rgba.size() != std::size_t(texture.width) * texture.height * 4)
        throw std::invalid_argument(where + " is empty or its pixel data does not match its size");
      if (texture.encoding != encoding)
        throw std::invalid_argument(where + (encoding == Texture::Encoding::Srgb ? " must be sRGB-encoded" : " must be linear"));
      if (mesh.texCoords.empty() || (needsTangents && mesh.tangents.empty()))
        throw std::invalid_argument(where + " is on a mesh without texture coordinates" + (needsTangents ? " or tangents" : ""));
    };
    check(object.material.baseColorTexture, Texture::Encoding::Srgb, "base color", false);
    check(object.material.normalTexture, Texture::Encoding::Linear, "normal", true);
  }

  void writeFrameConstants(const ViewMatrices& view, const ShadeMask& mask) {
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
    }
  }

  // The frame and object buffers and, at kGeometryTextureBinding and the one after it, the object's base-color
  // and normal textures (the 1x1 defaults when it has none).
  void pushGeometryDescriptors(VkCommandBuffer cmd, const Material& material) {
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

  // How drawObjects picks pipelines: the one bound, or per object its G-buffer or depth-only variant.
  enum class Pipelines { Bound, GBuffer, DepthOnly };

  void drawObjects(VkCommandBuffer cmd, const std::vector<std::uint32_t>& objects, Pipelines pipelines = Pipelines::Bound) {
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

  // Opaque objects nearest first (first-person ones before the world): the depth test then rejects hidden
  // fragments before they write anything, and the raster pass's cost follows the bytes its fragments write.
  void sortFrontToBack(const ViewMatrices& view) {
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

  // A masked render with ambient occlusion needs every pixel's depth (the occlusion samples outside the mask).
  // Under visibility shading of a scene without textured objects the G-buffer's fragments only write ids, so the
  // G-buffer pass rasterizes every pixel and the occlusion reads its depth; otherwise (costly fragments) the
  // G-buffer pass stays within the mask and a depth-only pass gives the occlusion its depth (recordAmbientDepth).
  bool maskedGBufferWritesEveryPixel() const { return visibilityShading && !surfaceTargetsBound && scene.ambientOcclusion; }

  // Masked render: every pixel outside the mask gets the nearest depth, so later depth tests there fail unshaded.
  // `loadOp` CLEAR first clears to the far plane (before the G-buffer), LOAD keeps the G-buffer's depth inside the
  // mask (before the transparent pass, after a G-buffer pass that wrote every pixel). Leaves depth an attachment.
  void recordMaskDepthFill(VkCommandBuffer cmd, const ShadeMask& mask, VkAttachmentLoadOp loadOp) {
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

  // The G-buffer pass: depth, and normal/glossiness and material (raster shading) or visibility ids (visibility
  // shading; textured objects write normal and material too). A masked render first gives every pixel outside
  // the mask the nearest depth, so the geometry's fragments there fail the depth test unshaded, unless the pass
  // writes every pixel (maskedGBufferWritesEveryPixel).
  void recordGBuffer(VkCommandBuffer cmd, const ShadeMask& mask) {
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

  void recordGBufferResolve(VkCommandBuffer cmd, const ShadeMask& mask) {
    const detail::GBufferResolve::Inputs inputs{depth,
                                                visibility,
                                                frameBuffer.buffer,
                                                objectBuffer.buffer,
                                                indexBuffer.buffer,
                                                vertexBuffer.buffer,
                                                tiles->buffer(),
                                                tiles->maskDescriptor(mask.image),
                                                mask.image != nullptr,
                                                tiles->tilesX(),
                                                tiles->tilesY()};
    gbufferResolve->record(cmd, inputs, normalGlossiness, materialTarget,
                           surfaceTargetsBound ? vk::kColorAttachment : vk::kUndefined);
  }

  // Masked renders with ambient occlusion: every pixel's depth (no fragment work), so the occlusion's samples
  // outside the mask see what an unmasked render's do.
  void recordAmbientDepth(VkCommandBuffer cmd) {
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

  // No transparent pass and no supersampling: the lighting pass writes the resolve's outputs itself.
  bool resolveInLighting() const { return !transparentPass->hasObjects() && supersample == 1; }

  // frameShadows: this renderer's shadow maps, rendered this frame, or a shadow source's (already readable).
  void recordLighting(VkCommandBuffer cmd, const ShadeMask& mask, const detail::ShadowMaps& frameShadows) {
    if (&frameShadows == shadows.get()) shadows->recordReadableForLighting(cmd);
    if (!scene.ambientOcclusion) ambientOcclusion->recordUnused(cmd);
    const detail::TiledLighting::Inputs inputs{depth,
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
    lighting->record(cmd, inputs, frameShadows, {hdr, display, resolvedHdr, linearDepth, resolveInLighting()});
  }

  // Transparent surfaces over the lit image, back to front, depth-tested against the opaque depth (in a masked
  // render the depth fill hides them outside the mask too).
  void recordTransparent(VkCommandBuffer cmd, const ViewMatrices& view, const ShadeMask& mask) {
    const detail::TransparentPass::Inputs inputs{
        depth, hdr, frameBuffer.buffer, objectBuffer.buffer, indexBuffer.buffer, vertexBuffer.buffer, surfaceBuffer.buffer,
        textureSampler, view.worldView, view.worldProjection * view.worldView, layerDepthRange(Layer::World),
        options.reversedZ, tiles->maskDescriptor(mask.image).imageView, mask.image != nullptr,
        [this](VkCommandBuffer drawCmd, const std::vector<std::uint32_t>& objects) { drawObjects(drawCmd, objects); }};
    transparentPass->record(cmd, inputs);
  }

  void recordResolve(VkCommandBuffer cmd, const ShadeMask& mask, bool afterTransparent) {
    const detail::ResolvePass::Inputs inputs{hdr,
                                             !afterTransparent,
                                             depth,
                                             frameBuffer.buffer,
                                             tiles->buffer(),
                                             tiles->maskDescriptor(mask.image),
                                             mask.image != nullptr,
                                             supersample,
                                             outputWidth,
                                             outputHeight};
    resolvePass->record(cmd, inputs, {display, resolvedHdr, linearDepth});
  }

  struct ScheduledPass {
    std::string name;
    std::function<void(VkCommandBuffer)> record;
    int counterSlot = -1;  // S3D_COUNT_*: the pass's shaded-pixel counter
  };

  // The passes this frame needs, in order: a pass that serves nothing in the scene does not run, nor shadow maps
  // a shadow source lends.
  std::vector<ScheduledPass> schedulePasses(const ViewMatrices& view, const ShadeMask& mask,
                                            const detail::ShadowMaps* lentShadows) {
    std::vector<ScheduledPass> passes;
    const bool masked = mask.image != nullptr;
    sortFrontToBack(view);
    const bool withAmbientOcclusion = scene.ambientOcclusion;
    if (masked) {
      passes.push_back({"mask-tiles", [this, mask](VkCommandBuffer cmd) {
                          tiles->recordReset(cmd, mask.image);
                          tiles->recordBuild(cmd, frameBuffer.buffer, *mask.image);
                        }});
      if (withAmbientOcclusion && !maskedGBufferWritesEveryPixel())
        passes.push_back({"ssao-depth", [this](VkCommandBuffer cmd) { recordAmbientDepth(cmd); }});
    }
    // The G-buffer's count (the render pixels with a surface) comes from the G-buffer resolve, or under raster
    // shading from a counting pass of its own.
    passes.push_back({"gbuffer",
                      [this, mask](VkCommandBuffer cmd) {
                        if (mask.image == nullptr) tiles->recordReset(cmd, nullptr);
                        recordGBuffer(cmd, mask);
                      },
                      S3D_COUNT_GBUFFER});
    if (visibilityShading)
      passes.push_back({"gbuffer-resolve", [this, mask](VkCommandBuffer cmd) { recordGBufferResolve(cmd, mask); }});
    else if (options.countShadedPixels)
      passes.push_back({"gbuffer-count", [this](VkCommandBuffer cmd) {
                          tiles->recordCountGBuffer(cmd, frameBuffer.buffer, materialTarget, nearestSampler);
                        }});
    if (withAmbientOcclusion) {
      const vk::Image& occlusionDepth = masked && !maskedGBufferWritesEveryPixel() ? ambientDepth : depth;
      passes.push_back({"ssao",
                        [this, &occlusionDepth, masked](VkCommandBuffer cmd) {
                          ambientOcclusion->recordOcclusion(cmd, occlusionDepth, frameBuffer.buffer, tiles->buffer(), masked);
                        },
                        S3D_COUNT_SSAO});
      passes.push_back({"ssao-blur",
                        [this, masked](VkCommandBuffer cmd) {
                          ambientOcclusion->recordBlur(cmd, frameBuffer.buffer, tiles->buffer(), masked);
                        },
                        S3D_COUNT_SSAO_BLUR});
    }
    if (lentShadows == nullptr)
      for (detail::ShadowPass& shadowPass : shadows->schedule(view))
        passes.push_back({std::move(shadowPass.name), std::move(shadowPass.record)});
    const detail::ShadowMaps* frameShadows = lentShadows != nullptr ? lentShadows : shadows.get();
    lighting->prepareFrame(scene, view, *frameShadows);
    passes.push_back({"lighting",
                      [this, mask, frameShadows](VkCommandBuffer cmd) { recordLighting(cmd, mask, *frameShadows); },
                      S3D_COUNT_LIGHTING});
    const bool withTransparent = transparentPass->hasObjects();
    // Keeps a raster transparent pass within the mask (the compute pass reads the mask itself: cheaper than the
    // full-screen fill, 0.078 ms for glass's whole frame against 0.16 ms an eye for the fill on an H200).
    if (withTransparent && masked && maskedGBufferWritesEveryPixel() && !transparentPass->usesCompute())
      passes.push_back({"mask-depth", [this, mask](VkCommandBuffer cmd) {
                          vk::transition(cmd, depth, kComputeSampled, vk::kDepthAttachment);
                          recordMaskDepthFill(cmd, mask, VK_ATTACHMENT_LOAD_OP_LOAD);
                          vk::transition(cmd, depth, vk::kDepthAttachment, kComputeSampled);
                        }});
    if (withTransparent) {
      passes.push_back({"transparent", [this, view, mask](VkCommandBuffer cmd) { recordTransparent(cmd, view, mask); }});
    }
    if (!resolveInLighting())
      passes.push_back({"resolve",
                        [this, mask, withTransparent](VkCommandBuffer cmd) { recordResolve(cmd, mask, withTransparent); },
                        S3D_COUNT_RESOLVE});
    return passes;
  }

  void validateMask(const ShadeMask& mask) const {
    if (mask.image == nullptr) return;
    if (mask.image->format != VK_FORMAT_R32_UINT)
      throw std::invalid_argument("renderer: the shade mask must be an R32_UINT image");
    if (mask.image->width != outputWidth || mask.image->height != outputHeight)
      throw std::invalid_argument("renderer: the shade mask is " + std::to_string(mask.image->width) + "x" +
                                  std::to_string(mask.image->height) + ", the output " + std::to_string(outputWidth) +
                                  "x" + std::to_string(outputHeight));
  }

  // A shadow source's maps, checked to be the ones this view would render (the scene, the size and the fit).
  const detail::ShadowMaps& lentShadowMaps(const ViewMatrices& view, const Impl& source) const {
    if (&source == this) throw std::invalid_argument("renderer: a renderer cannot be its own shadow source");
    if (source.width != width || source.height != height)
      throw std::invalid_argument("renderer: the shadow source renders " + std::to_string(source.width) + "x" +
                                  std::to_string(source.height) + ", this renderer " + std::to_string(width) + "x" +
                                  std::to_string(height));
    if (!source.shadows->castsLike(*shadows))
      throw std::invalid_argument("renderer: the shadow source holds another scene's shadows");
    const std::optional<ShadowFit> planned = source.shadows->plannedFit();
    if (!planned) throw std::invalid_argument("renderer: the shadow source has rendered no frame of its scene");
    if (*planned != shadowFitOf(view))
      throw std::invalid_argument("renderer: the shadow source's last frame planned its shadow maps for another camera");
    return *source.shadows;
  }

  FrameTimings render(const ViewMatrices& view, const ShadeMask& mask, const Impl* shadowSource) {
    if (meshRanges.empty()) throw std::logic_error("DeferredRenderer::render called before setScene");
    validateMask(mask);
    const detail::ShadowMaps* lentShadows = shadowSource != nullptr ? &lentShadowMaps(view, *shadowSource) : nullptr;
    writeFrameConstants(view, mask);
    const std::vector<ScheduledPass> passes = schedulePasses(view, mask, lentShadows);
    if (passes.size() > kMaxPasses) throw std::logic_error("renderer: more passes than timestamps");
    constexpr VkPipelineStageFlags2 kAll = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    context.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, kAll);
      for (std::uint32_t pass = 0; pass < passes.size(); ++pass) {
        passes[pass].record(cmd);
        timestamps.write(cmd, pass + 1, kAll);
      }
      if (options.countShadedPixels) tiles->recordCountReadback(cmd);
    });
    FrameTimings timings;
    const auto passCount = std::uint32_t(passes.size());
    timings.totalGpuMs = timestamps.elapsedMs(0, passCount);
    const std::array<std::uint32_t, S3D_COUNT_SLOTS> counts =
        options.countShadedPixels ? tiles->readCounts() : std::array<std::uint32_t, S3D_COUNT_SLOTS>{};
    for (std::uint32_t pass = 0; pass < passCount; ++pass) {
      PassTiming timing{passes[pass].name, timestamps.elapsedMs(pass, pass + 1).value_or(0.0), std::nullopt};
      if (options.countShadedPixels && passes[pass].counterSlot >= 0)
        timing.shadedPixels = counts[std::size_t(passes[pass].counterSlot)];
      timings.passes.push_back(timing);
    }
    return timings;
  }
};

DeferredRenderer::DeferredRenderer(vk::Context& context, std::uint32_t width, std::uint32_t height,
                                   RendererOptions options)
    : impl_(std::make_unique<Impl>(context, width, height, options)) {}
DeferredRenderer::~DeferredRenderer() = default;

void DeferredRenderer::setScene(const Scene& scene) { impl_->setScene(scene); }
void DeferredRenderer::updateGeometry(const Scene& scene) { impl_->updateGeometry(scene); }
FrameTimings DeferredRenderer::render(const ViewMatrices& view, const ShadeMask& mask) {
  return impl_->render(view, mask, nullptr);
}
FrameTimings DeferredRenderer::render(const ViewMatrices& view, const ShadeMask& mask,
                                      const DeferredRenderer& shadowSource) {
  return impl_->render(view, mask, shadowSource.impl_.get());
}
std::uint32_t DeferredRenderer::width() const { return impl_->outputWidth; }
std::uint32_t DeferredRenderer::height() const { return impl_->outputHeight; }
std::uint32_t DeferredRenderer::supersample() const { return impl_->supersample; }
const RendererOptions& DeferredRenderer::options() const { return impl_->options; }
RendererOptions::GBufferShading DeferredRenderer::gbufferShading() const {
  return impl_->visibilityShading ? RendererOptions::GBufferShading::Visibility : RendererOptions::GBufferShading::Raster;
}

const char* gbufferShadingName(RendererOptions::GBufferShading shading) {
  switch (shading) {
    case RendererOptions::GBufferShading::Raster: return "raster";
    case RendererOptions::GBufferShading::Visibility: return "visibility";
    default: return "auto";
  }
}

std::optional<RendererOptions::GBufferShading> gbufferShadingFromName(std::string_view name) {
  for (auto shading : {RendererOptions::GBufferShading::Automatic, RendererOptions::GBufferShading::Raster,
                       RendererOptions::GBufferShading::Visibility})
    if (name == gbufferShadingName(shading)) return shading;
  return std::nullopt;
}
const vk::Image& DeferredRenderer::displayColor() const { return impl_->display; }
const vk::Image& DeferredRenderer::linearDepth() const { return impl_->linearDepth; }
const vk::Image& DeferredRenderer::hdrColor() const { return impl_->resolvedHdr; }

ImageRGBA8 DeferredRenderer::readDisplayColor() {
  ImageRGBA8 image(impl_->outputWidth, impl_->outputHeight);
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->display, vk::kComputeWrite);
  std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
  return image;
}

DepthImage DeferredRenderer::readLinearDepth() {
  DepthImage image(impl_->outputWidth, impl_->outputHeight);
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->linearDepth, vk::kComputeWrite);
  std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
  return image;
}

std::vector<std::uint8_t> DeferredRenderer::readFirstPersonMask() {
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->depth, kComputeSampled);
  std::vector<float> deviceDepth(bytes.size() / sizeof(float));
  std::memcpy(deviceDepth.data(), bytes.data(), bytes.size());
  const Impl& r = *impl_;
  const bool reversed = r.options.reversedZ;
  std::vector<std::uint8_t> mask(std::size_t(r.outputWidth) * r.outputHeight, 0);
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) {
      const float device = deviceDepth[std::size_t(y) * r.width + x];
      if (reversed ? device >= 1.0f - kFirstPersonDeviceDepthMax : device <= kFirstPersonDeviceDepthMax)
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
    }
  return mask;
}

std::vector<std::uint8_t> DeferredRenderer::readTransparentMask() {
  const Impl& r = *impl_;
  std::vector<std::uint8_t> mask(std::size_t(r.outputWidth) * r.outputHeight, 0);
  if (!r.transparentPass->hasObjects()) return mask;  // the transparent pass did not run
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, r.transparentPass->coverage(),
                                                   r.transparentPass->coverageState());
  // With supersampling, an output pixel is transparent where any of its samples is.
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x)
      if (bytes[4 * (std::size_t(y) * r.width + x)] != std::byte{0})
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
  return mask;
}

std::vector<std::uint8_t> DeferredRenderer::readCutoutMask() {
  const Impl& r = *impl_;
  std::vector<std::uint8_t> mask(std::size_t(r.outputWidth) * r.outputHeight, 0);
  std::vector<bool> cutout(r.scene.objects.size());
  for (std::size_t i = 0; i < cutout.size(); ++i) cutout[i] = r.scene.objects[i].material.isCutout();
  if (std::find(cutout.begin(), cutout.end(), true) == cutout.end()) return mask;
  // The G-buffer's material target names each render pixel's object (S3D_NO_OBJECT for the sky).
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, r.materialTarget, kComputeSampled);
  std::vector<glm::uvec2> material(bytes.size() / sizeof(glm::uvec2));
  std::memcpy(material.data(), bytes.data(), bytes.size());
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) {
      const std::uint32_t object = gpu::unpackObjectIndex(material[std::size_t(y) * r.width + x]);
      if (object < cutout.size() && cutout[object])
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
    }
  return mask;
}

std::vector<std::uint32_t> DeferredRenderer::readVisibilityIds() {
  const Impl& r = *impl_;
  if (!r.visibilityShading || r.visibility.format != kNarrowVisibilityFormat) return {};
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, r.visibility, kComputeSampled);
  std::vector<std::uint32_t> ids(bytes.size() / sizeof(std::uint32_t));
  std::memcpy(ids.data(), bytes.data(), bytes.size());
  return ids;
}

ImageRGBA32F DeferredRenderer::readHdrColor() {
  // The shading target holds half floats; the exposure is applied here so center.exr matches the display.
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->resolvedHdr, vk::kComputeWrite);
  ImageRGBA32F image(impl_->outputWidth, impl_->outputHeight);
  std::vector<std::uint16_t> halves(bytes.size() / 2);
  std::memcpy(halves.data(), bytes.data(), bytes.size());
  for (std::size_t i = 0; i < halves.size(); ++i) {
    float value = glm::unpackHalf1x16(halves[i]);
    image.pixels[i] = (i % 4 == 3) ? value : value * impl_->scene.exposure;
  }
  return image;
}

}  // namespace s3d::renderer
