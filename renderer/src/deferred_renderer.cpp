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
#include "shadow_maps.h"
#include "s3d/vk/check.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/timestamps.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/fullscreen_vert.h>
#include <s3d_spirv/gbuffer_frag.h>
#include <s3d_spirv/geometry_vert.h>
#include <s3d_spirv/light_frag.h>
#include <s3d_spirv/shading_frag.h>
#include <s3d_spirv/sky_frag.h>
#include <s3d_spirv/ssao_comp.h>
#include <s3d_spirv/sky_vert.h>
#include <s3d_spirv/resolve_comp.h>
#include <s3d_spirv/transparent_frag.h>
// clang-format on

namespace s3d::renderer {
namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // world normal + glossiness
constexpr VkFormat kLightFormat = VK_FORMAT_R16G16B16A16_SFLOAT;   // HDR diffuse / specular light
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;     // sRGB-encoded by the tone-map pass
constexpr VkFormat kLinearDepthFormat = VK_FORMAT_R32_SFLOAT;
constexpr VkFormat kAmbientOcclusionFormat = VK_FORMAT_R16_SFLOAT;
constexpr VkFormat kCoverageFormat = VK_FORMAT_R8G8B8A8_UNORM;  // red: transparent coverage (the metrics' mask)

// Material textures (section 4.3's "sRGB textures read as linear"): colour through an sRGB format, data not.
VkFormat textureFormat(Texture::Encoding encoding) {
  return encoding == Texture::Encoding::Srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
}
// Descriptor bindings of an object's textures in the passes that draw geometry: base color, then normal map.
constexpr std::uint32_t kGeometryTextureBinding = 2;  // G-buffer and transparent pass (geometry layout)
constexpr std::uint32_t kShadingTextureBinding = 4;   // shading pass (after the two light buffers)

constexpr vk::ImageState kDepthSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                       VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
constexpr vk::ImageState kDepthReadOnlyAttachment{VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                                                  VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT};
// Sampled by the light pass (fragment) and SSAO (compute).
constexpr vk::ImageState kNormalSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
constexpr vk::ImageState kOcclusionSampled = kNormalSampled;
constexpr vk::ImageState kComputeSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

constexpr std::uint32_t kMaxPasses = 64;  // timestamps: one before the first pass and one after each (shadow maps: up to 53)

VkDescriptorSetLayoutBinding binding(std::uint32_t index, VkDescriptorType type, VkShaderStageFlags stages) {
  return {index, type, 1, stages, nullptr};
}

VkRenderingAttachmentInfo colorAttachment(const vk::Image& image, bool clear) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = image.view;
  info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  info.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  info.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  return info;
}

// The G-buffer's depth, tested but not written (shading, sky, transparent surfaces).
VkRenderingAttachmentInfo readOnlyDepthAttachment(const vk::Image& depth) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = depth.view;
  info.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  info.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  info.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
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

// The screen rectangle a point light's sphere can touch, so the light costs only those pixels
// (nullopt: entirely off screen or behind the camera).
std::optional<VkRect2D> lightScissor(const PointLight& light, const glm::mat4& viewProjection, std::uint32_t width,
                                     std::uint32_t height) {
  glm::vec2 lo(1e30f), hi(-1e30f);
  int behind = 0;
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 offset((corner & 1) ? light.radius : -light.radius, (corner & 2) ? light.radius : -light.radius,
                     (corner & 4) ? light.radius : -light.radius);
    glm::vec4 clip = viewProjection * glm::vec4(light.position + offset, 1.0f);
    if (clip.w <= 1e-4f) {
      ++behind;
      continue;
    }
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
  }
  if (behind == 8) return std::nullopt;
  if (behind > 0) return VkRect2D{{0, 0}, {width, height}};  // the sphere straddles the eye plane
  lo = glm::clamp((lo * 0.5f + 0.5f) * glm::vec2(width, height), glm::vec2(0.0f), glm::vec2(width, height));
  hi = glm::clamp((hi * 0.5f + 0.5f) * glm::vec2(width, height), glm::vec2(0.0f), glm::vec2(width, height));
  auto x0 = std::uint32_t(std::floor(lo.x)), y0 = std::uint32_t(std::floor(lo.y));
  auto x1 = std::uint32_t(std::ceil(hi.x)), y1 = std::uint32_t(std::ceil(hi.y));
  if (x1 <= x0 || y1 <= y0) return std::nullopt;
  return VkRect2D{{int32_t(x0), int32_t(y0)}, {x1 - x0, y1 - y0}};
}

struct MeshRange {
  std::uint32_t firstIndex = 0;
  std::uint32_t indexCount = 0;
  std::int32_t vertexOffset = 0;
};

}  // namespace

glm::mat4 vulkanPerspective(float verticalFovRadians, float aspect, float nearPlane, float farPlane) {
  glm::mat4 projection = glm::perspectiveRH_ZO(verticalFovRadians, aspect, nearPlane, farPlane);
  projection[1][1] = -projection[1][1];  // Vulkan's clip-space y points down
  return projection;
}

