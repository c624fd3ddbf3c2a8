#pragma once
// The hybrid stereo method with s3d's deferred renderer: displace both eyes (the base method), classify the
// pixels the displacement gets wrong and mask the budget's worst ones (stereo::HybridPass), render exactly those
// pixels from each real eye camera (the two-pass reference's cameras; their surfaces ray-cast where the renderer
// can, docs/DESIGN.md "Hybrid"), and composite them into the displaced eyes. A host with its own renderer does the same with HybridPass and its renderer (docs/DESIGN.md).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "s3d/image.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::frame {

// GPU milliseconds of one hybrid frame, both eyes (empty without timestamps).
struct HybridTimings {
  std::optional<double> displacement;    // the base method's pass
  std::optional<double> classification;  // classification, threshold and masks (the sum of the next three)
  std::optional<double> classify, threshold, mask;  // each of the three passes
  std::optional<double> eyeGeometry;     // both eyes' surfaces: rasterized ("gbuffer", "ssao-depth") or ray-cast
                                         // ("raycast", and baseDepth)
  std::optional<double> baseDepth;       // ray-cast eyes with ambient occlusion: both eyes' base depth (else 0)
  std::optional<double> maskedShading;   // both eyes' other passes (mask tiles, SSAO, lighting, resolve; the
                                         // shadow maps are the center frame's)
  // Both eyes' renders (eyeGeometry without baseDepth, and maskedShading): one after the other, their sum; at
  // once (concurrentEyes), from the first start to the last end, less than the sum where they overlap.
  std::optional<double> eyeRenders;
  bool concurrentEyes = false;           // the eyes rendered at once, by one eye renderer each
  std::optional<double> composite;       // both eyes
  // The displacement and classification with the work no mask decides beside them (baseDepth, the ray-cast eyes'
  // triangle setup and screen bins), from first start to last end: the frame up to the eye renders. Where nothing
  // runs beside them, displacement + classification + baseDepth.
  std::optional<double> frontSpan;
  std::optional<double> total;           // frontSpan, eyeRenders and composite
  std::vector<renderer::PassTiming> leftEyePasses, rightEyePasses;  // the masked renders' passes
  bool raycastSurfaces = false;  // an eye's geometry cast rays (HybridSynthesis::surfaces), or both rasterized
  bool mixedSurfaces = false;    // the left eye rasterized, the right eye's surfaces cast (HybridSurfaces::Mixed)
};

struct HybridSynthesis {
  stereo::StereoPair eyes;  // at the renderer's size; alpha as the displaced eyes' (the weapon mask)
  std::array<stereo::HybridThreshold, 2> thresholds;  // left, right; counted in the classification's cells
  std::uint64_t classifiedPixels = 0;                 // per eye (the crop's area)
  int cell = 1;                                       // the classification's cell, pixels per side
  std::uint64_t classifiedCells = 0;                  // per eye: the classification grid's cells in the crop
  std::array<std::vector<std::uint8_t>, 2> masks;     // left, right: 1 where the eye camera rendered the pixel
  std::array<std::uint64_t, 2> maskedPixels{};        // left, right: the masks' set pixels
  std::array<ImageRGBA32F, 2> renderedHdr;            // the masked renders' HDR colour (valid where masked; zero
                                                      // for an eye with nothing masked, which is not rendered)
  std::uint64_t filledLeft = 0, filledRight = 0;      // the iterative base's filled pixels that stayed displaced
  // Left, right: how each eye's masked pixels' surfaces were found: ray-cast where the eye renderer can shade what
  // rays find (DeferredRenderer::raycastSurfacesRefusal), else rasterized.
  std::array<renderer::ShadeMask::Surfaces, 2> surfaces{renderer::ShadeMask::Surfaces::Raster,
                                                        renderer::ShadeMask::Surfaces::Raster};
  HybridTimings timings;
  // Set on the frame where StereoSynthesis measured the surface paths to choose one (HybridSurfaces::Automatic):
  // each path's total GPU time for this frame at its budget, and (for a budget below 1) every pixel's.
  struct SurfaceChoice {
    std::optional<double> raycastMs, rasterMs, everyPixelRaycastMs;
    // Timed where the eyes can render at once (a second eye renderer): the left eye rasterized beside the right
    // eye's rays, at the frame's budget and for every pixel.
    std::optional<double> mixedMs, everyPixelMixedMs;
  };
  std::optional<SurfaceChoice> surfaceChoice;
};

