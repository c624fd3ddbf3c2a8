#include "s3d/frame/hybrid_stereo.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

#include "s3d/frame/layered_reference.h"
#include "s3d/renderer/scene_bvh.h"
#include "s3d/stereo/hybrid_base_depth_pass.h"
#include "s3d/stereo/hybrid_pass.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/stereo/synthesis.h"
#include "s3d/vk/resources.h"
#include "s3d/vk/timestamps.h"

namespace s3d::frame {
namespace {

std::optional<double> sum(std::optional<double> a, std::optional<double> b) {
  if (!a || !b) return std::nullopt;
  return *a + *b;
}

ImageRGBA8 readEye(vk::Context& context, const vk::Image& image) {
  ImageRGBA8 eye(image.width, image.height);
  const std::vector<std::byte> bytes = vk::readbackImage(context, image, vk::kComputeWrite);
  std::memcpy(eye.pixels.data(), bytes.data(), bytes.size());
  return eye;
}

// Submits `record` once untimed, then `timedRuns` times with a timestamp after each of its `marks` sections;
// returns the median milliseconds of each section.
std::vector<std::optional<double>> timeSections(vk::Context& context, int timedRuns, std::uint32_t sections,
                                                const std::function<void(VkCommandBuffer, const std::function<void()>&)>& record) {
  vk::TimestampQueries timestamps(context, sections + 1);
  std::vector<std::vector<double>> runs(sections);
  for (int run = 0; run <= timedRuns; ++run) {
    const bool timed = run > 0 && timestamps.supported();
    std::uint32_t next = 0;
    context.submitAndWait([&](VkCommandBuffer cmd) {
      if (timed) {
        timestamps.reset(cmd);
        timestamps.write(cmd, next++, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      }
      record(cmd, [&] {
        if (timed) timestamps.write(cmd, next++, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      });
    });
    if (timed)
      for (std::uint32_t section = 0; section < sections; ++section)
        if (const std::optional<double> ms = timestamps.elapsedMs(section, section + 1)) runs[section].push_back(*ms);
  }
  std::vector<std::optional<double>> medians;
  for (std::vector<double>& samples : runs) medians.push_back(stereo::medianMs(std::move(samples)));
  return medians;
}

// The eye renders, masked (renderer::ShadeMask: only the mask's pixels are shaded) or whole, and lit with the center
// frame's shadow maps (the eye views plan theirs for the center camera, so they are the same maps): per eye the
// median of each pass, and of "gbuffer" and "ssao-depth" (the eye's rasterized geometry, every pixel's depth) or
// "raycast" (its surfaces) against all others (shading the masked pixels); and the median time of all eyes'
// renders together (one after another: their totals' sum; at once: from the first start to the last end).
struct EyeRender {
  renderer::DeferredRenderer* renderer;
  renderer::ViewMatrices view;
  renderer::ShadeMask mask;
};

struct EyeRenderTimes {
  std::optional<double> geometry, shading, together;  // geometry, shading: summed over the eyes
  std::vector<std::vector<renderer::PassTiming>> passes;  // per eye
};

// One timed run of every eye's render: each eye's frame timings and their time together. With one renderer per
// eye the renders run at once (DeferredRenderer::renderConcurrently); sharing one, one after another.
std::pair<std::vector<renderer::FrameTimings>, std::optional<double>> renderOnce(
    const std::vector<EyeRender>& eyes, const renderer::DeferredRenderer& centerRenderer, bool together) {
  if (together) {
    std::vector<renderer::ConcurrentView> views;
    for (const EyeRender& eye : eyes) views.push_back({eye.renderer, eye.view, eye.mask, &centerRenderer});
    renderer::ConcurrentTimings timings = renderer::DeferredRenderer::renderConcurrently(views);
    return {std::move(timings.views), timings.spanGpuMs};
  }
  std::vector<renderer::FrameTimings> frames;
  std::optional<double> sum = 0.0;
  for (const EyeRender& eye : eyes) {
    frames.push_back(eye.renderer->render(eye.view, eye.mask, centerRenderer));
    sum = frames.back().totalGpuMs && sum ? std::optional<double>(*sum + *frames.back().totalGpuMs) : std::nullopt;
  }
  return {std::move(frames), sum};
}

EyeRenderTimes renderEyes(const std::vector<EyeRender>& eyes, const renderer::DeferredRenderer& centerRenderer,
                          bool together, int timedRuns, const std::function<void()>& prepare) {
  (void)renderOnce(eyes, centerRenderer, together);
  std::vector<double> totals;
  std::vector<std::map<std::string, std::vector<double>>> passTimes(eyes.size());
  std::vector<std::vector<renderer::PassTiming>> order(eyes.size());
  for (int run = 0; run < timedRuns; ++run) {
    prepare();
    const auto [frames, total] = renderOnce(eyes, centerRenderer, together);
    if (!total) continue;
    totals.push_back(*total);
    for (std::size_t eye = 0; eye < eyes.size(); ++eye) {
      if (order[eye].empty()) order[eye] = frames[eye].passes;
      for (const renderer::PassTiming& pass : frames[eye].passes) passTimes[eye][pass.name].push_back(pass.gpuMs);
    }
  }
  EyeRenderTimes times;
  times.together = stereo::medianMs(totals);
  if (!times.together) return times;
  double geometry = 0.0, shading = 0.0;
  for (std::size_t eye = 0; eye < eyes.size(); ++eye)
    for (renderer::PassTiming& pass : order[eye]) {
      pass.gpuMs = stereo::medianMs(passTimes[eye][pass.name]).value_or(0.0);
      const bool finds = pass.name == "gbuffer" || pass.name == "ssao-depth" || pass.name == "raycast";
      (finds ? geometry : shading) += pass.gpuMs;
    }
  times.geometry = geometry;
  times.shading = shading;
  times.passes = std::move(order);
  return times;
}

// The settings that ask for ray-cast eye surfaces (the masked pixels alone, the occlusion's whole region, or the
// right eye's).
bool forcesRays(HybridSurfaces surfaces) {
  return surfaces == HybridSurfaces::RayCast || surfaces == HybridSurfaces::RayCastRegion ||
         surfaces == HybridSurfaces::Mixed;
}

}  // namespace

const char* hybridSurfacesName(HybridSurfaces surfaces) {
  switch (surfaces) {
    case HybridSurfaces::Raster: return "raster";
    case HybridSurfaces::RayCast: return "raycast";
    case HybridSurfaces::RayCastRegion: return "raycast-region";
    case HybridSurfaces::Mixed: return "mixed";
    default: return "auto";
  }
}

std::optional<HybridSurfaces> hybridSurfacesFromName(std::string_view name) {
  for (HybridSurfaces surfaces :
       {HybridSurfaces::Automatic, HybridSurfaces::Raster, HybridSurfaces::RayCast, HybridSurfaces::RayCastRegion,
        HybridSurfaces::Mixed})
    if (name == hybridSurfacesName(surfaces)) return surfaces;
  return std::nullopt;
}

renderer::RendererOptions eyeRendererOptions(const renderer::RendererOptions& center, HybridSurfaces surfaces) {
  renderer::RendererOptions options = center;
  if (forcesRays(surfaces)) {
    options.gbufferShading = renderer::RendererOptions::GBufferShading::Visibility;
    options.transparentCompositing = renderer::RendererOptions::TransparentCompositing::Compute;
  }
  return options;
}

namespace {

// Each eye's masked pixels' surfaces (left, right): by ray casting wherever the eye renderers can shade what the
// rays find (a GPU's visibility shading; DeferredRenderer::raycastSurfacesRefusal), the left eye rasterized for
// Mixed; the BVH is built once per scene or pose and given to each casting eye renderer without it. Otherwise
// rasterized.
std::array<renderer::ShadeMask::Surfaces, 2> surfacesFor(const std::array<renderer::DeferredRenderer*, 2>& eyeRenderers,
                                                         const renderer::Scene& scene, HybridSurfaces surfaces) {
  using Surfaces = renderer::ShadeMask::Surfaces;
  std::optional<std::string> refusal = eyeRenderers[0]->raycastSurfacesRefusal();
  if (!refusal) refusal = eyeRenderers[1]->raycastSurfacesRefusal();
  if (forcesRays(surfaces) && refusal)
    throw std::invalid_argument("the hybrid cannot ray-cast its eye pixels here: " + *refusal);
  if (surfaces == HybridSurfaces::Raster || refusal) return {Surfaces::Raster, Surfaces::Raster};
  const std::array<Surfaces, 2> eyes{surfaces == HybridSurfaces::Mixed ? Surfaces::Raster : Surfaces::RayCast,
                                     Surfaces::RayCast};
  // A posed scene rebuilds its tree with every pose: the fast build; a still one builds once, with spatial splits.
  const renderer::BvhQuality quality = scene.animation ? renderer::BvhQuality::Fast : renderer::BvhQuality::SpatialSplits;
  std::optional<renderer::SceneBvh> bvh;
  for (std::size_t eye = 0; eye < 2; ++eye)
    if (eyes[eye] == Surfaces::RayCast && !eyeRenderers[eye]->hasSurfaceBvh()) {
      if (!bvh) bvh = renderer::SceneBvh::build(scene, quality);
      eyeRenderers[eye]->setSurfaceBvh(*bvh);
    }
  return eyes;
}

bool castsRays(const std::array<renderer::ShadeMask::Surfaces, 2>& surfaces) {
  return surfaces[0] == renderer::ShadeMask::Surfaces::RayCast || surfaces[1] == renderer::ShadeMask::Surfaces::RayCast;
}

// Budget 1's mask: every classified pixel (the crop) set, as the mask pass would leave it. Made here, not on the
// GPU: budget 1 renders the eyes whole, so no pass reads it.
std::vector<std::uint8_t> cropMask(const gpu::HybridConstants& constants, std::uint32_t width, std::uint32_t height) {
  std::vector<std::uint8_t> crop(std::size_t(width) * height, 0);
  for (std::uint32_t y = 0; y < height; ++y)
    for (int x = constants.cropBegin; x < constants.cropEnd; ++x) crop[std::size_t(y) * width + std::size_t(x)] = 1;
  return crop;
}

// One hybrid frame's GPU objects and the state its steps share.
struct HybridFrame {
  vk::Context& context;
  const renderer::DeferredRenderer& centerRenderer;
  // Left, right: one renderer for both eyes (one after the other) or one each (at once).
  std::array<renderer::DeferredRenderer*, 2> eyeRenderers;
  std::uint32_t width, height;
  int timedRuns;
  const stereo::HybridPass& hybrid;
  const stereo::HybridBaseDepthPass& baseDepthPass;
  const gpu::HybridConstants constants;
  stereo::HybridPass::Images& images;
  const vk::Image &left, &right;
  bool nothingMasked, everythingMasked, classify;
  // Ray-cast eyes with ambient occlusion over a gather base: each eye's depth where the base samples, given to
  // the pixels of the occlusion's region that are not cast (none: the region is cast); made on first use.
  std::array<vk::Image, 2>& baseDepth;
  bool givesBaseDepth = false;
  // The eye cameras' views, and the eyes whose ray-cast surfaces' setup, screen bins and tile reset run beside the
  // classification (one renderer per eye: each holds its own view's).
  std::array<renderer::ViewMatrices, 2> eyeViews{};
  std::array<bool, 2> preparesRays{};
};

// One step of the ray-cast eyes' work that no mask decides (DeferredRenderer::recordRaycastPreparation).
void recordEyePreparation(const HybridFrame& f, VkCommandBuffer cmd, int step) {
  for (std::size_t eye = 0; eye < 2; ++eye)
    if (f.preparesRays[eye])
      f.eyeRenderers[eye]->recordRaycastPreparation(cmd, f.eyeViews[eye],
                                                    renderer::RaycastVisibility::PreparationStep(step));
}

// The ray-cast eyes' setup, bins and tile reset on their own (before each timed eye render: a frame prepares its
// eyes once).
void prepareEyes(const HybridFrame& f) {
  if (!f.preparesRays[0] && !f.preparesRays[1]) return;
  f.context.submitAndWait([&](VkCommandBuffer cmd) {
    for (int step = 0; step < 3; ++step) {
      vk::computeStorageBarrier(cmd);
      recordEyePreparation(f, cmd, step);
    }
  });
}

// Displacement, classification, threshold and masks: one submission, nothing read back in between, timed twice.
// First each pass alone. Then, with a classification, as the frame runs them (frontSpan, one span): the work that
// does not wait for the classification beside it, so it needs no barrier of its own and fills the GPU's gaps (the
// passes' tails and barriers; the classify pass itself occupies every SM): the displacement (the classification reads
// the center's depth, not the eyes), with both eyes' base depth in the same dispatch where the eyes get one, beside
// the classify pass and, after the classify, threshold and mask dispatches, each step of the ray-cast eyes' setup
// (with their renderers' tile reset) and screen bins (each step's barrier next to one of the classification's).
// Returns the displacement's method (the hybrid's base). With every pixel masked the eyes are rendered whole: no
// displacement.
stereo::StereoMethod displaceAndClassify(HybridFrame& f, const stereo::StereoParameters& parameters, HybridTimings& timings) {
  if (f.everythingMasked) {
    timings.displacement = timings.classify = timings.threshold = timings.mask = timings.classification = 0.0;
    timings.frontSpan = timings.baseDepth;
    return stereo::displacementParameters(parameters).method;
  }
  const vk::Image& centerColor = f.centerRenderer.displayColor();
  const vk::Image& linearDepth = f.centerRenderer.linearDepth();
  const stereo::DisplacementPass displacement(f.context, parameters, f.width, f.height);
  const gpu::StereoConstants gather =
      stereo::makeStereoConstants(stereo::displacementParameters(parameters), f.width, f.height);
  const auto record = [&](VkCommandBuffer cmd, const std::function<void()>& mark, bool beside) {
    if (beside && f.givesBaseDepth)
      for (const vk::Image& eye : f.baseDepth) vk::transition(cmd, eye, vk::kUndefined, vk::kComputeWrite);
    stereo::StereoPass::recordInputBarriers(cmd, centerColor, linearDepth, f.left, f.right);
    if (!beside) {
      displacement.record(cmd, centerColor, linearDepth, f.left, f.right);
      mark();
    }
    int step = 0;
    const auto besideNextDispatch = [&] {
      if (step == 0 && f.givesBaseDepth)  // the gather base and its depth in one dispatch
        f.baseDepthPass.recordWithGather(cmd, centerColor, linearDepth, f.centerRenderer.deviceDepth(), f.left, f.right,
                                         f.baseDepth[0], f.baseDepth[1], gather);
      else if (step == 0)
        displacement.record(cmd, centerColor, linearDepth, f.left, f.right);
      recordEyePreparation(f, cmd, step++);
      vk::computeStorageBarrier(cmd);  // beside the classification's next barrier: orders the steps' buffers too
    };
    if (f.classify)
      f.hybrid.recordMasks(cmd, linearDepth, f.images, f.constants,
                           beside ? std::function<void()>(besideNextDispatch) : mark);
    stereo::StereoPass::recordInputRelease(cmd, centerColor, linearDepth);
    if (beside) mark();
  };
  const std::vector<std::optional<double>> alone =
      timeSections(f.context, f.timedRuns, f.classify ? 4 : 1,
                   [&](VkCommandBuffer cmd, const std::function<void()>& mark) { record(cmd, mark, false); });
  timings.displacement = alone[0];
  if (f.classify) {
    timings.classify = alone[1];
    timings.threshold = alone[2];
    timings.mask = alone[3];
  } else {
    timings.classify = timings.threshold = timings.mask = 0.0;
  }
  timings.classification = sum(sum(timings.classify, timings.threshold), timings.mask);
  timings.frontSpan =
      f.classify ? timeSections(f.context, f.timedRuns, 1,
                                [&](VkCommandBuffer cmd, const std::function<void()>& mark) { record(cmd, mark, true); })[0]
                 : sum(sum(timings.displacement, timings.classification), timings.baseDepth);
  return displacement.method();
}

// Ray-cast eyes over a gather base with ambient occlusion (and a mask): the rays are cast for the masked pixels
// only, the occlusion's region takes the center's depth where the base samples (RayCastRegion: it is cast). The
// center's device depth must be at the eyes' size and mean what theirs does (the same depth direction).
bool givesBaseDepth(const HybridFrame& f, const renderer::Scene& scene,
                    const std::array<renderer::ShadeMask::Surfaces, 2>& eyeSurfaces, HybridSurfaces surfaces) {
  const bool sameDeviceDepth = f.centerRenderer.supersample() == 1 &&
                               f.centerRenderer.options().reversedZ == f.eyeRenderers[0]->options().reversedZ;
  return castsRays(eyeSurfaces) && surfaces != HybridSurfaces::RayCastRegion && scene.ambientOcclusion &&
         f.constants.baseTapCount > 0 && f.classify && sameDeviceDepth;
}

// Both eyes' base depth (stereo::HybridBaseDepthPass) from the center's linear and device depth, timed.
void recordBaseDepth(HybridFrame& f, HybridTimings& timings) {
  if (f.baseDepth[0].width != f.width || f.baseDepth[0].height != f.height)
    for (vk::Image& eye : f.baseDepth) eye = stereo::HybridBaseDepthPass::createEyeDepth(f.context, f.width, f.height);
  const vk::Image& linearDepth = f.centerRenderer.linearDepth();
  const vk::Image& deviceDepth = f.centerRenderer.deviceDepth();
  const std::vector<std::optional<double>> times =
      timeSections(f.context, f.timedRuns, 1, [&](VkCommandBuffer cmd, const std::function<void()>& mark) {
        vk::transition(cmd, linearDepth, vk::kComputeWrite, vk::kComputeRead);
        for (const vk::Image& eye : f.baseDepth) vk::transition(cmd, eye, vk::kUndefined, vk::kComputeWrite);
        f.baseDepthPass.record(cmd, linearDepth, deviceDepth, f.baseDepth[0], f.baseDepth[1], f.constants);
        mark();
        vk::transition(cmd, linearDepth, vk::kComputeRead, vk::kComputeWrite);
      });
  timings.baseDepth = times[0];
  f.givesBaseDepth = true;
}

// Both eyes: their masked pixels rendered from the eye cameras straight into the displaced eyes (the renderers'
// display targets), or with every pixel masked the whole eyes rendered into them and their cropped columns made
// black. An eye with nothing masked is the displaced eye as it is, and costs no render.
void renderIntoEyes(HybridFrame& f, HybridSynthesis& result) {
  std::vector<EyeRender> renders;
  std::vector<std::size_t> rendered;  // the eyes (0 left, 1 right) with masked pixels
  for (const std::size_t index : {std::size_t(0), std::size_t(1)}) {
    const vk::Image& mask = index == 0 ? f.images.leftMask : f.images.rightMask;
    if (f.classify)
      result.thresholds[index] = stereo::HybridPass::readThreshold(f.context, f.images.thresholds, int(index));
    else if (f.everythingMasked)  // bin 0 and up: every classified pixel, no split (hybridThreshold's)
      result.thresholds[index] = {0, result.classifiedCells, S3D_HYBRID_NO_PIXEL, 0};
    if (result.thresholds[index].maskedPixels == 0) {
      result.masks[index].assign(std::size_t(f.width) * f.height, 0);
      result.renderedHdr[index] = ImageRGBA32F(f.width, f.height);
      continue;
    }
    // HybridPass masks: 1 where the eye camera renders the pixel; none: every pixel (an unmasked render).
    const bool casts = result.surfaces[index] == renderer::ShadeMask::Surfaces::RayCast;
    const renderer::ShadeMask shadeMask{f.everythingMasked ? nullptr : &mask, 1, result.surfaces[index],
                                        f.givesBaseDepth && casts ? &f.baseDepth[index] : nullptr,
                                        index == 0 ? &f.left : &f.right};
    renders.push_back({f.eyeRenderers[index], f.eyeViews[index], shadeMask});
    rendered.push_back(index);
  }
  HybridTimings& timings = result.timings;
  timings.eyeRenders = 0.0;
  if (renders.empty()) return;
  // At once where the right eye's render can run on the GPU's compute queue (ray-cast surfaces: compute only); the
  // left eye's, on the graphics queue, may be rasterized.
  const bool together = renders.size() == 2 && f.eyeRenderers[0] != f.eyeRenderers[1] && f.context.hasConcurrentQueue() &&
                        result.surfaces[1] == renderer::ShadeMask::Surfaces::RayCast;
  timings.concurrentEyes = together;
  // Sharing one renderer, each eye's results are read before the next eye renders over them.
  const std::size_t batch = together ? renders.size() : 1;
  for (std::size_t first = 0; first < renders.size(); first += batch) {
    const std::vector<EyeRender> now(renders.begin() + std::ptrdiff_t(first), renders.begin() + std::ptrdiff_t(first + batch));
    const EyeRenderTimes times = renderEyes(now, f.centerRenderer, together, f.timedRuns, [&] { prepareEyes(f); });
    timings.eyeGeometry = sum(timings.eyeGeometry, times.geometry);
    timings.maskedShading = sum(timings.maskedShading, times.shading);
    timings.eyeRenders = sum(timings.eyeRenders, times.together);
    for (std::size_t i = 0; i < now.size(); ++i) {
      const std::size_t index = rendered[first + i];
      if (i < times.passes.size()) (index == 0 ? timings.leftEyePasses : timings.rightEyePasses) = times.passes[i];
      result.renderedHdr[index] = now[i].renderer->readHdrColor();
    }
  }
  for (const std::size_t index : rendered) {
    const vk::Image& target = index == 0 ? f.left : f.right;
    if (f.everythingMasked) {
      const std::vector<std::optional<double>> cropEdges =
          timeSections(f.context, f.timedRuns, 1, [&](VkCommandBuffer cmd, const std::function<void()>& mark) {
            vk::transition(cmd, target, vk::kComputeWrite, vk::kComputeWrite);
            f.hybrid.recordCropEdges(cmd, target, f.constants);
            mark();
          });
      timings.composite = sum(timings.composite, cropEdges[0]);
    }
    result.masks[index] = f.everythingMasked
                              ? cropMask(f.constants, f.width, f.height)
                              : stereo::HybridPass::readMask(f.context, index == 0 ? f.images.leftMask : f.images.rightMask);
    result.maskedPixels[index] = std::uint64_t(std::count(result.masks[index].begin(), result.masks[index].end(), 1));
  }
}

}  // namespace

struct HybridSynthesizer::Kept {
  explicit Kept(vk::Context& c) : context(c), hybrid(c), baseDepthPass(c) {}

  // The images of the center view's size: made for the first frame and again for a new size or classification
  // cell (the base depth's only where a frame needs it: recordBaseDepth).
  void fit(std::uint32_t w, std::uint32_t h, int cell) {
    if (w == width && h == height && cell == images.cell) return;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    images = hybrid.createImages(w, h, cell);
    left = vk::createImage(context, stereo::StereoPass::kColorFormat, w, h, usage);
    right = vk::createImage(context, stereo::StereoPass::kColorFormat, w, h, usage);
    // In GENERAL from the start: a frame with every pixel masked renders into them before any displacement.
    context.submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* eye : {&left, &right}) vk::transition(cmd, *eye, vk::kUndefined, vk::kComputeWrite);
    });
    width = w;
    height = h;
  }