glm::mat4 reversedDepthProjection(const glm::mat4& projection, float nearPlane, float farPlane) {
  // A zero-to-one perspective with near and far swapped: z_ndc = n / (n - f) + n f / ((f - n) d), 1 at the near
  // plane and 0 at the far plane. Only the depth row changes, so off-axis terms (P20, P21) stay; the two terms
  // are computed in double from n and f (not as w - z from the matrix, which would cancel to ~1e-4 relative).
  glm::mat4 reversed = projection;
  const double n = nearPlane, f = farPlane;
  reversed[2][2] = float(n / (f - n));
  reversed[3][2] = float(n * f / (f - n));
  return reversed;
}

glm::mat4 cameraView(const Camera& camera) {
  glm::vec3 forward(-std::sin(camera.yawRadians) * std::cos(camera.pitchRadians), std::sin(camera.pitchRadians),
                    -std::cos(camera.yawRadians) * std::cos(camera.pitchRadians));
  return glm::lookAt(camera.position, camera.position + forward, glm::vec3(0.0f, 1.0f, 0.0f));
}

std::optional<glm::vec2> firstPersonDepthRange(const Scene& scene) {
  std::optional<glm::vec2> range;
  for (const Object& object : scene.objects) {
    if (object.layer != Layer::FirstPerson) continue;
    for (const Vertex& vertex : scene.meshes.at(object.mesh).vertices) {
      float depth = -(object.transform * glm::vec4(vertex.position, 1.0f)).z;
      range = range ? glm::vec2(std::min(range->x, depth), std::max(range->y, depth)) : glm::vec2(depth);
    }
  }
  return range;
}

ViewMatrices centerViewMatrices(const Scene& scene, float aspect, FirstPersonDepthPush push) {
  if (!std::isfinite(push.offset) || push.offset < 0.0f)
    throw std::invalid_argument("weapon depth offset must be finite and >= 0 (got " + std::to_string(push.offset) + ")");
  if (!std::isfinite(push.scale) || push.scale <= 0.0f)
    throw std::invalid_argument("weapon depth scale must be finite and > 0 (got " + std::to_string(push.scale) + ")");
  ViewMatrices view;
  view.firstPersonDepthPush = push;
  view.worldView = cameraView(scene.camera);
  view.worldProjection =
      vulkanPerspective(scene.camera.verticalFovRadians, aspect, scene.camera.nearPlane, scene.camera.farPlane);
  view.firstPersonView = glm::mat4(1.0f);
  view.firstPersonProjection = vulkanPerspective(scene.firstPerson.verticalFovRadians, aspect,
                                                 scene.firstPerson.nearPlane, scene.firstPerson.farPlane);
  view.worldFromCamera = glm::inverse(view.worldView);
  return view;
}

struct DeferredRenderer::Impl {
  vk::Context& context;
  std::uint32_t outputWidth;   // display colour, linear depth, resolved HDR
  std::uint32_t outputHeight;
  std::uint32_t supersample;   // every pass before the resolve runs at supersample x the output size
  std::uint32_t width;         // render size of those passes
  std::uint32_t height;
  RendererOptions options;

  // Render targets (render size), then the resolve's outputs (output size).
  vk::Image depth, normalGlossiness, diffuseLight, specularLight, hdr, ambientOcclusion;
  vk::Image transparentCoverage;  // written by the transparent pass only (scenes with transparent objects)
  vk::Image display, linearDepth, resolvedHdr;
  vk::Unique<VkSampler> nearestSampler;
  vk::Unique<VkSampler> textureSampler;  // bilinear, repeating, no mipmaps
  vk::Image whiteTexture, flatNormalTexture;  // what untextured objects sample: albedo x 1, normal (0, 0, 1)

  // Passes: layouts and pipelines.
  vk::PipelineLayout geometryLayout, lightLayout, shadingLayout, skyLayout, resolveLayout, ssaoLayout;
  vk::Unique<VkPipeline> gbufferPipeline, lightPipeline, shadingPipeline, transparentPipeline, skyPipeline, resolvePipeline,
      ssaoPipeline;

  // Scene data.
  Scene scene;
  vk::Buffer vertexBuffer, surfaceBuffer, indexBuffer, objectBuffer, frameBuffer;
  std::vector<vk::Image> textures;  // Scene::textures, uploaded
  std::vector<MeshRange> meshRanges;
  std::vector<std::uint32_t> drawOrder;          // opaque object indices, world layer first
  std::vector<std::uint32_t> transparentOrder;   // transparent objects, sorted back to front per frame