// How the hybrid finds its masked pixels' surfaces. Automatic: where the eye renderer can shade what rays find
// (DeferredRenderer::raycastSurfacesRefusal), StereoSynthesis times both paths on a scene's first hybrid frame
// at each budget and keeps the faster (thin geometry makes a poor BVH, where rays lose), or casts every pixel
// (budget 1: the exact eyes) where that was faster still, as it is where the classification costs more than the
// rays it saves; synthesizeHybrid alone casts rays; elsewhere rasterized. Raster: always rasterized. RayCast:
// always by rays (a renderer that cannot is an error naming why). With ambient occlusion and a gather base (seed,
// search), rays are cast for the masked pixels only and the rest of the occlusion's region takes the center's
// depth where the base samples (stereo::HybridBaseDepthPass); RayCastRegion casts that whole region instead (the
// earlier way, for comparing). Mixed: the left eye rasterized and the right eye's surfaces cast, so that with an
// eye renderer each the two render at once, the raster on the graphics queue and the rays on the compute queue
// (where rays cost more than the raster but less than the two rasterized eyes one after the other); Automatic
// times it too where the eyes can render at once.
enum class HybridSurfaces { Automatic, Raster, RayCast, RayCastRegion, Mixed };

// "auto", "raster", "raycast", "raycast-region", "mixed"; and back (nullopt for any other name).
const char* hybridSurfacesName(HybridSurfaces surfaces);
std::optional<HybridSurfaces> hybridSurfacesFromName(std::string_view name);

// The options of an eye renderer that can ray-cast (visibility shading, the compute transparent pass) made from
// the center view's; with Automatic or Raster, the center view's as they are.
renderer::RendererOptions eyeRendererOptions(const renderer::RendererOptions& center, HybridSurfaces surfaces);

// The hybrid's own GPU objects, kept between frames so that a frame does not make them again: the
// classification's pipelines (the costly part of a small frame on lavapipe), the base depth pass, and the masks,
// bins and eyes of the last size (a new size makes them again).
class HybridSynthesizer {
 public:
  explicit HybridSynthesizer(vk::Context& context);
  ~HybridSynthesizer();
  HybridSynthesizer(HybridSynthesizer&&) noexcept;
  HybridSynthesizer& operator=(HybridSynthesizer&&) noexcept;

  // centerRenderer: its last frame is the center view `center` (its displayColor and linearDepth, in
  // vk::kComputeWrite state, left so, are what the eyes are displaced from, and its shadow maps light the eye
  // renders). eyeRenderer: a renderer of the same size with `scene` set, used for the eye cameras' masked renders
  // (it holds the right eye's afterwards; given the scene's BVH when it ray-casts and has none); an eye with no
  // masked pixel is not rendered. parameters (method Hybrid) are for that size (the guard band's rescaled ones
  // when it has one). Every GPU part runs once untimed (first use compiles on lavapipe), then timedRuns times;
  // the timings are medians.
  HybridSynthesis synthesize(const renderer::DeferredRenderer& centerRenderer, renderer::DeferredRenderer& eyeRenderer,
                             const renderer::Scene& scene, const renderer::ViewMatrices& center,
                             const stereo::StereoParameters& parameters, int timedRuns = 1,
                             HybridSurfaces surfaces = HybridSurfaces::Automatic);
  // The same with an eye renderer per eye (left, right; each as eyeRenderer above, the same options): on a device
  // with a compute queue (vk::Context::hasConcurrentQueue) ray-cast eyes render at once (renderer::DeferredRenderer::
  // renderConcurrently), so one eye's small masked passes fill the GPU while the other's wait on their barriers;
  // elsewhere, or rasterized, in turn. The eyes are the same as with one renderer.
  HybridSynthesis synthesize(const renderer::DeferredRenderer& centerRenderer,
                             const std::array<renderer::DeferredRenderer*, 2>& eyeRenderers,
                             const renderer::Scene& scene, const renderer::ViewMatrices& center,
                             const stereo::StereoParameters& parameters, int timedRuns = 1,
                             HybridSurfaces surfaces = HybridSurfaces::Automatic);

 private:
  struct Kept;
  std::unique_ptr<Kept> kept_;
};

// One frame with a synthesizer of its own (its pipelines compiled for this call alone).
HybridSynthesis synthesizeHybrid(vk::Context& context, const renderer::DeferredRenderer& centerRenderer,
                                 renderer::DeferredRenderer& eyeRenderer, const renderer::Scene& scene,
                                 const renderer::ViewMatrices& center, const stereo::StereoParameters& parameters,
                                 int timedRuns = 1, HybridSurfaces surfaces = HybridSurfaces::Automatic);

}  // namespace s3d::frame