  vk::Context& context;
  const stereo::HybridPass hybrid;
  const stereo::HybridBaseDepthPass baseDepthPass;
  std::uint32_t width = 0, height = 0;
  stereo::HybridPass::Images images;
  vk::Image left, right;
  std::array<vk::Image, 2> baseDepth;
};

HybridSynthesizer::HybridSynthesizer(vk::Context& context) : kept_(std::make_unique<Kept>(context)) {}
HybridSynthesizer::~HybridSynthesizer() = default;
HybridSynthesizer::HybridSynthesizer(HybridSynthesizer&&) noexcept = default;
HybridSynthesizer& HybridSynthesizer::operator=(HybridSynthesizer&&) noexcept = default;

HybridSynthesis HybridSynthesizer::synthesize(const renderer::DeferredRenderer& centerRenderer,
                                              renderer::DeferredRenderer& eyeRenderer, const renderer::Scene& scene,
                                              const renderer::ViewMatrices& center,
                                              const stereo::StereoParameters& parameters, int timedRuns,
                                              HybridSurfaces surfaces) {
  return synthesize(centerRenderer, {&eyeRenderer, &eyeRenderer}, scene, center, parameters, timedRuns, surfaces);
}

HybridSynthesis HybridSynthesizer::synthesize(const renderer::DeferredRenderer& centerRenderer,
                                              const std::array<renderer::DeferredRenderer*, 2>& eyeRenderers,
                                              const renderer::Scene& scene, const renderer::ViewMatrices& center,
                                              const stereo::StereoParameters& parameters, int timedRuns,
                                              HybridSurfaces surfaces) {
  if (parameters.method != stereo::StereoMethod::Hybrid)
    throw std::invalid_argument("synthesizeHybrid needs the hybrid method's parameters");
  if (timedRuns < 1) throw std::invalid_argument("synthesizeHybrid: timedRuns must be at least 1");
  const std::uint32_t width = centerRenderer.displayColor().width, height = centerRenderer.displayColor().height;
  for (const renderer::DeferredRenderer* eyeRenderer : eyeRenderers) {
    if (eyeRenderer == nullptr) throw std::invalid_argument("synthesizeHybrid: an eye renderer is missing");
    if (eyeRenderer == &centerRenderer)
      throw std::invalid_argument("synthesizeHybrid: the center renderer cannot render the eyes");
    if (eyeRenderer->width() != width || eyeRenderer->height() != height)
      throw std::invalid_argument("synthesizeHybrid: the eye renderer's size differs from the center view's");
  }
  vk::Context& context = kept_->context;
  HybridSynthesis result;
  result.surfaces = surfacesFor(eyeRenderers, scene, surfaces);
  const gpu::HybridConstants constants = stereo::makeHybridConstants(parameters, width, height);
  kept_->fit(width, height, constants.cell);
  HybridFrame f{context, centerRenderer, eyeRenderers, width, height, timedRuns, kept_->hybrid, kept_->baseDepthPass,
                constants, kept_->images, kept_->left, kept_->right, false, false, false, kept_->baseDepth};
  const gpu::HybridConstants grid = stereo::hybridGridConstants(f.constants);
  result.classifiedPixels = std::uint64_t(f.constants.cropEnd - f.constants.cropBegin) * height;
  result.classifiedCells = std::uint64_t(grid.cropEnd - grid.cropBegin) * std::uint64_t(grid.height);
  result.cell = constants.cell;
  // The budget's ends need no classification: none masks nothing (the base displacement), all masks every
  // classified cell (the eyes rendered whole, the two-pass reference), whatever the scores.
  f.nothingMasked = grid.maskedPixelCap == 0;
  f.everythingMasked = !f.nothingMasked && grid.maskedPixelCap >= result.classifiedCells;
  f.classify = !f.nothingMasked && !f.everythingMasked;
  HybridTimings& timings = result.timings;
  timings.raycastSurfaces = castsRays(result.surfaces);
  timings.mixedSurfaces = result.surfaces[0] != result.surfaces[1];
  for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right})
    f.eyeViews[eye == stereo::Eye::Left ? 0 : 1] = referenceEyeView(scene, center, eye, parameters);
  for (std::size_t eye = 0; eye < 2; ++eye)
    f.preparesRays[eye] = f.classify && result.surfaces[eye] == renderer::ShadeMask::Surfaces::RayCast &&
                          eyeRenderers[0] != eyeRenderers[1];
  timings.maskedShading = timings.composite = timings.baseDepth = 0.0;
  if (givesBaseDepth(f, scene, result.surfaces, surfaces)) recordBaseDepth(f, timings);
  timings.eyeGeometry = timings.baseDepth;
  const stereo::StereoMethod base = displaceAndClassify(f, parameters, timings);
  // The masked counts come back first (the submission above was waited for anyway).
  renderIntoEyes(f, result);
  timings.total = sum(sum(timings.frontSpan, timings.eyeRenders), timings.composite);
  result.eyes = {readEye(context, f.left), readEye(context, f.right)};
  if (base == stereo::StereoMethod::Iterative)
    std::tie(result.filledLeft, result.filledRight) =
        stereo::countIterativeFills(context, centerRenderer.displayColor(), centerRenderer.linearDepth(), parameters);
  return result;
}

HybridSynthesis synthesizeHybrid(vk::Context& context, const renderer::DeferredRenderer& centerRenderer,
                                 renderer::DeferredRenderer& eyeRenderer, const renderer::Scene& scene,
                                 const renderer::ViewMatrices& center, const stereo::StereoParameters& parameters,
                                 int timedRuns, HybridSurfaces surfaces) {
  return HybridSynthesizer(context).synthesize(centerRenderer, eyeRenderer, scene, center, parameters, timedRuns,
                                               surfaces);
}

}  // namespace s3d::frame
