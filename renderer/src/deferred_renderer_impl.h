#pragma once
// DeferredRenderer's internal state and the declarations its files share: deferred_renderer.cpp (the public API and
// the frame's schedule), renderer_setup.cpp, renderer_scene_upload.cpp, renderer_passes.cpp and
// renderer_readback.cpp. Not installed.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/raycast_visibility.h"
#include "s3d/renderer/renderer_shared.h"
#include "ambient_occlusion.h"
#include "gbuffer_resolve.h"
#include "material_variants.h"
#include "resolve_pass.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/timestamps.h"
#include "shadow_maps.h"
#include "tile_lists.h"
#include "tiled_lighting.h"
#include "transparent_pass.h"

namespace s3d::renderer {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // world normal + glossiness
constexpr VkFormat kMaterialFormat = VK_FORMAT_R32G32_UINT;        // packed albedo (gpu::packAlbedo), object index
constexpr VkFormat kNarrowVisibilityFormat = VK_FORMAT_R32_UINT;   // gpu::packVisibility, narrow ids
constexpr VkFormat kWideVisibilityFormat = VK_FORMAT_R32G32_UINT;  // wide ids: object, triangle
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;     // sRGB-encoded by the tone-map pass
constexpr VkFormat kLinearDepthFormat = VK_FORMAT_R32_SFLOAT;

// The G-buffer's targets once drawn: sampled by compute (ambient occlusion, lighting, resolve, counting).
constexpr vk::ImageState kComputeSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

// Timestamps: one before the first pass and one after each (shadow maps: up to 52 passes, the rest up to 9).
constexpr std::uint32_t kMaxPasses = 64;

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
  // Ray-cast surfaces (ShadeMask::Surfaces::RayCast): the pass, and the ids and device depth it writes in place of
  // the G-buffer pass's visibility and depth (storage images the later passes sample); made at setSurfaceBvh.
  std::unique_ptr<RaycastVisibility> raycast;
  vk::Image raycastIds, raycastDepth;
  bool raycastBvhCurrent = false;  // the BVH last given matches the scene (setScene, updateGeometry drop it)
  bool raycastFrame = false;       // the last render ray-cast its surfaces
  bool tilesResetAhead = false;    // the next render's masked tile reset was recorded (recordRaycastPreparation)
  // What the G-buffer resolve samples for ray-cast textured surfaces: per texture (first texel, width, height,
  // sRGB) and every texture's RGBA8 texels; made at setSurfaceBvh for the scene (setScene drops them).
  vk::Buffer surfaceTextureTable, surfaceTexels;
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
  struct MeshRange {
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    std::int32_t vertexOffset = 0;
  };
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

  // Reversed-Z: nearer surfaces have greater device depth.
  VkCompareOp nearer() const { return options.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS; }
  float clearedDepth() const { return options.reversedZ ? 0.0f : 1.0f; }  // the far plane: sky
  float nearestDepth() const { return options.reversedZ ? 1.0f : 0.0f; }  // nothing passes a depth test here

  // renderer_setup.cpp: targets, samplers, layouts and pipelines (material variants made at first use).
  Impl(vk::Context& ctx, std::uint32_t w, std::uint32_t h, RendererOptions rendererOptions);

  void createTargets();

  vk::Image uploadTexture(const Texture& texture);

  void createPipelines();

  // The G-buffer pass's colour attachments (0 normal/glossiness, 1 material, 2 visibility ids): raster shading
  // binds the first two; visibility shading the ids alone, or all three for a scene with textured objects, which
  // write normal and material in the raster pass (gbuffer_marked.frag) while the others write zeros there
  // (visibility_textured.frag) that the G-buffer resolve overwrites.
  std::vector<const vk::Image*> gbufferAttachments() const;

  // The G-buffer pipeline of a material variant (detail::materialVariant), made at first use.
  VkPipeline gbufferPipeline(std::size_t variant);

