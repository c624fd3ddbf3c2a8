#include "shadow_maps.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <optional>
#include <stdexcept>

#include <glm/gtc/constants.hpp>

#include "material_variants.h"
#include "s3d/vk/check.h"

// clang-format off
#include <cstdint>
#include <s3d_spirv/shadow_cutout_frag.h>
#include <s3d_spirv/shadow_cutout_vert.h>
#include <s3d_spirv/shadow_depth_frag.h>
#include <s3d_spirv/shadow_depth_vert.h>
// clang-format on

namespace s3d::renderer::detail {
namespace {

// 16-bit depth: the maps' raster cost follows the bytes cleared and written (D32 against D16: docs/RESULTS.md,
// "What did not work"). Resolution: the sun cascades' boxes span tens of metres
// (a millimetre a step, far under the 2 cm receiver bias); a local light's perspective map over its radius.
constexpr VkFormat kShadowDepthFormat = VK_FORMAT_D16_UNORM;
constexpr std::uint32_t kLocalAtlasColumns = 8;
// Receiver-side constant bias of the sun lookup (seed 000 4.3.3: "a constant depth bias was used during deferred
// shadow passes"), in world units along the sunlight.
constexpr float kSunReceiverBias = 0.02f;
// Slope-scaled rasterizer bias in units of the depth slope per texel: sun casters render their front faces, so
// lit surfaces compare against their own depth; local lights render back faces and need less.
constexpr float kSunSlopeBias = 2.0f;
constexpr float kLocalSlopeBias = 1.0f;

// Push constants of a cut-out caster (shadow_cutout.vert/.frag).
struct CutoutCaster {
  glm::mat4 objectToClip;
  glm::vec4 uvRows;       // the base-colour texture transform, as gpu::ObjectConstants packs it
  glm::vec2 uvOffset;
  glm::vec2 alphaCutoff;  // x: the material's coverage alpha, y: its cutoff
};

constexpr vk::ImageState kSampledByLighting{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

vk::Unique<VkSampler> createCompareSampler(const vk::Context& context) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.compareEnable = VK_TRUE;
  info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit where the receiver is no farther than the nearest caster
  info.maxLod = 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
  return vk::Unique<VkSampler>(context.device(), sampler, vkDestroySampler);
}

// The shadow-map size actually used: the requested one, but no more than about two texels per screen pixel
// along the longer screen side (never under 256), so tiny test images do not pay for megapixel maps.
std::uint32_t effectiveShadowMapSize(std::uint32_t requested, std::uint32_t width, std::uint32_t height) {
  return std::min(requested, std::max(256u, std::bit_ceil(2u * std::max(width, height))));
}

// Depth per world unit of an orthographic light view-projection (its third row).
float depthPerWorldUnit(const glm::mat4& viewProjection) {
  return glm::length(glm::vec3(viewProjection[0][2], viewProjection[1][2], viewProjection[2][2]));
}

}  // namespace

ShadowMaps::ShadowMaps(vk::Context& context, std::uint32_t width, std::uint32_t height)
    : context_(context), width_(width), height_(height) {
  depthLayout_ = vk::createPushDescriptorLayout(context_, {}, sizeof(glm::mat4), VK_SHADER_STAGE_VERTEX_BIT);
  const VkDescriptorSetLayoutBinding texture{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
                                             nullptr};
  cutoutLayout_ = vk::createPushDescriptorLayout(context_, {&texture, 1}, sizeof(CutoutCaster),
                                                 VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);

  vk::GraphicsPipelineDesc depth;
  depth.vertexSpirv = spirv_shadow_depth_vert;
  depth.fragmentSpirv = spirv_shadow_depth_frag;
  depth.vertexBindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  depth.vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)}};
  depth.depthFormat = kShadowDepthFormat;
  depth.depthTest = true;
  depth.depthWrite = true;
  depth.depthCompare = VK_COMPARE_OP_LESS;
  // Seed 000 4.3.3 ("shadow acne"): the sun renders front faces with slope-scaled bias, local lights back faces.
  vk::GraphicsPipelineDesc sun = depth;
  sun.cullMode = VK_CULL_MODE_BACK_BIT;
  sun.depthBiasSlope = kSunSlopeBias;
  sunDepth_ = sun;
  sunDepthPipelines_[0] = vk::createGraphicsPipeline(context_, depthLayout_.layout, sun);
  vk::GraphicsPipelineDesc local = depth;
  local.cullMode = VK_CULL_MODE_FRONT_BIT;
  local.depthBiasSlope = kLocalSlopeBias;
  localDepth_ = local;
  localDepthPipelines_[0] = vk::createGraphicsPipeline(context_, depthLayout_.layout, local);

  compareSampler_ = createCompareSampler(context_);
  // 1x1 placeholders until a scene needs an atlas: the lighting pass binds both every frame.
  sunAtlas_ = vk::createImage(context_, kShadowDepthFormat, 1, 1,
                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  localAtlas_ = vk::createImage(context_, kShadowDepthFormat, 1, 1,
                                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  constants_ = vk::createBuffer(context_, sizeof(gpu::ShadowConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                vk::MemoryLocation::HostVisible);
}

// Variants: double-sided casters render both faces; cut-outs add the alpha test (shadow_cutout.*), which reads
// texture coordinates from the second vertex stream.
VkPipeline ShadowMaps::depthPipeline(bool sun, std::size_t variant) {
  vk::Unique<VkPipeline>& pipeline = (sun ? sunDepthPipelines_ : localDepthPipelines_)[variant];
  if (!pipeline) {
    vk::GraphicsPipelineDesc desc = sun ? sunDepth_ : localDepth_;
    if ((variant & 2) != 0) desc.cullMode = VK_CULL_MODE_NONE;
    const bool cutout = (variant & 1) != 0;
    if (cutout) {
      desc.vertexSpirv = spirv_shadow_cutout_vert;
      desc.fragmentSpirv = spirv_shadow_cutout_frag;
      desc.vertexBindings.push_back({1, sizeof(gpu::SurfaceVertex), VK_VERTEX_INPUT_RATE_VERTEX});
      desc.vertexAttributes.push_back({1, 1, VK_FORMAT_R32G32_SFLOAT, offsetof(gpu::SurfaceVertex, texCoord)});
    }
    pipeline = vk::createGraphicsPipeline(context_, cutout ? cutoutLayout_.layout : depthLayout_.layout, desc);
  }
  return pipeline;
}

namespace {

// The sun's cascades and shadow map, and every spot light's cone, as the shadow views need them; throws
// std::invalid_argument naming the scene (`prefix`) and the setting.
void requireShadowLights(const Scene& scene, const std::string& prefix) {
  const SunLight& sun = scene.sun;
  if (sun.castsShadows) {
    if (sun.cascadeCount < 1 || sun.cascadeCount > S3D_MAX_SUN_CASCADES)
      throw std::invalid_argument(prefix + "sun cascade count must be 1..4 (got " + std::to_string(sun.cascadeCount) + ")");
    if (sun.shadowMapSize < 16 || sun.shadowMapSize > 4096)
      throw std::invalid_argument(prefix + "sun shadow-map size must be 16..4096 (got " +
                                  std::to_string(sun.shadowMapSize) + ")");
    if (!(sun.shadowDistance > 0.0f && std::isfinite(sun.shadowDistance)))
      throw std::invalid_argument(prefix + "sun shadow distance must be finite and > 0");
  }
  for (const SpotLight& spot : scene.spotLights)
    if (!(spot.innerConeRadians >= 0.0f && spot.innerConeRadians <= spot.outerConeRadians &&
          spot.outerConeRadians > 0.0f && spot.outerConeRadians < 0.5f * glm::pi<float>() && spot.radius > 0.0f &&
          glm::length(spot.direction) > 0.0f))
      throw std::invalid_argument(prefix + "a spot light needs 0 <= inner <= outer < pi/2 cone angles, a radius > 0 "
                                           "and a direction");
}

}  // namespace

void ShadowMaps::setScene(const Scene& scene, VkBuffer vertexBuffer, VkBuffer indexBuffer,
                          std::vector<ShadowMeshRange> meshRanges, ShadowTextures textures) {
  const std::string prefix = "scene '" + scene.name + "': ";
  const SunLight& sun = scene.sun;
  requireShadowLights(scene, prefix);

  localShadows_.clear();
  localAtlasKept_ = false;  // a new scene's lights render again
  std::uint32_t views = 0;
  for (std::size_t i = 0; i < scene.pointLights.size(); ++i)
    if (scene.pointLights[i].castsShadows) {
      localShadows_.push_back({scene.pointLights[i].position, scene.pointLights[i].radius, views, 6, true, i});
      views += 6;
    }
  for (std::size_t i = 0; i < scene.spotLights.size(); ++i)
    if (scene.spotLights[i].castsShadows) {
      localShadows_.push_back({scene.spotLights[i].position, scene.spotLights[i].radius, views, 1, false, i});
      views += 1;
    }
  if (views > S3D_MAX_LOCAL_SHADOW_VIEWS)
    throw std::invalid_argument(prefix + "shadowed point and spot lights need " + std::to_string(views) +
                                " shadow views, at most " + std::to_string(S3D_MAX_LOCAL_SHADOW_VIEWS) +
                                " (a point light takes 6, a spot light 1)");
  if (views > 0 && (scene.localShadowMapSize < 16 || scene.localShadowMapSize > 2048))
    throw std::invalid_argument(prefix + "local shadow-map size must be 16..2048 (got " +
                                std::to_string(scene.localShadowMapSize) + ")");
  sunMapSize_ = effectiveShadowMapSize(sun.shadowMapSize, width_, height_);
  localTileSize_ = effectiveShadowMapSize(scene.localShadowMapSize, width_, height_);
  const std::uint32_t tile = localTileSize_;

  // Allocate only what the scene can use; a later setScene with the same sizes keeps the images.
  {
    const std::uint32_t w = sun.castsShadows ? sun.cascadeCount * sunMapSize_ : 1;
    const std::uint32_t h = sun.castsShadows ? sunMapSize_ : 1;
    if (sunAtlas_.width != w || sunAtlas_.height != h)
      sunAtlas_ = vk::createImage(context_, kShadowDepthFormat, w, h,
                                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  }
  localColumns_ = std::max(1u, std::min(views, kLocalAtlasColumns));
  const std::uint32_t atlasWidth = views > 0 ? localColumns_ * tile : 1;
  const std::uint32_t atlasHeight = views > 0 ? (views + localColumns_ - 1) / localColumns_ * tile : 1;
  if (localAtlas_.width != atlasWidth || localAtlas_.height != atlasHeight)
    localAtlas_ = vk::createImage(context_, kShadowDepthFormat, atlasWidth, atlasHeight,
                                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);

  // Casters: opaque world-layer objects (the weapon's world position follows the camera; glass would need
  // translucency maps, seed 000 4.3.3, left out).
  casters_.clear();
  casterBounds_.clear();
  for (std::uint32_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    if (!object.castsShadow || object.layer != Layer::World || object.material.opacity < 1.0f) continue;
    casters_.push_back(i);
    casterBounds_.push_back(objectBounds(scene.meshes.at(object.mesh), object.transform));
  }
  // What the shadow views read (lights, camera, objects), not the textures' pixels: DeferredRenderer::updateGeometry
  // sets a new pose every frame and must not copy them again.
  scene_ = Scene{};
  scene_.sun = scene.sun;
  scene_.pointLights = scene.pointLights;
  scene_.spotLights = scene.spotLights;
  scene_.camera = scene.camera;
  scene_.objects = scene.objects;
  plannedFit_.reset();
  vertexBuffer_ = vertexBuffer;
  indexBuffer_ = indexBuffer;
  meshRanges_ = std::move(meshRanges);
  textures_ = std::move(textures);
}

bool ShadowMaps::castsLike(const ShadowMaps& other) const {
  auto sameSpheres = [](const std::vector<BoundingSphere>& a, const std::vector<BoundingSphere>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const BoundingSphere& x, const BoundingSphere& y) {
      return x.center == y.center && x.radius == y.radius;
    });
  };
  auto samePoints = [](const std::vector<PointLight>& a, const std::vector<PointLight>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const PointLight& x, const PointLight& y) {
      return x.position == y.position && x.radius == y.radius && x.castsShadows == y.castsShadows;
    });
  };
  auto sameSpots = [](const std::vector<SpotLight>& a, const std::vector<SpotLight>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const SpotLight& x, const SpotLight& y) {
      return x.position == y.position && x.direction == y.direction && x.outerConeRadians == y.outerConeRadians &&
             x.radius == y.radius && x.castsShadows == y.castsShadows;
    });
  };
  auto sameMeshes = [](const std::vector<ShadowMeshRange>& a, const std::vector<ShadowMeshRange>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const ShadowMeshRange& x, const ShadowMeshRange& y) {
      return x.indexCount == y.indexCount;
    });
  };
  const SunLight& sun = scene_.sun;
  const SunLight& otherSun = other.scene_.sun;
  return casters_ == other.casters_ && sameSpheres(casterBounds_, other.casterBounds_) &&
         sameMeshes(meshRanges_, other.meshRanges_) && samePoints(scene_.pointLights, other.scene_.pointLights) &&
         sameSpots(scene_.spotLights, other.scene_.spotLights) && sun.castsShadows == otherSun.castsShadows &&
         sun.directionToSun == otherSun.directionToSun && sun.color == otherSun.color &&
         sun.cascadeCount == otherSun.cascadeCount && sun.shadowDistance == otherSun.shadowDistance &&
         scene_.camera.nearPlane == other.scene_.camera.nearPlane &&
         scene_.camera.farPlane == other.scene_.camera.farPlane && sunMapSize_ == other.sunMapSize_ &&
         localTileSize_ == other.localTileSize_;
}

