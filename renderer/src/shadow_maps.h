#pragma once
// The deferred renderer's shadow passes (seed 003 8.5.3, 000 4.3.3): sun cascades into one depth atlas,
// point-light faces and spot views into a second; the lighting pass reads both (the sun's deferred shadow mask
// is computed there, per pixel, rather than in a screen pass of its own). Planned per frame: a shadow map
// without a caster in its view does not render. Point and spot views depend on the light and the world's casters
// only, so each renders once per scene (setScene) and later frames reuse it; the sun's cascades follow the view.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/renderer/view_matrices.h"
#include "s3d/renderer/renderer_shared.h"
#include "s3d/renderer/shadows.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer::detail {

struct ShadowMeshRange {
  std::uint32_t firstIndex = 0;
  std::uint32_t indexCount = 0;
  std::int32_t vertexOffset = 0;
};

// What cut-out casters need for their alpha test: texture coordinates (the renderer's gpu::SurfaceVertex
// stream, a vertex buffer) and the scene's textures with the sampler the G-buffer reads them with.
struct ShadowTextures {
  VkBuffer surfaceBuffer = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  std::vector<VkImageView> views;  // Scene::textures, uploaded
  VkImageView white = VK_NULL_HANDLE;  // what an untextured cut-out samples
};

struct ShadowPass {
  std::string name;
  std::function<void(VkCommandBuffer)> record;
};

class ShadowMaps {
 public:
  ShadowMaps(vk::Context& context, std::uint32_t width, std::uint32_t height);

  // Validates the scene's shadow settings and sizes the atlases. The buffers stay owned by the renderer.
  void setScene(const Scene& scene, VkBuffer vertexBuffer, VkBuffer indexBuffer, std::vector<ShadowMeshRange> meshRanges,
                ShadowTextures textures);

  // Plans the frame for shadowFitOf(view): which shadow maps have a caster in reach, their matrices (written to the
  // shadow constants), and the passes that render them, in order.
  std::vector<ShadowPass> schedule(const ViewMatrices& view);
  // The camera the last plan was made for (empty before the first plan of the scene): another renderer may
  // light a view of the same fit with these maps.
  const std::optional<ShadowFit>& plannedFit() const { return plannedFit_; }
  // Whether `other` renders the same shadow maps for the same fit: the same casters, lights and map sizes.
  bool castsLike(const ShadowMaps& other) const;

  // Before lighting: both atlases readable by compute (also when not written this frame).
  void recordReadableForLighting(VkCommandBuffer cmd);

  // This frame's plan for the lighting pass: whether the sun's cascades rendered, and each light's first shadow
  // view (-1: unshadowed).
  bool sunShadowed() const { return sunShadowedThisFrame_; }
  int pointLightShadowView(std::size_t light) const { return pointViewsThisFrame_.at(light); }
  int spotLightShadowView(std::size_t light) const { return spotViewsThisFrame_.at(light); }

  // Lighting-pass descriptors: the atlases (compare samplers) and gpu::ShadowConstants.
  VkDescriptorImageInfo sunAtlasDescriptor() const;
  VkDescriptorImageInfo localAtlasDescriptor() const;
  VkDescriptorBufferInfo constantsDescriptor() const;

 private:
  struct LocalShadow {
    glm::vec3 position;
    float radius;
    std::uint32_t firstView;  // in the local atlas
    std::uint32_t viewCount;  // 6 for a point light, 1 for a spot
    bool isPoint;
    std::size_t lightIndex;
    bool rendered = false;  // its views hold this scene's depth (kept from an earlier frame)
  };
  struct ViewDraws {
    glm::mat4 viewProjection;
    VkRect2D tile;
    std::vector<std::uint32_t> casters;  // object indices
  };

  void recordDepthViews(VkCommandBuffer cmd, const vk::Image& atlas, bool sun, const std::vector<ViewDraws>& views,
                        const vk::ImageState& before);
  // The casters a view reaches, nearest the light first.
  std::vector<std::uint32_t> castersIn(const glm::mat4& viewProjection) const;
  // schedule's two halves: the sun's cascades, and the point and spot lights on screen.
  void scheduleSun(const ShadowFit& fit, gpu::ShadowConstants& constants, std::vector<ShadowPass>& passes);
  void scheduleLocalLights(const ShadowFit& fit, gpu::ShadowConstants& constants, std::vector<ShadowPass>& passes);
  // The sun's or the local lights' depth pipeline for a caster's detail::depthVariant, made at first use.
  VkPipeline depthPipeline(bool sun, std::size_t variant);
  void drawCaster(VkCommandBuffer cmd, const Object& object, const glm::mat4& viewProjection);

  vk::Context& context_;
  std::uint32_t width_, height_;
  vk::PipelineLayout depthLayout_, cutoutLayout_;  // cut-out casters: their base-colour texture, uv and cutoff
  vk::GraphicsPipelineDesc sunDepth_, localDepth_;
  std::array<vk::Unique<VkPipeline>, 4> sunDepthPipelines_, localDepthPipelines_;  // per detail::depthVariant
  ShadowTextures textures_;
  vk::Unique<VkSampler> compareSampler_;
  vk::Image sunAtlas_;     // cascades side by side (1x1 when the sun casts no shadows)
  vk::Image localAtlas_;   // local-light views in a grid (1x1 when no light casts)
  vk::Buffer constants_;   // gpu::ShadowConstants

  Scene scene_;
  VkBuffer vertexBuffer_ = VK_NULL_HANDLE, indexBuffer_ = VK_NULL_HANDLE;
  std::vector<ShadowMeshRange> meshRanges_;
  std::vector<std::uint32_t> casters_;            // opaque world-layer objects that cast
  std::vector<BoundingSphere> casterBounds_;      // same order
  std::vector<LocalShadow> localShadows_;
  std::uint32_t localColumns_ = 1;
  std::uint32_t sunMapSize_ = 0, localTileSize_ = 0;  // the sizes in use (see effectiveShadowMapSize)

  // This frame's plan.
  std::optional<ShadowFit> plannedFit_;
  bool sunShadowedThisFrame_ = false;
  bool localAtlasWritten_ = false;
  bool localAtlasKept_ = false;  // the local atlas holds views rendered in earlier frames (left readable)
  std::vector<int> pointViewsThisFrame_, spotViewsThisFrame_;
};

}  // namespace s3d::renderer::detail