  vk::Unique<VkPipeline> createGBufferPipeline(std::size_t variant) const;

  // The depth-only pipeline of a detail::depthVariant (bit 0 cut-out, bit 1 double-sided), made at first use.
  VkPipeline depthOnlyPipeline(std::size_t variant);

  // renderer_scene_upload.cpp: the scene's buffers, textures and draw order, checked.
  static glm::uvec2 visibilityPackingFor(const Scene& scene);

  void setScene(const Scene& newScene);

  // The visibility target's format (narrow or wide ids) and whether the G-buffer pass binds normal and material
  // (`textured`: some opaque object is drawn with a material variant) follow the scene; the G-buffer pipelines are
  // made again when either changes.
  void fitGBufferToScene(const Scene& newScene, bool textured);

  // What cut-out shadow casters sample: the uploaded surface stream and textures.
  detail::ShadowTextures shadowTextures() const;

  // A new pose of the scene last set (scene_animation.h): vertices, tangents and object transforms replace the old
  // ones in place; textures, indices and pipelines stay. Everything else must be as setScene left it.
  void updateGeometry(const Scene& newScene);

  void requireSameTopology(const Scene& newScene) const;

  // The mesh's texture coordinates and tangents as the second vertex stream (zeros where it has none).
  static void appendSurfaceVertices(const Scene& scene, const Mesh& mesh, std::vector<gpu::SurfaceVertex>& surface);

  // Cut-out, emission and texture transforms within their ranges (scene.h).
  static void validateMaterialExtras(const Scene& scene, std::uint32_t objectIndex);

  // A texture reference must name a texture of the right encoding, on a mesh that can place it.
  static void validateTextures(const Scene& scene, const Object& object);

  // renderer_passes.cpp: the frame constants and the recording of each pass.
  // A layer's viewport depth range (Listing 4.3): first-person in [0, split], the world in [split, 1]; reversed-Z
  // mirrors both (the world in [0, 1 - split], first-person in [1 - split, 1]).
  glm::vec2 layerDepthRange(Layer layer) const;
  void setLayerViewport(VkCommandBuffer cmd, Layer layer) const;

  void writeFrameConstants(const ViewMatrices& view, const ShadeMask& mask);

  // The frame and object buffers and, at kGeometryTextureBinding and the one after it, the object's base-color
  // and normal textures (the 1x1 defaults when it has none).
  void pushGeometryDescriptors(VkCommandBuffer cmd, const Material& material);

  // How drawObjects picks pipelines: the one bound, or per object its G-buffer or depth-only variant.
  enum class Pipelines { Bound, GBuffer, DepthOnly };

  void drawObjects(VkCommandBuffer cmd, const std::vector<std::uint32_t>& objects, Pipelines pipelines = Pipelines::Bound);

  // Opaque objects nearest first (first-person ones before the world): the depth test then rejects hidden
  // fragments before they write anything, and the raster pass's cost follows the bytes its fragments write.
  void sortFrontToBack(const ViewMatrices& view);

  // A masked render with ambient occlusion needs every pixel's depth (the occlusion samples outside the mask).
  // Under visibility shading of a scene without textured objects the G-buffer's fragments only write ids, so the
  // G-buffer pass rasterizes every pixel and the occlusion reads its depth; otherwise (costly fragments) the
  // G-buffer pass stays within the mask and a depth-only pass gives the occlusion its depth (recordAmbientDepth).
  bool maskedGBufferWritesEveryPixel() const { return visibilityShading && !surfaceTargetsBound && scene.ambientOcclusion; }

  // Masked render: every pixel outside the mask gets the nearest depth, so later depth tests there fail unshaded.
  // `loadOp` CLEAR first clears to the far plane (before the G-buffer), LOAD keeps the G-buffer's depth inside the
  // mask (before the transparent pass, after a G-buffer pass that wrote every pixel). Leaves depth an attachment.
  void recordMaskDepthFill(VkCommandBuffer cmd, const ShadeMask& mask, VkAttachmentLoadOp loadOp);