std::vector<ShadowPass> ShadowMaps::schedule(const ViewMatrices& view) {
  const ShadowFit fit = shadowFitOf(view);
  plannedFit_ = fit;
  gpu::ShadowConstants constants{};
  std::vector<ShadowPass> passes;
  sunShadowedThisFrame_ = false;
  localAtlasWritten_ = false;
  pointViewsThisFrame_.assign(scene_.pointLights.size(), -1);
  spotViewsThisFrame_.assign(scene_.spotLights.size(), -1);
  scheduleSun(fit, constants, passes);
  scheduleLocalLights(fit, constants, passes);
  std::memcpy(constants_.mapped, &constants, sizeof(constants));
  return passes;
}

// Nearest the light first: the depth test then rejects hidden fragments before they write (the map is the nearest
// depth whatever the order).
std::vector<std::uint32_t> ShadowMaps::castersIn(const glm::mat4& viewProjection) const {
  std::vector<std::pair<float, std::uint32_t>> keyed;
  for (std::size_t i = 0; i < casters_.size(); ++i)
    if (sphereTouchesFrustum(viewProjection, casterBounds_[i])) {
      const glm::vec4 clip = viewProjection * glm::vec4(casterBounds_[i].center, 1.0f);
      keyed.push_back({clip.w > 0.0f ? clip.z / clip.w : -1.0f, casters_[i]});
    }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> inView;
  for (const auto& entry : keyed) inView.push_back(entry.second);
  return inView;
}

