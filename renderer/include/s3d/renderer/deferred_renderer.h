#pragma once
// The deferred renderer (the seed's section 4.3): a G-buffer (depth, normal and glossiness, material), half-
// resolution ambient occlusion, shadow maps, one tiled compute pass for all lighting, shading and the sky, the
// transparent surfaces, then tone mapping and linear depth. It can shade part of an image (ShadeMask).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/image.h"
#include "s3d/renderer/scene.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer {

// Seed 4.6.2: the first-person layer's depth is offset and scaled (pushed into the screen) in the linear
// depth handed to the stereo pass: pushed = offset + scale * depth. Rendering and lighting are unchanged.
// {0, 1} leaves it where it is.
struct FirstPersonDepthPush {
  float offset = 0.0f;  // world units
  float scale = 1.0f;
};

// The camera a frame's shadow maps are planned for: the sun's cascades cover the slices of its frustum (seed 000
// 4.3.3) and the point and spot lights it can see get their maps.
struct ShadowFit {
  glm::mat4 worldView{1.0f};
  glm::mat4 worldProjection{1.0f};
  bool operator==(const ShadowFit&) const = default;
};

// Matrices of one rendered view. Vulkan clip space (y down, depth 0..1).
struct ViewMatrices {
  glm::mat4 worldView{1.0f};        // world -> view of the world layer
  glm::mat4 worldProjection{1.0f};  // may be off-axis (two-pass reference eyes)
  glm::mat4 firstPersonView{1.0f};  // camera space -> first-person view (identity for the center view)
  glm::mat4 firstPersonProjection{1.0f};
  glm::mat4 worldFromCamera{1.0f};  // inverse of the center camera's view: places first-person objects for lighting
  FirstPersonDepthPush firstPersonDepthPush;  // applied to linearDepth() only
  // Where the shadow maps are planned from; empty: this view's own world camera. A stereo frame's eye views name
  // their center view's camera, so every view of the frame has the same shadow maps (the eyes see what the center
  // sees inside the compared columns, whose cascades cover it) and an eye render can reuse the center frame's
  // (DeferredRenderer::render with a shadow source).
  std::optional<ShadowFit> shadowFit;
};

// The camera `view`'s shadow maps are planned from: its shadowFit, else its own world camera.
ShadowFit shadowFitOf(const ViewMatrices& view);

// Perspective projection with Vulkan's downward y and zero-to-one depth.
glm::mat4 vulkanPerspective(float verticalFovRadians, float aspect, float nearPlane, float farPlane);
glm::mat4 cameraView(const Camera& camera);  // world -> view
// The scene camera's center view at the given aspect ratio (width / height).
// Nearest and farthest camera-space depth of the first-person layer's vertices (nullopt: no such layer).
std::optional<glm::vec2> firstPersonDepthRange(const Scene& scene);

// Throws std::invalid_argument for a negative/non-finite offset or a non-positive/non-finite scale.
ViewMatrices centerViewMatrices(const Scene& scene, float aspect, FirstPersonDepthPush push = {});

// Reversed-Z (near/far swapped in the projection): see reversedDepthProjection.
glm::mat4 reversedDepthProjection(const glm::mat4& projection, float nearPlane, float farPlane);

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

