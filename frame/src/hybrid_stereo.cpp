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
// frame's shadow maps (the eye views plan theirs for the center camera, so they are the same maps): median total
// and median per pass; "gbuffer" and "ssao-depth" (the eye's rasterized geometry, every pixel's depth) or
// "raycast" find the surfaces, all others shade the masked pixels.
struct EyeRenderTimes {
  std::optional<double> geometry, shading;
  std::vector<renderer::PassTiming> passes;
};

EyeRenderTimes renderEye(renderer::DeferredRenderer& eyeRenderer, const renderer::DeferredRenderer& centerRenderer,
                         const renderer::ViewMatrices& view, const vk::Image* mask, renderer::ShadeMask::Surfaces surfaces,
                         const vk::Image* uncastDepth, const vk::Image* displayTarget, int timedRuns) {
  // HybridPass masks: 1 where the eye camera renders the pixel; none: every pixel (an unmasked render).
  const renderer::ShadeMask shadeMask{mask, 1, surfaces, uncastDepth, displayTarget};
  (void)eyeRenderer.render(view, shadeMask, centerRenderer);
  std::vector<double> totals;
  std::map<std::string, std::vector<double>> passTimes;
  std::vector<renderer::PassTiming> order;
  for (int run = 0; run < timedRuns; ++run) {
    const renderer::FrameTimings frame = eyeRenderer.render(view, shadeMask, centerRenderer);
    if (!frame.totalGpuMs) continue;
    totals.push_back(*frame.totalGpuMs);
    if (order.empty()) order = frame.passes;
    for (const renderer::PassTiming& pass : frame.passes) passTimes[pass.name].push_back(pass.gpuMs);
  }
  EyeRenderTimes times;
  const std::optional<double> total = stereo::medianMs(totals);
  if (!total) return times;
  double geometry = 0.0;
  for (renderer::PassTiming& pass : order) {
    pass.gpuMs = stereo::medianMs(passTimes[pass.name]).value_or(0.0);
    if (pass.name == "gbuffer" || pass.name == "ssao-depth" || pass.name == "raycast") geometry += pass.gpuMs;
  }
  times.geometry = geometry;
  times.shading = *total - geometry;
  times.passes = std::move(order);
  return times;
}

// The settings that ask for ray-cast eye surfaces (the masked pixels alone, or the occlusion's whole region).
bool forcesRays(HybridSurfaces surfaces) {
  return surfaces == HybridSurfaces::RayCast || surfaces == HybridSurfaces::RayCastRegion;
}

}  // namespace

const char* hybridSurfacesName(HybridSurfaces surfaces) {
  switch (surfaces) {
    case HybridSurfaces::Raster: return "raster";
    case HybridSurfaces::RayCast: return "raycast";
    case HybridSurfaces::RayCastRegion: return "raycast-region";
    default: return "auto";
  }
}