void ShadowMaps::scheduleSun(const ShadowFit& fit, gpu::ShadowConstants& constants, std::vector<ShadowPass>& passes) {
  // Sun cascades: only with casters, and a cascade only with a caster in its box.
  const SunLight& sun = scene_.sun;
  const float shadowFar = std::min(sun.shadowDistance, scene_.camera.farPlane);
  const bool sunLit = glm::length(sun.color) > 0.0f;
  if (sun.castsShadows && sunLit && !casters_.empty() && shadowFar > scene_.camera.nearPlane) {
    const std::vector<float> splits = cascadeSplitDistances(scene_.camera.nearPlane, shadowFar, sun.cascadeCount);
    const std::vector<SunCascade> cascades = sunCascades(fit.worldView, fit.worldProjection, splits,
                                                         sun.directionToSun, sunMapSize_, casterBounds_);
    const float count = float(cascades.size());
    constants.sunShadow = glm::vec4(count, 1.0f / float(sunAtlas_.width), 1.0f / float(sunAtlas_.height), 0.0f);
    bool first = true;
    for (std::uint32_t i = 0; i < cascades.size(); ++i) {
      ViewDraws draws{cascades[i].viewProjection,
                      {{std::int32_t(i * sunMapSize_), 0}, {sunMapSize_, sunMapSize_}},
                      castersIn(cascades[i].viewProjection)};
      const bool rendered = !draws.casters.empty();
      constants.cascadeViewProjection[i] = cascades[i].viewProjection;
      constants.cascadeAtlasRect[i] = glm::vec4(float(i) / count, 0.0f, 1.0f / count, 1.0f);
      constants.cascadeParams[i] = glm::vec4(cascades[i].texelWorldSize, rendered ? 1.0f : 0.0f,
                                             kSunReceiverBias * depthPerWorldUnit(cascades[i].viewProjection), 0.0f);
      if (!rendered) continue;
      const vk::ImageState before = first ? vk::kUndefined : vk::kDepthAttachment;
      passes.push_back({"shadow-sun-cascade-" + std::to_string(i), [this, draws, before](VkCommandBuffer cmd) {
                          recordDepthViews(cmd, sunAtlas_, true, {draws}, before);
                        }});
      first = false;
    }
    sunShadowedThisFrame_ = !first;
  }
}

