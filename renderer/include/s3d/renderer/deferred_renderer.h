#pragma once
// The deferred renderer (the seed's section 4.3): a G-buffer (depth, normal and glossiness, material), half-
// resolution ambient occlusion, shadow maps, one tiled compute pass for all lighting, shading and the sky, the
// transparent surfaces, then tone mapping and linear depth. It can shade part of an image (ShadeMask).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/image.h"
#include "s3d/renderer/raycast_visibility.h"
#include "s3d/renderer/renderer_options.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/shade_mask.h"
#include "s3d/renderer/view_matrices.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer {

struct PassTiming {
  std::string name;
  double gpuMs = 0.0;
  // With RendererOptions::countShadedPixels, what the pass shaded: gbuffer, lighting: render pixels (G-buffer:
  // those it wrote); ssao, ssao-blur: half-resolution texels; resolve: output pixels. Empty otherwise.
  std::optional<std::uint64_t> shadedPixels;
};

struct FrameTimings {
  std::optional<double> totalGpuMs;  // empty when the device has no timestamp queries
  std::vector<PassTiming> passes;    // every pass that ran, in order (gpuMs 0 without timestamps)
};

struct SceneBvh;
class DeferredRenderer;

// One view of DeferredRenderer::renderConcurrently: what render() takes, with the renderer that draws it.
struct ConcurrentView {
  DeferredRenderer* renderer = nullptr;
  ViewMatrices view;
  ShadeMask mask;
  const DeferredRenderer* shadowSource = nullptr;  // as render()'s; null: the view renders its own shadow maps
};

struct ConcurrentTimings {
  std::vector<FrameTimings> views;   // each view's own passes, as render() times them (they overlap in time)
  // From the first view's start to the last view's end; empty without timestamps, or where the queues' clocks
  // do not compare (a span shorter than a view's own time).
  std::optional<double> spanGpuMs;
};

class DeferredRenderer {
 public:
  // width x height is the output size (display colour, linear depth, HDR colour, masks). Throws
  // std::invalid_argument for a zero size, a supersample outside 1..4, or a render size above 16384.
  DeferredRenderer(vk::Context& context, std::uint32_t width, std::uint32_t height, RendererOptions options = {});
  ~DeferredRenderer();
  DeferredRenderer(const DeferredRenderer&) = delete;
  DeferredRenderer& operator=(const DeferredRenderer&) = delete;

  // Uploads the scene's meshes and materials; call again when the scene changes.
  void setScene(const Scene& scene);
  // A new pose of the scene last set (poseScene, scene_animation.h): only vertex positions, normals, tangents and
  // object transforms differ. Uploads those and keeps the textures, index buffers and pipelines (setScene re-uploads
  // every texture: docs/RESULTS.md, "Animated scenes"). Throws std::invalid_argument naming the scene when its
  // meshes' sizes or indices, objects' meshes, layers or textures, or the texture count differ from the last set.
  void updateGeometry(const Scene& scene);
  // The BVH ShadeMask::Surfaces::RayCast renders cast through: SceneBvh::build of the scene last set (or posed
  // by updateGeometry), uploaded once. setScene and updateGeometry drop it, since it no longer matches.
  void setSurfaceBvh(const SceneBvh& bvh);
  // Why this renderer cannot ray-cast its surfaces for the scene last set (nullopt: it can, given a BVH): raster
  // G-buffer shading, wide visibility ids, more texels than one storage buffer of the device spans, supersampling,
  // or transparent objects the raster pass blends (it needs the depth buffer). Textured, double-sided and cut-out
  // objects are cast: the rays run cut-outs' alpha test, the compute resolve samples the texels and flips back faces.
  std::optional<std::string> raycastSurfacesRefusal() const;
  // Whether a BVH of the current scene (or pose) was given (setSurfaceBvh).
  bool hasSurfaceBvh() const;
  // One step of ray-cast surfaces' work for `view` that no mask decides (RaycastVisibility::recordPreparation,
  // with its ordering rules), recorded by the caller ahead of this renderer's next ray-cast render of the same
  // view, which then skips it: the triangles' setup and screen bins can run beside the caller's other dispatches
  // (the hybrid's classification). The Setup step also records the tile lists' reset for the next render (a masked
  // one skips its own), so the caller orders Setup after this renderer's previous render; nothing else may render
  // with this renderer in between. Throws std::invalid_argument without a BVH (setSurfaceBvh).
  void recordRaycastPreparation(VkCommandBuffer cmd, const ViewMatrices& view, RaycastVisibility::PreparationStep step);
  // Renders one view; the results stay on the GPU until read back. With a mask (its image non-null), only the
  // mask's pixels (ShadeMask). Throws std::invalid_argument for a mask of another size or format, or for a RayCast
  // mask this renderer refuses (raycastSurfacesRefusal) or has no BVH for.
  FrameTimings render(const ViewMatrices& view, const ShadeMask& mask = {});
  // The same, lit with the shadow maps `shadowSource` rendered for its last frame instead of rendering its own (a
  // stereo frame's eye renders reuse the center frame's): no shadow pass runs. shadowSource must hold the same
  // scene (setScene with equal scenes), have the same render size, and its last frame's shadowFitOf must equal
  // `view`'s; its maps are read in this render's lighting pass on the same queue, after its own frame made them
  // readable, so they must not be re-rendered until this render returns (render() waits for the GPU). Throws
  // std::invalid_argument when shadowSource has no frame or another scene, size or shadow fit.
  FrameTimings render(const ViewMatrices& view, const ShadeMask& mask, const DeferredRenderer& shadowSource);
  // Several views at once, each by its own renderer (as its render() would, with the same checks and results):
  // the first view's passes on the context's main queue, the others' on its compute queue where the device has
  // one (vk::Context::hasConcurrentQueue) and they are compute-only frames (ray-cast surfaces lit with a shadow
  // source's maps), so one view's small passes fill the GPU while another's wait on their barriers; otherwise one
  // after the other on the main queue. The renderers share a context; none appears twice or lends its shadows to
  // another view of the call (it would be read while written). Waits for the GPU.
  static ConcurrentTimings renderConcurrently(std::span<const ConcurrentView> views);