struct RendererOptions {
  // Supersampling anti-aliasing: every pass before the resolve runs at supersample x the output size; the
  // resolve averages the samples of each output pixel (seed 4.6's "edge sampling" flaw: aliased edges in the
  // center view cannot be displaced by a fraction of a pixel). 1 (default) to 4.
  std::uint32_t supersample = 1;
  // Reversed-Z depth buffer: cleared to 0, depth test GREATER, near and far swapped in both layers'
  // projections (the world in device depth [0, 0.9], first-person in [0.9, 1]). D32 float then keeps its
  // precision at the far end, where standard Z spends it all near 1. Linear depth is the same either way.
  bool reversedZ = false;
  // Tests: every frame counts what its passes shaded (PassTiming::shadedPixels), with atomic adds per pixel.
  bool countShadedPixels = false;
  // How the G-buffer pass gets each pixel's normal and material (the images agree to half-float rounding).
  enum class GBufferShading {
    Automatic,   // Visibility on GPUs, Raster on CPU devices: measured the faster on each (docs/RESULTS.md)
    Raster,      // the fragment shader evaluates and writes them (a CPU rasterizer interpolates cheaply)
    Visibility,  // fragments write a triangle id only; a compute pass evaluates the surface per pixel (a GPU
                 // whose raster side is a small part of the chip pays per byte a fragment writes)
  };
  GBufferShading gbufferShading = GBufferShading::Automatic;
  // How transparent objects are blended over the lit image (the images agree to half-float rounding and the
  // rare pixel centre on a triangle edge).
  enum class TransparentCompositing {
    Automatic,  // Compute on GPUs, Raster on CPU devices: measured the faster on each (docs/RESULTS.md)
    Raster,     // a blended raster pass: only covered fragments are shaded (cheap on a CPU rasterizer)
    Compute,    // a compute pass per object over the tiles its bounds cover (a GPU whose raster side is a small
                // part of the chip pays per byte a blended fragment reads and writes)
  };
  TransparentCompositing transparentCompositing = TransparentCompositing::Automatic;
};

// "auto", "raster", "visibility"; and back (nullopt for any other name).
const char* gbufferShadingName(RendererOptions::GBufferShading shading);
std::optional<RendererOptions::GBufferShading> gbufferShadingFromName(std::string_view name);

// Which pixels a render shades (the hybrid stereo method renders only the eye pixels displacement gets wrong).
//
// `image`: VK_FORMAT_R32_UINT, exactly the renderer's output size (width() x height()), created with
// VK_IMAGE_USAGE_STORAGE_BIT, in VK_IMAGE_LAYOUT_GENERAL; its writes submitted before render() (render records a
// barrier from any earlier write on its queue, then reads it as a storage image in compute and fragment
// shaders). A pixel is shaded where its value >= threshold, so a classification's bin image can be passed with
// its threshold bin as is (1: every nonzero pixel). With supersampling the value covers all samples of its pixel.
//
// What a masked render does: the G-buffer still rasterizes all geometry, but every pixel outside the mask has
// the nearest depth before it draws, so its fragments fail the depth test before shading; ambient occlusion
// (with a depth-only pass of its own, so its samples see real depth outside the mask) runs on the tiles of the
// mask and their neighbours; lighting and the resolve run on the mask's tiles only (found on the GPU) and skip
// unmasked pixels inside them; shadow maps render as for a full frame (or come from a shadow source: render's
// third argument).
//
// Outputs outside the mask are undefined after a masked render: displayColor, linearDepth, hdrColor and the
// read*() masks there may hold anything (the previous frame, zeros, the depth fill). Inside it they equal the
// unmasked render's (tests: within one 8-bit level and 1e-5 relative depth).
//
// The first masked render creates the masked pipeline variants and, with ambient occlusion, a render-size depth
// image; later renders allocate nothing. render() submits on the context's queue and waits, so the mask may be
// rewritten as soon as it returns.
struct ShadeMask {
  const vk::Image* image = nullptr;
  std::uint32_t threshold = 1;
  // How the shaded pixels' surfaces are found. Raster: the G-buffer pass above. RayCast: the ray-cast visibility
  // pass (raycast_visibility.h) casts the mask's pixels through the BVH given to setSurfaceBvh and the G-buffer
  // resolve, lighting and resolve shade them: no depth clear and no raster pass (compute runs on all of a GPU,
  // the raster side on a small part of it). With ambient occlusion the occlusion's region is cast (the masked
  // tiles and their 8 neighbours), and its samples beyond that region find no surface: near the region's border
  // an occluder further away than a tile is missed (docs/RESULTS.md, "Hybrid by ray casting"). A null image with
  // RayCast casts and shades every pixel.
  enum class Surfaces { Raster, RayCast };
  Surfaces surfaces = Surfaces::Raster;
};

struct SceneBvh;

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
  // G-buffer shading, objects the raster pass shades itself (textured or cut-out: the compute resolve samples no
  // textures), wide visibility ids, supersampling, or transparent objects the raster pass blends (it needs the
  // depth buffer).
  std::optional<std::string> raycastSurfacesRefusal() const;
  // Whether a BVH of the current scene (or pose) was given (setSurfaceBvh).
  bool hasSurfaceBvh() const;
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