void ShadowMaps::scheduleLocalLights(const ShadowFit& fit, gpu::ShadowConstants& constants,
                                     std::vector<ShadowPass>& passes) {
  // Point and spot lights on screen, each only with a caster in one of its views.
  const glm::mat4 cameraViewProjection = fit.worldProjection * fit.worldView;
  const std::uint32_t tile = localTileSize_;
  constants.localShadow = glm::vec4(1.0f / float(localAtlas_.width), 1.0f / float(localAtlas_.height), 0.0f, 0.0f);
  for (LocalShadow& local : localShadows_) {
    if (!sphereTouchesFrustum(cameraViewProjection, {local.position, local.radius})) continue;
    std::vector<ViewDraws> views;
    bool anyCaster = false;
    for (std::uint32_t v = 0; v < local.viewCount; ++v) {
      const std::uint32_t index = local.firstView + v;
      const glm::mat4 viewProjection = local.isPoint
                                           ? pointLightFaceViewProjection(scene_.pointLights[local.lightIndex], v)
                                           : spotLightViewProjection(scene_.spotLights[local.lightIndex]);
      const float halfAngle = local.isPoint ? 0.25f * glm::pi<float>() : scene_.spotLights[local.lightIndex].outerConeRadians;
      const std::uint32_t column = index % localColumns_, row = index / localColumns_;
      views.push_back({viewProjection,
                       {{std::int32_t(column * tile), std::int32_t(row * tile)}, {tile, tile}},
                       castersIn(viewProjection)});
      anyCaster = anyCaster || !views.back().casters.empty();
      constants.localViewProjection[index] = viewProjection;
      constants.localAtlasRect[index] =
          glm::vec4(float(column * tile) / float(localAtlas_.width), float(row * tile) / float(localAtlas_.height),
                    float(tile) / float(localAtlas_.width), float(tile) / float(localAtlas_.height));
      constants.localParams[index] = glm::vec4(2.0f * std::tan(halfAngle) / float(tile), 0.0f, 0.0f, 0.0f);
    }
    if (!anyCaster) continue;  // nothing can shadow it: lit as an unshadowed light
    (local.isPoint ? pointViewsThisFrame_ : spotViewsThisFrame_)[local.lightIndex] = int(local.firstView);
    // Its views depend on the light and the world's casters only: rendered once per scene, then kept.
    if (local.rendered) continue;
    local.rendered = true;
    // The frame's first local pass keeps what earlier frames rendered into the atlas (lighting left it readable).
    const vk::ImageState before =
        localAtlasWritten_ ? vk::kDepthAttachment : localAtlasKept_ ? kSampledByLighting : vk::kUndefined;
    localAtlasWritten_ = true;
    const std::string name = std::string(local.isPoint ? "shadow-point-" : "shadow-spot-") + std::to_string(local.lightIndex);
    passes.push_back({name, [this, views, before](VkCommandBuffer cmd) {
                        recordDepthViews(cmd, localAtlas_, false, views, before);
                      }});
  }
}