  std::uint32_t width() const;   // output size
  std::uint32_t height() const;
  std::uint32_t supersample() const;
  const RendererOptions& options() const;
  // The G-buffer shading this renderer runs (Automatic resolved for its device).
  RendererOptions::GBufferShading gbufferShading() const;

  // Outputs of the last render(), left in VK_IMAGE_LAYOUT_GENERAL (vk::kComputeWrite state):
  const vk::Image& displayColor() const;  // RGBA8, tone-mapped, sRGB-encoded
  const vk::Image& linearDepth() const;   // R32F, view depth in world units, +inf for sky (Listing 4.3), weapon pushed
  const vk::Image& hdrColor() const;      // RGBA16F, linear HDR before exposure and tone mapping (resolved)
  // The device depth at render size (D32_SFLOAT, or R32_SFLOAT after a ray-cast render), left in
  // VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL for compute to sample; after a masked render, valid on the mask only.
  const vk::Image& deviceDepth() const;

  ImageRGBA8 readDisplayColor();
  DepthImage readLinearDepth();
  ImageRGBA32F readHdrColor();
  // 1 where the last frame's visible surface belongs to the first-person layer (Listing 4.3's depth range);
  // with supersampling, where any sample of the output pixel does (its linear depth is the weapon's then).
  std::vector<std::uint8_t> readFirstPersonMask();
  // 1 where a transparent surface covers the last frame's pixel (its blended coverage is above 0); all 0 when
  // the scene has no transparent objects (the error metrics' transparent region).
  std::vector<std::uint8_t> readTransparentMask();
  // 1 where the last frame's visible surface is an alpha cut-out (Material::isCutout, glTF alphaMode MASK) of
  // the opaque pass (a transparent surface in front does not change it); with supersampling, where any sample
  // of the output pixel is. All 0 when the scene has none (the error metrics' foliage region).
  std::vector<std::uint8_t> readCutoutMask();
  // Under visibility G-buffer shading with narrow ids, the last frame's visibility ids at render size
  // (gpu::packVisibility; undefined where nothing was drawn: the linear depth is +inf there); empty otherwise.
  // What the ray-cast visibility pass (raycast_visibility.h) is held to.
  std::vector<std::uint32_t> readVisibilityIds();

  // Device depth values that separate the layers (Listing 4.3): first-person depth is in [0, split]
  // ([1 - split, 1] with reversed-Z).
  static constexpr float kFirstPersonDeviceDepthMax = 0.1f;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace s3d::renderer