  // The G-buffer pass: depth, and normal/glossiness and material (raster shading) or visibility ids (visibility
  // shading; textured objects write normal and material too). A masked render first gives every pixel outside
  // the mask the nearest depth, so the geometry's fragments there fail the depth test unshaded, unless the pass
  // writes every pixel (maskedGBufferWritesEveryPixel).
  void recordGBuffer(VkCommandBuffer cmd, const ShadeMask& mask);

  void recordGBufferResolve(VkCommandBuffer cmd, const ShadeMask& mask);

  // What the passes after the G-buffer read as depth and ids this frame: the raster pass's, or the ray cast's.
  const vk::Image& frameDepth() const { return raycastFrame ? raycastDepth : depth; }
  const vk::Image& frameVisibility() const { return raycastFrame ? raycastIds : visibility; }
  std::optional<std::string> raycastRefusal() const;
  void uploadSurfaceTexels();  // surfaceTextureTable and surfaceTexels from the scene's textures
  // The ray-cast visibility pass for the mask's pixels (every pixel with ambient occlusion), left sampled.
  void recordRaycastSurfaces(VkCommandBuffer cmd, const ViewMatrices& view, const ShadeMask& mask);

  // Masked renders with ambient occlusion: every pixel's depth (no fragment work), so the occlusion's samples
  // outside the mask see what an unmasked render's do.
  void recordAmbientDepth(VkCommandBuffer cmd);

  // No transparent pass and no supersampling: the lighting pass writes the resolve's outputs itself.
  bool resolveInLighting() const { return !transparentPass->hasObjects() && supersample == 1; }
  // Where a render writes its display colour: the mask's display target, else its own.
  const vk::Image& displayOutput(const ShadeMask& mask) const {
    return mask.displayTarget ? *mask.displayTarget : display;
  }

  // frameShadows: this renderer's shadow maps, rendered this frame, or a shadow source's (already readable).
  void recordLighting(VkCommandBuffer cmd, const ShadeMask& mask, const detail::ShadowMaps& frameShadows);

  // Transparent surfaces over the lit image, back to front, depth-tested against the opaque depth (in a masked
  // render the depth fill hides them outside the mask too).
  void recordTransparent(VkCommandBuffer cmd, const ViewMatrices& view, const ShadeMask& mask);

  void recordResolve(VkCommandBuffer cmd, const ShadeMask& mask, bool afterTransparent);

  // deferred_renderer.cpp: the frame's schedule and its submission.
  struct ScheduledPass {
    std::string name;
    std::function<void(VkCommandBuffer)> record;
    int counterSlot = -1;  // S3D_COUNT_*: the pass's shaded-pixel counter
  };

  // The passes this frame needs, in order: a pass that serves nothing in the scene does not run, nor shadow maps
  // a shadow source lends.
  std::vector<ScheduledPass> schedulePasses(const ViewMatrices& view, const ShadeMask& mask,
                                            const detail::ShadowMaps* lentShadows);

  void validateMask(const ShadeMask& mask) const;

  // A shadow source's maps, checked to be the ones this view would render (the scene, the size and the fit).
  const detail::ShadowMaps& lentShadowMaps(const ViewMatrices& view, const Impl& source) const;

  // A frame in three steps (render() runs them around one submission; renderConcurrently around one per view):
  // check and schedule; record with a timestamp after each pass; read the timings after the GPU finished.
  std::vector<ScheduledPass> prepareFrame(const ViewMatrices& view, const ShadeMask& mask, const Impl* shadowSource);
  void recordFrame(VkCommandBuffer cmd, const std::vector<ScheduledPass>& passes);
  FrameTimings frameTimings(const std::vector<ScheduledPass>& passes) const;
  FrameTimings render(const ViewMatrices& view, const ShadeMask& mask, const Impl* shadowSource);
};

}  // namespace s3d::renderer