void ShadowMaps::recordDepthViews(VkCommandBuffer cmd, const vk::Image& atlas, bool sun,
                                  const std::vector<ViewDraws>& views, const vk::ImageState& before) {
  vk::transition(cmd, atlas, before, vk::kDepthAttachment);
  VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthAttachment.imageView = atlas.view;
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // other tiles keep what earlier passes wrote
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {atlas.width, atlas.height}};
  info.layerCount = 1;
  info.pDepthAttachment = &depthAttachment;
  vkCmdBeginRendering(cmd, &info);
  const VkBuffer vertexStreams[] = {vertexBuffer_, textures_.surfaceBuffer};
  const VkDeviceSize offsets[] = {0, 0};
  vkCmdBindVertexBuffers(cmd, 0, 2, vertexStreams, offsets);
  vkCmdBindIndexBuffer(cmd, indexBuffer_, 0, VK_INDEX_TYPE_UINT32);
  for (const ViewDraws& draws : views) {
    VkClearAttachment clear{VK_IMAGE_ASPECT_DEPTH_BIT, 0, {}};
    clear.clearValue.depthStencil = {1.0f, 0};
    VkClearRect rect{draws.tile, 0, 1};
    vkCmdClearAttachments(cmd, 1, &clear, 1, &rect);
    VkViewport viewport{float(draws.tile.offset.x), float(draws.tile.offset.y), float(draws.tile.extent.width),
                        float(draws.tile.extent.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &draws.tile);
    std::optional<std::size_t> bound;
    for (std::uint32_t objectIndex : draws.casters) {
      const Object& object = scene_.objects[objectIndex];
      const std::size_t variant = depthVariant(object.material);
      if (bound != variant) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, depthPipeline(sun, variant));
      bound = variant;
      drawCaster(cmd, object, draws.viewProjection);
    }
  }
  vkCmdEndRendering(cmd);
}