  vk::TimestampQueries timestamps;
  std::unique_ptr<detail::ShadowMaps> shadows;  // sun cascades + mask, point/spot shadow maps (shadow_maps.cpp)

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
    createTargets();
    createPipelines();
    shadows = std::make_unique<detail::ShadowMaps>(context, width, height);
    frameBuffer = vk::createBuffer(context, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                   vk::MemoryLocation::HostVisible);
  }

  void createTargets() {
    const VkImageUsageFlags attachmentSampled = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    depth = vk::createImage(context, kDepthFormat, width, height,
                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | attachmentSampled);
    normalGlossiness = vk::createImage(context, kNormalFormat, width, height,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | attachmentSampled);
    diffuseLight = vk::createImage(context, kLightFormat, width, height,
                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | attachmentSampled);
    specularLight = vk::createImage(context, kLightFormat, width, height,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | attachmentSampled);
    hdr = vk::createImage(context, kHdrFormat, width, height,
                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    const VkImageUsageFlags computeOutput = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    display = vk::createImage(context, kDisplayFormat, outputWidth, outputHeight, computeOutput);
    linearDepth = vk::createImage(context, kLinearDepthFormat, outputWidth, outputHeight, computeOutput);
    resolvedHdr = vk::createImage(context, kHdrFormat, outputWidth, outputHeight, computeOutput);
    transparentCoverage = vk::createImage(context, kCoverageFormat, width, height,
                                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    ambientOcclusion = vk::createImage(context, kAmbientOcclusionFormat, width, height,
                                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                           VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);

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
    constexpr VkShaderStageFlags compute = VK_SHADER_STAGE_COMPUTE_BIT;

    const VkDescriptorSetLayoutBinding geometryBindings[] = {binding(0, ubo, graphics), binding(1, ssbo, graphics),
                                                             binding(2, sampled, fragment), binding(3, sampled, fragment)};
    geometryLayout = vk::createPushDescriptorLayout(context, geometryBindings, sizeof(std::uint32_t), graphics);
    const VkDescriptorSetLayoutBinding shadingBindings[] = {binding(0, ubo, graphics),      binding(1, ssbo, graphics),
                                                            binding(2, sampled, fragment), binding(3, sampled, fragment),
                                                            binding(4, sampled, fragment), binding(5, sampled, fragment)};
    shadingLayout = vk::createPushDescriptorLayout(context, shadingBindings, sizeof(std::uint32_t), graphics);
    const VkDescriptorSetLayoutBinding lightBindings[] = {binding(0, ubo, fragment),     binding(1, sampled, fragment),
                                                          binding(2, sampled, fragment), binding(3, sampled, fragment),
                                                          binding(4, sampled, fragment), binding(5, sampled, fragment),
                                                          binding(6, ubo, fragment)};
    lightLayout = vk::createPushDescriptorLayout(context, lightBindings, sizeof(gpu::LightConstants), fragment);
    const VkDescriptorSetLayoutBinding skyBindings[] = {binding(0, ubo, fragment)};
    skyLayout = vk::createPushDescriptorLayout(context, skyBindings, 0, 0);
    const VkDescriptorSetLayoutBinding resolveBindings[] = {binding(0, ubo, compute),     binding(1, storage, compute),
                                                            binding(2, storage, compute), binding(3, storage, compute),
                                                            binding(4, sampled, compute), binding(5, storage, compute)};
    resolveLayout = vk::createPushDescriptorLayout(context, resolveBindings, sizeof(gpu::ResolveConstants), compute);
    const VkDescriptorSetLayoutBinding ssaoBindings[] = {binding(0, ubo, compute), binding(1, sampled, compute),
                                                         binding(2, sampled, compute), binding(3, storage, compute)};
    ssaoLayout = vk::createPushDescriptorLayout(context, ssaoBindings, 0, 0);

    vk::GraphicsPipelineDesc geometry;
    geometry.vertexSpirv = spirv_geometry_vert;
    geometry.vertexBindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX},
                               {1, sizeof(gpu::SurfaceVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    geometry.vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                                 {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                                 {2, 1, VK_FORMAT_R32G32_SFLOAT, offsetof(gpu::SurfaceVertex, texCoord)},
                                 {3, 1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::SurfaceVertex, tangent)}};
    geometry.depthFormat = kDepthFormat;
    geometry.depthTest = true;
    geometry.cullMode = VK_CULL_MODE_BACK_BIT;

    vk::GraphicsPipelineDesc gbuffer = geometry;
    gbuffer.fragmentSpirv = spirv_gbuffer_frag;
    gbuffer.colorFormats = {kNormalFormat};
    gbuffer.depthWrite = true;
    gbuffer.depthCompare = nearer();
    gbufferPipeline = vk::createGraphicsPipeline(context, geometryLayout.layout, gbuffer);

    vk::GraphicsPipelineDesc shading = geometry;
    shading.fragmentSpirv = spirv_shading_frag;
    shading.colorFormats = {kHdrFormat};
    shading.depthCompare = VK_COMPARE_OP_EQUAL;  // only the surface the G-buffer kept
    shadingPipeline = vk::createGraphicsPipeline(context, shadingLayout.layout, shading);

    vk::GraphicsPipelineDesc transparent = geometry;
    transparent.fragmentSpirv = spirv_transparent_frag;
    transparent.colorFormats = {kHdrFormat, kCoverageFormat};  // coverage blends to 1 - prod(1 - opacity)
    transparent.depthCompare = nearer();  // behind opaque surfaces is hidden; no depth write
    transparent.cullMode = VK_CULL_MODE_NONE;
    transparent.blend = vk::GraphicsPipelineDesc::Blend::Alpha;
    transparentPipeline = vk::createGraphicsPipeline(context, geometryLayout.layout, transparent);

    vk::GraphicsPipelineDesc light;
    light.vertexSpirv = spirv_fullscreen_vert;
    light.fragmentSpirv = spirv_light_frag;
    light.colorFormats = {kLightFormat, kLightFormat};
    light.blend = vk::GraphicsPipelineDesc::Blend::Additive;
    lightPipeline = vk::createGraphicsPipeline(context, lightLayout.layout, light);

    vk::GraphicsPipelineDesc sky;
    sky.vertexSpirv = spirv_sky_vert;
    sky.fragmentSpirv = spirv_sky_frag;
    sky.colorFormats = {kHdrFormat};
    sky.depthFormat = kDepthFormat;
    sky.depthTest = true;
    // Reaches only pixels still at the cleared far plane (the sky's viewport puts it there: drawSky).
    sky.depthCompare = options.reversedZ ? VK_COMPARE_OP_GREATER_OR_EQUAL : VK_COMPARE_OP_LESS_OR_EQUAL;
    skyPipeline = vk::createGraphicsPipeline(context, skyLayout.layout, sky);

    resolvePipeline = vk::createComputePipeline(context, resolveLayout.layout, spirv_resolve_comp);
    ssaoPipeline = vk::createComputePipeline(context, ssaoLayout.layout, spirv_ssao_comp);
  }

  // Reversed-Z: nearer surfaces have greater device depth.
  VkCompareOp nearer() const { return options.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS; }
  float clearedDepth() const { return options.reversedZ ? 0.0f : 1.0f; }  // the far plane: sky

  // A layer's viewport depth range (Listing 4.3): first-person in [0, split], the world in [split, 1]; reversed-Z
  // mirrors both (the world in [0, 1 - split], first-person in [1 - split, 1]).
  void setLayerViewport(VkCommandBuffer cmd, Layer layer) const {
    const bool firstPerson = layer == Layer::FirstPerson;
    if (options.reversedZ)
      setViewport(cmd, width, height, firstPerson ? 1.0f - kFirstPersonDeviceDepthMax : 0.0f,
                  firstPerson ? 1.0f : 1.0f - kFirstPersonDeviceDepthMax);
    else
      setViewport(cmd, width, height, firstPerson ? 0.0f : kFirstPersonDeviceDepthMax, firstPerson ? kFirstPersonDeviceDepthMax : 1.0f);
  }

  void setScene(const Scene& newScene) {
    std::vector<Vertex> vertices;
    std::vector<gpu::SurfaceVertex> surface;
    std::vector<std::uint32_t> indices;
    meshRanges.clear();
    for (const Mesh& mesh : newScene.meshes) {
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
    if (newScene.pointLights.size() + newScene.spotLights.size() > 256)
      throw std::invalid_argument("scene has more than 256 point and spot lights");
    if (newScene.ambientOcclusion && !(newScene.ambientOcclusionRadius > 0.0f && newScene.ambientOcclusionRadius < 1e4f))
      throw std::invalid_argument("scene '" + newScene.name + "': ambient-occlusion radius must be in (0, 1e4) world units");

    vertexBuffer = vk::createBuffer(context, vertices.size() * sizeof(Vertex),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    vk::MemoryLocation::Device);
    vk::uploadBuffer(context, vertexBuffer, std::as_bytes(std::span(vertices)));
    surfaceBuffer = vk::createBuffer(context, surface.size() * sizeof(gpu::SurfaceVertex),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     vk::MemoryLocation::Device);
    vk::uploadBuffer(context, surfaceBuffer, std::as_bytes(std::span(surface)));
    textures.clear();
    for (const Texture& texture : newScene.textures) textures.push_back(uploadTexture(texture));
    indexBuffer = vk::createBuffer(context, indices.size() * sizeof(std::uint32_t),
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   vk::MemoryLocation::Device);
    vk::uploadBuffer(context, indexBuffer, std::as_bytes(std::span(indices)));
    objectBuffer = vk::createBuffer(context, std::max<std::size_t>(1, newScene.objects.size()) * sizeof(gpu::ObjectConstants),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryLocation::HostVisible);
    drawOrder.clear();
    transparentOrder.clear();
    for (std::uint32_t i = 0; i < newScene.objects.size(); ++i) {
      const float opacity = newScene.objects[i].material.opacity;
      if (!(opacity > 0.0f && opacity <= 1.0f))
        throw std::invalid_argument("scene '" + newScene.name + "': object " + std::to_string(i) + " has opacity " +
                                    std::to_string(opacity) + " outside (0, 1]");
      if (newScene.objects[i].material.isTransparent() && newScene.objects[i].layer == Layer::FirstPerson)
        throw std::invalid_argument("scene '" + newScene.name + "': transparent first-person objects are not supported");
    }
    for (Layer layer : {Layer::World, Layer::FirstPerson})
      for (std::uint32_t i = 0; i < newScene.objects.size(); ++i)
        if (newScene.objects[i].layer == layer && !newScene.objects[i].material.isTransparent()) drawOrder.push_back(i);
    for (std::uint32_t i = 0; i < newScene.objects.size(); ++i)
      if (newScene.objects[i].material.isTransparent()) transparentOrder.push_back(i);
    std::vector<detail::ShadowMeshRange> shadowRanges;
    for (const MeshRange& range : meshRanges) shadowRanges.push_back({range.firstIndex, range.indexCount, range.vertexOffset});
    shadows->setScene(newScene, vertexBuffer.buffer, indexBuffer.buffer, std::move(shadowRanges));
    scene = newScene;
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

  void writeFrameConstants(const ViewMatrices& view) {
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
    frame.ambientOcclusion = glm::vec4(scene.ambientOcclusionRadius, 0.0f, 0.0f, 0.0f);
    std::memcpy(frameBuffer.mapped, &frame, sizeof(frame));

    auto* objects = static_cast<gpu::ObjectConstants*>(objectBuffer.mapped);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const Object& object = scene.objects[i];
      gpu::ObjectConstants& constants = objects[i];
      constants = {};
      constants.objectToLayer = object.transform;
      constants.objectToWorld = object.layer == Layer::FirstPerson ? view.worldFromCamera * object.transform : object.transform;
      constants.normalToWorld = glm::transpose(glm::inverse(constants.objectToWorld));
      constants.albedo = glm::vec4(object.material.albedo, object.material.opacity);
      constants.specular = glm::vec4(object.material.specularColor, object.material.glossiness);
      constants.layer = object.layer == Layer::FirstPerson ? S3D_LAYER_FIRST_PERSON : S3D_LAYER_WORLD;
      constants.normalScale = object.material.normalTexture == kNoTexture ? 0.0f : object.material.normalScale;
    }
  }

  // The frame and object buffers, the pass's own descriptors (`extra`) and, at textureBinding and the one after
  // it, the object's base-color and normal textures (the 1x1 defaults when it has none).
  void pushGeometryDescriptors(VkCommandBuffer cmd, VkPipelineLayout layout, std::span<VkWriteDescriptorSet> extra,
                               const Material& material, std::uint32_t textureBinding) {
    VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo objectInfo{objectBuffer.buffer, 0, VK_WHOLE_SIZE};
    std::vector<VkWriteDescriptorSet> writes = {vk::uniformBufferWrite(0, &frameInfo), vk::uniformBufferWrite(1, &objectInfo)};
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes.insert(writes.end(), extra.begin(), extra.end());
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

  void drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, const std::vector<std::uint32_t>& objects,
                   std::span<VkWriteDescriptorSet> extra, std::uint32_t textureBinding) {
    const VkDeviceSize offsets[] = {0, 0};
    const VkBuffer streams[] = {vertexBuffer.buffer, surfaceBuffer.buffer};
    vkCmdBindVertexBuffers(cmd, 0, 2, streams, offsets);
    vkCmdBindIndexBuffer(cmd, indexBuffer.buffer, 0, VK_INDEX_TYPE_UINT32);
    std::optional<Layer> currentLayer;
    for (std::uint32_t objectIndex : objects) {
      const Object& object = scene.objects[objectIndex];
      if (currentLayer != object.layer) {
        setLayerViewport(cmd, object.layer);
        currentLayer = object.layer;
      }
      pushGeometryDescriptors(cmd, layout, extra, object.material, textureBinding);  // per object: its textures
      vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                         sizeof(std::uint32_t), &objectIndex);
      const MeshRange& range = meshRanges[object.mesh];
      vkCmdDrawIndexed(cmd, range.indexCount, 1, range.firstIndex, range.vertexOffset, 0);
    }
  }

  void recordGBuffer(VkCommandBuffer cmd) {
    vk::transition(cmd, depth, vk::kUndefined, vk::kDepthAttachment);
    vk::transition(cmd, normalGlossiness, vk::kUndefined, vk::kColorAttachment);
    VkRenderingAttachmentInfo color = colorAttachment(normalGlossiness, true);
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = depth.view;
    depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depthAttachment.clearValue.depthStencil = {clearedDepth(), 0};
    beginRendering(cmd, width, height, std::span(&color, 1), &depthAttachment);
    setScissor(cmd, {{0, 0}, {width, height}});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gbufferPipeline);
    drawObjects(cmd, geometryLayout.layout, drawOrder, {}, kGeometryTextureBinding);
    vkCmdEndRendering(cmd);
    recordGBufferReadable(cmd);  // SSAO, the shadow mask and the light pass read depth and normals
  }

  void pushLightDescriptors(VkCommandBuffer cmd) {
    VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorImageInfo depthInfo{nearestSampler, depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo normalInfo{nearestSampler, normalGlossiness.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo occlusionInfo{nearestSampler, ambientOcclusion.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo maskInfo = shadows->maskDescriptor();
    VkDescriptorImageInfo localShadowInfo = shadows->localAtlasDescriptor();
    VkDescriptorBufferInfo shadowInfo = shadows->constantsDescriptor();
    VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo),     vk::sampledImageWrite(1, &depthInfo),
                                     vk::sampledImageWrite(2, &normalInfo),     vk::sampledImageWrite(3, &occlusionInfo),
                                     vk::sampledImageWrite(4, &maskInfo),       vk::sampledImageWrite(5, &localShadowInfo),
                                     vk::uniformBufferWrite(6, &shadowInfo)};
    for (int i = 1; i <= 5; ++i) writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lightLayout.layout, 0, 7, writes);
  }

  // Starts a light-accumulation render pass instance over the diffuse and specular light buffers.
  void beginLightAccumulation(VkCommandBuffer cmd, bool clear) {
    VkRenderingAttachmentInfo colors[] = {colorAttachment(diffuseLight, clear), colorAttachment(specularLight, clear)};
    beginRendering(cmd, width, height, colors, nullptr);
    setViewport(cmd, width, height, 0.0f, 1.0f);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lightPipeline);
    pushLightDescriptors(cmd);
  }

  // After the G-buffer: depth and normals become readable by the fragment and compute passes that follow.
  void recordGBufferReadable(VkCommandBuffer cmd) {
    vk::transition(cmd, depth, vk::kDepthAttachment, kDepthSampled);
    vk::transition(cmd, normalGlossiness, vk::kColorAttachment, kNormalSampled);
  }

  // SSAO into the ambient-occlusion image (left readable by the light pass).
  void recordAmbientOcclusion(VkCommandBuffer cmd) {
    vk::transition(cmd, ambientOcclusion, vk::kUndefined, vk::kComputeWrite);
    VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorImageInfo depthInfo{nearestSampler, depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo normalInfo{nearestSampler, normalGlossiness.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo occlusionInfo{VK_NULL_HANDLE, ambientOcclusion.view, VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo), vk::sampledImageWrite(1, &depthInfo),
                                     vk::sampledImageWrite(2, &normalInfo), vk::storageImageWrite(3, &occlusionInfo)};
    writes[1].descriptorType = writes[2].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ssaoPipeline);
    context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ssaoLayout.layout, 0, 4, writes);
    vkCmdDispatch(cmd, (width + S3D_COMPUTE_GROUP_SIZE - 1) / S3D_COMPUTE_GROUP_SIZE,
                  (height + S3D_COMPUTE_GROUP_SIZE - 1) / S3D_COMPUTE_GROUP_SIZE, 1);
    vk::transition(cmd, ambientOcclusion, vk::kComputeWrite, kOcclusionSampled);
  }

  // Without SSAO the light pass reads an occlusion of 1 everywhere.
  void recordNoAmbientOcclusion(VkCommandBuffer cmd) {
    vk::transition(cmd, ambientOcclusion, vk::kUndefined, vk::kTransferDestination);
    VkClearColorValue one{{1.0f, 1.0f, 1.0f, 1.0f}};
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, ambientOcclusion.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &one, 1, &range);
    vk::transition(cmd, ambientOcclusion, vk::kTransferDestination, kOcclusionSampled);
  }

  // Hemisphere ambient and the sun: one fullscreen triangle; clears the light buffers.
  void recordSunAndAmbient(VkCommandBuffer cmd, bool withAmbientOcclusion) {
    if (!withAmbientOcclusion) recordNoAmbientOcclusion(cmd);
    shadows->recordReadableForLighting(cmd);
    vk::transition(cmd, diffuseLight, vk::kUndefined, vk::kColorAttachment);
    vk::transition(cmd, specularLight, vk::kUndefined, vk::kColorAttachment);
    beginLightAccumulation(cmd, true);
    gpu::LightConstants sun{};
    sun.kind = S3D_LIGHT_AMBIENT_AND_SUN;
    sun.shadowView = shadows->sunShadowView();
    setScissor(cmd, {{0, 0}, {width, height}});
    vkCmdPushConstants(cmd, lightLayout.layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(sun), &sun);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
  }

  struct VisibleLight {
    gpu::LightConstants constants;
    VkRect2D screenRect;
  };

  // Point and spot lights whose sphere reaches the screen, with the rectangle each can touch (call after the
  // shadow maps are scheduled: a light uses its shadow map only when one renders this frame).
  std::vector<VisibleLight> visiblePointLights(const ViewMatrices& view) const {
    std::vector<VisibleLight> visible;
    const glm::mat4 viewProjection = view.worldProjection * view.worldView;
    for (std::size_t i = 0; i < scene.pointLights.size(); ++i) {
      const PointLight& pointLight = scene.pointLights[i];
      if (std::optional<VkRect2D> rect = lightScissor(pointLight, viewProjection, width, height)) {
        gpu::LightConstants constants{};
        constants.kind = S3D_LIGHT_POINT;
        constants.positionRadius = glm::vec4(pointLight.position, pointLight.radius);
        constants.color = glm::vec4(pointLight.color, 0.0f);
        constants.shadowView = shadows->pointLightShadowView(i);
        visible.push_back({constants, *rect});
      }
    }
    for (std::size_t i = 0; i < scene.spotLights.size(); ++i) {
      const SpotLight& spot = scene.spotLights[i];
      if (std::optional<VkRect2D> rect =
              lightScissor(PointLight{spot.position, spot.color, spot.radius}, viewProjection, width, height)) {
        gpu::LightConstants constants{};
        constants.kind = S3D_LIGHT_SPOT;
        constants.positionRadius = glm::vec4(spot.position, spot.radius);
        constants.color = glm::vec4(spot.color, 0.0f);
        constants.spotDirection = glm::vec4(glm::normalize(spot.direction), 0.0f);
        constants.spotCone = glm::vec4(std::cos(spot.outerConeRadians), std::cos(spot.innerConeRadians), 0.0f, 0.0f);
        constants.shadowView = shadows->spotLightShadowView(i);
        visible.push_back({constants, *rect});
      }
    }
    return visible;
  }

  // Point lights, each scissored to its screen rectangle so it costs only the pixels it can touch.
  void recordPointLights(VkCommandBuffer cmd, const std::vector<VisibleLight>& lights) {
    vk::transition(cmd, diffuseLight, vk::kColorAttachment, vk::kColorAttachment);  // after the sun's writes
    vk::transition(cmd, specularLight, vk::kColorAttachment, vk::kColorAttachment);
    beginLightAccumulation(cmd, false);
    for (const VisibleLight& visible : lights) {
      setScissor(cmd, visible.screenRect);
      vkCmdPushConstants(cmd, lightLayout.layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(visible.constants),
                         &visible.constants);
      vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    vkCmdEndRendering(cmd);
  }

  void recordShading(VkCommandBuffer cmd) {
    vk::transition(cmd, depth, kDepthSampled, kDepthReadOnlyAttachment);
    vk::transition(cmd, diffuseLight, vk::kColorAttachment, vk::kFragmentRead);
    vk::transition(cmd, specularLight, vk::kColorAttachment, vk::kFragmentRead);
    vk::transition(cmd, hdr, vk::kUndefined, vk::kColorAttachment);
    VkRenderingAttachmentInfo color = colorAttachment(hdr, true);
    const VkRenderingAttachmentInfo depthAttachment = readOnlyDepthAttachment(depth);
    beginRendering(cmd, width, height, std::span(&color, 1), &depthAttachment);
    setScissor(cmd, {{0, 0}, {width, height}});

    // The sky triangle sits at z = 1; the viewport maps it onto the cleared far plane (0 with reversed-Z).
    setViewport(cmd, width, height, 0.0f, clearedDepth());
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, skyPipeline);
    VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet skyWrite = vk::uniformBufferWrite(0, &frameInfo);
    context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, skyLayout.layout, 0, 1, &skyWrite);
    vkCmdDraw(cmd, 3, 1, 0, 0);

    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadingPipeline);
    VkDescriptorImageInfo diffuseInfo{nearestSampler, diffuseLight.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo specularInfo{nearestSampler, specularLight.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet extra[] = {vk::sampledImageWrite(2, &diffuseInfo), vk::sampledImageWrite(3, &specularInfo)};
    extra[0].descriptorType = extra[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    drawObjects(cmd, shadingLayout.layout, drawOrder, extra, kShadingTextureBinding);
    vkCmdEndRendering(cmd);
  }

  // Transparent surfaces over the shaded image, back to front, depth-tested against the opaque depth.
  void recordTransparent(VkCommandBuffer cmd, const std::vector<std::uint32_t>& backToFront) {
    vk::transition(cmd, hdr, vk::kColorAttachment, vk::kColorAttachment);  // after the shading pass's writes
    vk::transition(cmd, transparentCoverage, vk::kUndefined, vk::kColorAttachment);
    VkRenderingAttachmentInfo colors[] = {colorAttachment(hdr, false), colorAttachment(transparentCoverage, true)};
    const VkRenderingAttachmentInfo depthAttachment = readOnlyDepthAttachment(depth);
    beginRendering(cmd, width, height, colors, &depthAttachment);
    setScissor(cmd, {{0, 0}, {width, height}});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, transparentPipeline);
    drawObjects(cmd, geometryLayout.layout, backToFront, {}, kGeometryTextureBinding);
    vkCmdEndRendering(cmd);
  }

  // Transparent objects sorted by the view depth of their origin, farthest first.
  std::vector<std::uint32_t> transparentBackToFront(const ViewMatrices& view) const {
    std::vector<std::pair<float, std::uint32_t>> keyed;
    for (std::uint32_t index : transparentOrder)
      keyed.push_back({(view.worldView * scene.objects[index].transform[3]).z, index});
    std::sort(keyed.begin(), keyed.end());  // most negative view z = farthest
    std::vector<std::uint32_t> sorted;
    for (const auto& entry : keyed) sorted.push_back(entry.second);
    return sorted;
  }

  void recordResolve(VkCommandBuffer cmd) {
    vk::transition(cmd, hdr, vk::kColorAttachment, vk::kComputeRead);
    vk::transition(cmd, depth, kDepthReadOnlyAttachment, kComputeSampled);
    vk::transition(cmd, display, vk::kUndefined, vk::kComputeWrite);
    vk::transition(cmd, linearDepth, vk::kUndefined, vk::kComputeWrite);
    vk::transition(cmd, resolvedHdr, vk::kUndefined, vk::kComputeWrite);
    const std::uint32_t groupsX = (outputWidth + S3D_COMPUTE_GROUP_SIZE - 1) / S3D_COMPUTE_GROUP_SIZE;
    const std::uint32_t groupsY = (outputHeight + S3D_COMPUTE_GROUP_SIZE - 1) / S3D_COMPUTE_GROUP_SIZE;
    const gpu::ResolveConstants resolve{int(supersample), int(outputWidth), int(outputHeight), 0};
    VkDescriptorBufferInfo frameInfo{frameBuffer.buffer, 0, VK_WHOLE_SIZE};

    VkDescriptorImageInfo hdrInfo{VK_NULL_HANDLE, hdr.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo displayInfo{VK_NULL_HANDLE, display.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo resolvedHdrInfo{VK_NULL_HANDLE, resolvedHdr.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo depthInfo{nearestSampler, depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo linearInfo{VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[] = {vk::uniformBufferWrite(0, &frameInfo),       vk::storageImageWrite(1, &hdrInfo),
                                     vk::storageImageWrite(2, &displayInfo),      vk::storageImageWrite(3, &resolvedHdrInfo),
                                     vk::sampledImageWrite(4, &depthInfo),        vk::storageImageWrite(5, &linearInfo)};
    writes[4].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolvePipeline);
    context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolveLayout.layout, 0, 6, writes);
    vkCmdPushConstants(cmd, resolveLayout.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(resolve), &resolve);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
  }

  struct ScheduledPass {
    std::string name;
    std::function<void(VkCommandBuffer)> record;
  };

  // The passes this frame needs, in order: a pass that serves nothing in the scene does not run.
  std::vector<ScheduledPass> schedulePasses(const ViewMatrices& view) {
    std::vector<ScheduledPass> passes;
    passes.push_back({"gbuffer", [this](VkCommandBuffer cmd) { recordGBuffer(cmd); }});
    const bool withAmbientOcclusion = scene.ambientOcclusion;
    if (withAmbientOcclusion) passes.push_back({"ssao", [this](VkCommandBuffer cmd) { recordAmbientOcclusion(cmd); }});
    for (detail::ShadowPass& shadowPass : shadows->schedule(view, depth, normalGlossiness, frameBuffer.buffer))
      passes.push_back({std::move(shadowPass.name), std::move(shadowPass.record)});
    passes.push_back({"sun-and-ambient", [this, withAmbientOcclusion](VkCommandBuffer cmd) {
                        recordSunAndAmbient(cmd, withAmbientOcclusion);
                      }});
    std::vector<VisibleLight> lights = visiblePointLights(view);
    if (!lights.empty())
      passes.push_back({"point-lights", [this, lights](VkCommandBuffer cmd) { recordPointLights(cmd, lights); }});
    passes.push_back({"shading", [this](VkCommandBuffer cmd) { recordShading(cmd); }});
    if (!transparentOrder.empty()) {
      std::vector<std::uint32_t> backToFront = transparentBackToFront(view);
      passes.push_back({"transparent", [this, backToFront](VkCommandBuffer cmd) { recordTransparent(cmd, backToFront); }});
    }
    passes.push_back({"resolve", [this](VkCommandBuffer cmd) { recordResolve(cmd); }});
    return passes;
  }

  FrameTimings render(const ViewMatrices& view) {
    if (meshRanges.empty()) throw std::logic_error("DeferredRenderer::render called before setScene");
    writeFrameConstants(view);
    const std::vector<ScheduledPass> passes = schedulePasses(view);
    constexpr VkPipelineStageFlags2 kAll = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    context.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, kAll);
      for (std::uint32_t pass = 0; pass < passes.size(); ++pass) {
        passes[pass].record(cmd);
        timestamps.write(cmd, pass + 1, kAll);
      }
    });
    FrameTimings timings;
    const auto passCount = std::uint32_t(passes.size());
    timings.totalGpuMs = timestamps.elapsedMs(0, passCount);
    for (std::uint32_t pass = 0; pass < passCount; ++pass) {
      PassTiming timing{passes[pass].name, timestamps.elapsedMs(pass, pass + 1).value_or(0.0)};
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
FrameTimings DeferredRenderer::render(const ViewMatrices& view) { return impl_->render(view); }
std::uint32_t DeferredRenderer::width() const { return impl_->outputWidth; }
std::uint32_t DeferredRenderer::height() const { return impl_->outputHeight; }
std::uint32_t DeferredRenderer::supersample() const { return impl_->supersample; }
const RendererOptions& DeferredRenderer::options() const { return impl_->options; }
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
  if (r.transparentOrder.empty()) return mask;  // the transparent pass did not run
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->transparentCoverage, vk::kColorAttachment);
  // With supersampling, an output pixel is transparent where any of its samples is.
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x)
      if (bytes[4 * (std::size_t(y) * r.width + x)] != std::byte{0})
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
  return mask;
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