std::optional<HybridSurfaces> hybridSurfacesFromName(std::string_view name) {
  for (HybridSurfaces surfaces :
       {HybridSurfaces::Automatic, HybridSurfaces::Raster, HybridSurfaces::RayCast, HybridSurfaces::RayCastRegion})
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

// The masked pixels' surfaces by ray casting wherever the eye renderer can shade what the rays find (a GPU's
// visibility shading; DeferredRenderer::raycastSurfacesRefusal); its BVH is built once per scene or pose.
// Otherwise rasterized.
renderer::ShadeMask::Surfaces surfacesFor(renderer::DeferredRenderer& eyeRenderer, const renderer::Scene& scene,
                                          HybridSurfaces surfaces) {
  const std::optional<std::string> refusal = eyeRenderer.raycastSurfacesRefusal();
  if (forcesRays(surfaces) && refusal)
    throw std::invalid_argument("the hybrid cannot ray-cast its eye pixels here: " + *refusal);
  if (surfaces == HybridSurfaces::Raster || refusal) return renderer::ShadeMask::Surfaces::Raster;
  // A posed scene rebuilds its tree with every pose: the fast build; a still one builds once, with spatial splits.
  const renderer::BvhQuality quality = scene.animation ? renderer::BvhQuality::Fast : renderer::BvhQuality::SpatialSplits;
  if (!eyeRenderer.hasSurfaceBvh()) eyeRenderer.setSurfaceBvh(renderer::SceneBvh::build(scene, quality));
  return renderer::ShadeMask::Surfaces::RayCast;
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
  renderer::DeferredRenderer& eyeRenderer;
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
};

// Displacement, classification, threshold and masks: one submission, nothing read back in between. Returns the
// displacement's method (the hybrid's base). With every pixel masked the eyes are rendered whole: no displacement.
stereo::StereoMethod displaceAndClassify(HybridFrame& f, const stereo::StereoParameters& parameters, HybridTimings& timings) {
  if (f.everythingMasked) {
    timings.displacement = timings.classify = timings.threshold = timings.mask = timings.classification = 0.0;
    return stereo::displacementParameters(parameters).method;
  }
  const vk::Image& centerColor = f.centerRenderer.displayColor();
  const vk::Image& linearDepth = f.centerRenderer.linearDepth();
  const stereo::DisplacementPass displacement(f.context, parameters, f.width, f.height);
  const std::vector<std::optional<double>> front = timeSections(
      f.context, f.timedRuns, f.classify ? 4 : 1, [&](VkCommandBuffer cmd, const std::function<void()>& mark) {
        stereo::StereoPass::recordInputBarriers(cmd, centerColor, linearDepth, f.left, f.right);
        displacement.record(cmd, centerColor, linearDepth, f.left, f.right);
        mark();
        if (f.classify) f.hybrid.recordMasks(cmd, linearDepth, f.images, f.constants, mark);
        stereo::StereoPass::recordInputRelease(cmd, centerColor, linearDepth);
      });
  timings.displacement = front[0];
  if (f.classify) {
    timings.classify = front[1];
    timings.threshold = front[2];
    timings.mask = front[3];
  } else {
    timings.classify = timings.threshold = timings.mask = 0.0;
  }
  timings.classification = sum(sum(timings.classify, timings.threshold), timings.mask);
  return displacement.method();
}

// Ray-cast eyes over a gather base with ambient occlusion (and a mask): the rays are cast for the masked pixels
// only, the occlusion's region takes the center's depth where the base samples (RayCastRegion: it is cast). The
// center's device depth must be at the eyes' size and mean what theirs does (the same depth direction).
bool givesBaseDepth(const HybridFrame& f, const renderer::Scene& scene, renderer::ShadeMask::Surfaces eyeSurfaces,
                    HybridSurfaces surfaces) {
  const bool sameDeviceDepth = f.centerRenderer.supersample() == 1 &&
                               f.centerRenderer.options().reversedZ == f.eyeRenderer.options().reversedZ;
  return eyeSurfaces == renderer::ShadeMask::Surfaces::RayCast && surfaces != HybridSurfaces::RayCastRegion &&
         scene.ambientOcclusion && f.constants.baseTapCount > 0 && f.classify && sameDeviceDepth;
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

// One eye: its masked pixels rendered from the eye camera straight into the displaced eye (the renderer's display
// target), or with every pixel masked the whole eye rendered into it and its cropped columns made black. An eye
// with nothing masked is the displaced eye as it is, and costs no render.
void renderIntoEye(HybridFrame& f, const renderer::Scene& scene, const renderer::ViewMatrices& center,
                   const stereo::StereoParameters& parameters, stereo::Eye eye, HybridSynthesis& result) {
  const std::size_t index = eye == stereo::Eye::Left ? 0 : 1;
  const vk::Image& target = index == 0 ? f.left : f.right;
  const vk::Image& mask = index == 0 ? f.images.leftMask : f.images.rightMask;
  if (f.classify)
    result.thresholds[index] = stereo::HybridPass::readThreshold(f.context, f.images.thresholds, int(index));
  else if (f.everythingMasked)  // bin 0 and up: every classified pixel, no split (hybridThreshold's)
    result.thresholds[index] = {0, result.classifiedCells, S3D_HYBRID_NO_PIXEL, 0};
  if (result.thresholds[index].maskedPixels == 0) {
    result.masks[index].assign(std::size_t(f.width) * f.height, 0);
    result.renderedHdr[index] = ImageRGBA32F(f.width, f.height);
    return;
  }
  HybridTimings& timings = result.timings;
  const EyeRenderTimes render =
      renderEye(f.eyeRenderer, f.centerRenderer, referenceEyeView(scene, center, eye, parameters),
                f.everythingMasked ? nullptr : &mask, result.surfaces,
                f.givesBaseDepth ? &f.baseDepth[index] : nullptr, &target, f.timedRuns);
  timings.eyeGeometry = sum(timings.eyeGeometry, render.geometry);
  timings.maskedShading = sum(timings.maskedShading, render.shading);
  (index == 0 ? timings.leftEyePasses : timings.rightEyePasses) = render.passes;
  if (f.everythingMasked) {
    const std::vector<std::optional<double>> cropEdges =
        timeSections(f.context, f.timedRuns, 1, [&](VkCommandBuffer cmd, const std::function<void()>& mark) {
          vk::transition(cmd, target, vk::kComputeWrite, vk::kComputeWrite);
          f.hybrid.recordCropEdges(cmd, target, f.constants);
          mark();
        });
    timings.composite = sum(timings.composite, cropEdges[0]);
  }
  result.renderedHdr[index] = f.eyeRenderer.readHdrColor();
  result.masks[index] = f.everythingMasked ? cropMask(f.constants, f.width, f.height)
                                           : stereo::HybridPass::readMask(f.context, mask);
  result.maskedPixels[index] = std::uint64_t(std::count(result.masks[index].begin(), result.masks[index].end(), 1));
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
  if (parameters.method != stereo::StereoMethod::Hybrid)
    throw std::invalid_argument("synthesizeHybrid needs the hybrid method's parameters");
  if (timedRuns < 1) throw std::invalid_argument("synthesizeHybrid: timedRuns must be at least 1");
  const std::uint32_t width = centerRenderer.displayColor().width, height = centerRenderer.displayColor().height;
  if (eyeRenderer.width() != width || eyeRenderer.height() != height)
    throw std::invalid_argument("synthesizeHybrid: the eye renderer's size differs from the center view's");
  vk::Context& context = kept_->context;
  HybridSynthesis result;
  result.surfaces = surfacesFor(eyeRenderer, scene, surfaces);
  const gpu::HybridConstants constants = stereo::makeHybridConstants(parameters, width, height);
  kept_->fit(width, height, constants.cell);
  HybridFrame f{context, centerRenderer, eyeRenderer, width, height, timedRuns, kept_->hybrid, kept_->baseDepthPass,
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
  timings.raycastSurfaces = result.surfaces == renderer::ShadeMask::Surfaces::RayCast;
  const stereo::StereoMethod base = displaceAndClassify(f, parameters, timings);
  timings.maskedShading = timings.composite = timings.baseDepth = 0.0;
  if (givesBaseDepth(f, scene, result.surfaces, surfaces)) recordBaseDepth(f, timings);
  timings.eyeGeometry = timings.baseDepth;
  // The masked counts come back first (the submission above was waited for anyway).
  for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right})
    renderIntoEye(f, scene, center, parameters, eye, result);
  timings.total =
      sum(sum(sum(sum(timings.displacement, timings.classification), timings.eyeGeometry), timings.maskedShading),
          timings.composite);
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