void ShadowMaps::drawCaster(VkCommandBuffer cmd, const Object& object, const glm::mat4& viewProjection) {
  const Material& material = object.material;
  if (material.isCutout()) {
    const std::int32_t texture = material.baseColorTexture;
    const VkDescriptorImageInfo image{textures_.sampler,
                                      texture == kNoTexture ? textures_.white : textures_.views.at(std::size_t(texture)),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet write = vk::sampledImageWrite(0, &image);
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    context_.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, cutoutLayout_.layout, 0, 1, &write);
    const glm::mat3 uv = material.baseColorTransform.matrix();
    const CutoutCaster caster{viewProjection * object.transform, glm::vec4(uv[0][0], uv[1][0], uv[0][1], uv[1][1]),
                              glm::vec2(uv[2]), glm::vec2(material.cutoutAlpha, material.alphaCutoff)};
    vkCmdPushConstants(cmd, cutoutLayout_.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(caster), &caster);
  } else {
    const glm::mat4 objectToClip = viewProjection * object.transform;
    vkCmdPushConstants(cmd, depthLayout_.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(objectToClip), &objectToClip);
  }
  const ShadowMeshRange& range = meshRanges_[object.mesh];
  vkCmdDrawIndexed(cmd, range.indexCount, 1, range.firstIndex, range.vertexOffset, 0);
}

void ShadowMaps::recordReadableForLighting(VkCommandBuffer cmd) {
  vk::transition(cmd, sunAtlas_, sunShadowedThisFrame_ ? vk::kDepthAttachment : vk::kUndefined, kSampledByLighting);
  vk::transition(cmd, localAtlas_,
                 localAtlasWritten_ ? vk::kDepthAttachment : localAtlasKept_ ? kSampledByLighting : vk::kUndefined,
                 kSampledByLighting);
  localAtlasKept_ = localAtlasKept_ || localAtlasWritten_;
}

VkDescriptorImageInfo ShadowMaps::sunAtlasDescriptor() const {
  return {compareSampler_, sunAtlas_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

VkDescriptorImageInfo ShadowMaps::localAtlasDescriptor() const {
  return {compareSampler_, localAtlas_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

VkDescriptorBufferInfo ShadowMaps::constantsDescriptor() const { return {constants_.buffer, 0, VK_WHOLE_SIZE}; }

}  // namespace s3d::renderer::detail
