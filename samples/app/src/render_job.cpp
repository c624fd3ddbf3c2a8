#include "s3d/app/render_job.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>

#include "s3d/app/comfort_json.h"
#include "s3d/app/frame_rules.h"
#include "s3d/app/scene_world.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/frame/stereo_synthesis.h"
#include "s3d/hud/crosshair.h"
#include "s3d/io/image_io.h"
#include "s3d/io/output_transaction.h"
#include "s3d/number_text.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_animation.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/hdr_gather.h"
#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/sanitize.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/vk/resources.h"
#include "s3d/vk/timestamps.h"

namespace s3d::app {
namespace fs = std::filesystem;

namespace {

struct ValidatedJob {
  renderer::Scene scene;
  gpu::StereoConstants constants;
  stereo::StereoParameters stereo;    // options.stereo with the zero-parallax distance clamped
  std::vector<std::string> warnings;  // why it was clamped
};

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) text += ", ";
    text += name;
  }
  return text;
}

void requireImageSize(std::uint32_t value, const char* name) {
  if (value == 0 || value > kMaxImageSize)
    throw std::invalid_argument(std::string(name) + " must be in [1, " + std::to_string(kMaxImageSize) + "] (got " +
                                std::to_string(value) + ")");
}

frame::MemoryEstimate estimateAtRenderedWidth(const RenderJobOptions& options, const stereo::StereoParameters& parameters,
                                       std::uint32_t renderedWidth) {
  return frame::renderMemoryEstimate(options.width, options.height, renderedWidth, options.supersample,
                              parameters.method == stereo::StereoMethod::Hybrid,
                              frame::maxReferenceLayers(parameters.disparityMapping));
}

// The memory estimate before the first frame, with the guard band of the separation (or the disparity budget's
// uncrossed side on the display, what the controller fills), from the zero-parallax plane, or from the near
// plane with negative parallax allowed. The controller may choose a wider band for a shallow frame (up to its
// maximumSeparation): that width is checked again once chosen, before anything is rendered at it.
frame::MemoryEstimate memoryEstimateFor(const RenderJobOptions& options, const renderer::Scene& scene,
                                 const stereo::StereoParameters& parameters) {
  std::uint32_t renderedWidth = options.width;
  if (parameters.edgeCrop < 0.0f) {
    float separation = parameters.maxSeparation;
    if (options.disparityBudget != comfort::DisparityBudgetRule::Off)
      separation = std::max(separation, float(comfort::disparityBudget(options.display).uncrossedFraction));
    const float nearest = options.allowNegativeParallax ? scene.camera.nearPlane : parameters.zeroParallaxDistance;
    renderedWidth = stereo::guardBandFor(separation, parameters.zeroParallaxDistance, nearest, options.width,
                                         kMaxImageSize / options.supersample)
                        .renderedWidth(options.width);
  }
  return estimateAtRenderedWidth(options, parameters, renderedWidth);
}

// Everything runRenderJob checks before touching the GPU or the file system; returns what it built on the way.
ValidatedJob validateJob(const RenderJobOptions& options) {
  requireImageSize(options.width, "width");
  if (options.supersample < 1 || options.supersample > 4)
    throw std::invalid_argument("supersample must be in [1, 4] (got " + std::to_string(options.supersample) + ")");
  if (std::max(options.width, options.height) * options.supersample > kMaxImageSize)
    throw std::invalid_argument("width and height times supersample must stay within " + std::to_string(kMaxImageSize));
  requireImageSize(options.height, "height");
  for (const std::string& name : options.outputs)
    if (std::find(kAllOutputs.begin(), kAllOutputs.end(), name) == kAllOutputs.end())
      throw std::invalid_argument("unknown output '" + name + "' (choices: " + joined(kAllOutputs) + ")");
  if (options.outputFolder.empty()) throw std::invalid_argument("the output folder is empty");
  std::error_code error;
  const fs::file_status status = fs::status(options.outputFolder, error);
  if (fs::exists(status) && !fs::is_directory(status))
    throw std::invalid_argument("output folder '" + options.outputFolder.string() + "' exists and is not a folder");
  // A scene file's folder may be the output folder: no output may land on the scene or a file it reads.
  io::requireOutputsAreNotInputs(options.outputFolder,
                                 std::vector<std::string>(options.outputs.begin(), options.outputs.end()),
                                 renderer::isSceneFile(options.scene) ? renderer::sceneFileInputs(options.scene)
                                                                      : std::vector<fs::path>{});

  stereo::validate(options.stereo);
  comfort::validate(options.display);
  ValidatedJob job{renderer::loadScene(options.scene),  // throws naming the scene (or file) and the choices
                   stereo::makeStereoConstants(options.stereo, options.width, options.height), options.stereo, {}};
  // A zero-parallax plane at or beyond the far plane, or near zero, is clamped with a warning.
  const stereo::ClampedZeroParallax zpp = stereo::clampZeroParallaxDistance(
      options.stereo.zeroParallaxDistance, job.scene.camera.nearPlane, job.scene.camera.farPlane);
  job.stereo.zeroParallaxDistance = zpp.zeroParallaxDistance;
  if (zpp.warning) job.warnings.push_back(*zpp.warning);
  job.warnings.insert(job.warnings.end(), job.scene.warnings.begin(), job.scene.warnings.end());
  job.constants = stereo::makeStereoConstants(job.stereo, options.width, options.height);
  // The scene's camera at the requested frame of its path (throws naming the frame and the count).
  job.scene.camera = renderer::cameraForFrame(job.scene, options.frame);
  if (!(options.framesPerSecond > 0.0f) || options.framesPerSecond > 1000.0f)
    throw std::invalid_argument("frames per second must be in (0, 1000] (got " + numberText(options.framesPerSecond) + ")");
  // Everything after this sees the scene as posed at the frame's time: the renderer, the world queries.
  renderer::poseScene(job.scene, double(options.frame) / double(options.framesPerSecond));
  if (options.stereo.edgeCrop >= 0.0f && job.constants.cropEnd <= job.constants.cropBegin)
    throw std::invalid_argument("edgeCrop " + numberText(options.stereo.edgeCrop) + " blacks out all " +
                                std::to_string(options.width) + " columns: nothing left to compare");
  // Packing limits, so a size the options accept cannot fail after the whole render.
  requirePackableEyes(options.width, options.height, options.outputs.count("sbs.png") != 0, options.sideBySide,
                      options.outputs.count("tab.png") != 0, options.topBottom, true);
  // Memory last: the estimate needs the scene (near plane) and the valid parameters.
  frame::requireHostMemory(memoryEstimateFor(options, job.scene, job.stereo), options.memoryLimitBytes, false);
  return job;
}

// tidy, finiteOrNull, optionalMs, statsJson and errorJson: extracted to eye_comparison.cpp (shared with s3d bench).

nlohmann::json hybridJson(const HybridReport& hybrid) {
  auto eyeJson = [&](const stereo::HybridThreshold& threshold) {
    return nlohmann::json{{"thresholdBin", threshold.bin},
                          {"splitBin", threshold.splitBin < S3D_HYBRID_BINS ? nlohmann::json(threshold.splitBin) : nlohmann::json()},
                          {"splitPixels", threshold.splitPixels},
                          {"maskedPixels", threshold.maskedPixels},
                          {"maskedShare", finiteOrNull(tidy(float(threshold.maskedPixels) /
                                                            float(std::max<std::uint64_t>(hybrid.classifiedPixels, 1))))}};
  };
  return {{"budget", finiteOrNull(tidy(hybrid.budget))},
          {"base", stereo::methodName(hybrid.base)},
          {"classifiedPixels", hybrid.classifiedPixels},
          {"left", eyeJson(hybrid.thresholds[0])},
          {"right", eyeJson(hybrid.thresholds[1])},
          {"gpuTimeMs", toJson(hybrid.timings)}};
}

}  // namespace

void validateRenderJobOptions(const RenderJobOptions& options) { (void)validateJob(options); }

frame::MemoryEstimate renderJobMemoryEstimate(const RenderJobOptions& options) {
  const ValidatedJob job = validateJob(options);
  return memoryEstimateFor(options, job.scene, job.stereo);
}

RenderReport runRenderJob(vk::Context& context, const RenderJobOptions& options) {
  // 1. Options: all checks happen before any GPU resource or file exists.
  const ValidatedJob job = validateJob(options);
  // With the device known: lavapipe's images live in main memory too, a GPU's must fit its memory.
  const frame::MemoryEstimate memory = memoryEstimateFor(options, job.scene, job.stereo);
  frame::requireMemory(context, memory, options.memoryLimitBytes);
  const std::uint32_t width = options.width;
  const std::uint32_t height = options.height;
  auto selected = [&](const std::string& name) { return options.outputs.count(name) != 0; };

  RenderReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  report.width = width;
  report.height = height;
  report.warnings = job.warnings;
  report.memory = memory;
  // Without negative parallax allowed, the weapon push reaches at least the screen plane
  // (comfort::pushWeaponBehindScreen) and, once the frame's depth is known, the zero-parallax distance is
  // held at its nearest surface: every pixel gets zero or positive parallax.
  // (s3d/comfort/budget_frame.h, shared with `s3d tune`)
  const std::optional<glm::vec2> weaponDepths = renderer::firstPersonDepthRange(job.scene);
  stereo::StereoParameters parameters =  // the zero-parallax distance clamped
      comfort::pushWeaponUnlessNegativeParallaxAllowed(job.stereo, weaponDepths, options.allowNegativeParallax);

  // Guard band (no --edge-crop): the center view is rendered wider by the largest displacement an eye can
  // need, so every eye pixel's source lies inside it. The nearest depth allowed is the zero-parallax plane
  // (held there below) unless negative parallax is allowed: then the near plane or the pushed weapon's nearest.
  const bool guardBand = options.stereo.edgeCrop < 0.0f;
  auto bandFor = [&](const stereo::StereoParameters& p) {
    if (!guardBand) return stereo::GuardBand{};
    float nearest = p.zeroParallaxDistance;
    if (options.allowNegativeParallax) {
      nearest = job.scene.camera.nearPlane;
      if (weaponDepths) nearest = std::min(nearest, p.weaponDepthOffset + p.weaponDepthScale * weaponDepths->x);
    }
    return stereo::guardBandFor(p.maxSeparation, p.zeroParallaxDistance, nearest, width,
                                kMaxImageSize / options.supersample);
  };
  stereo::GuardBand band;
  std::uint32_t renderedWidth = width;
  // The output's columns inside the rendered frame.
  auto output = [&](const auto& image) { return stereo::cropColumns(image, band.columns, width); };
  auto outputMask = [&](const std::vector<std::uint8_t>& mask) {
    return stereo::cropColumns(mask, renderedWidth, band.columns, width);
  };

  // 2. The center view (a wider frustum with the same vertical field of view when there is a band).
  std::unique_ptr<renderer::DeferredRenderer> deferred;
  renderer::ViewMatrices center;
  auto renderCenter = [&](const stereo::GuardBand& newBand) {
    band = newBand;
    renderedWidth = band.renderedWidth(width);
    deferred = std::make_unique<renderer::DeferredRenderer>(context, renderedWidth, height,
                                                            renderer::RendererOptions{options.supersample, options.reversedZ});
    deferred->setScene(job.scene);
    center = renderer::centerViewMatrices(job.scene, float(renderedWidth) / float(height),
                                          {parameters.weaponDepthOffset, parameters.weaponDepthScale});
    // The first frame on fresh pipelines includes shader compilation (lavapipe compiles at first use):
    // render it once untimed so the center frame, the stereo pass and the reference eye are all warm.
    (void)deferred->render(center);
    renderer::FrameTimings centerTimings = deferred->render(center);
    report.centerFrameGpuMs = centerTimings.totalGpuMs;
    report.centerPasses = std::move(centerTimings.passes);
  };
  renderCenter(bandFor(parameters));
  // For center.exr, the regions and the HDR error; NaN or inf is sanitized and counted (the GPU pass reads
  // invalid depth as the zero-parallax plane too, and the tone map writes non-finite color as black).
  DepthImage renderedDepth;
  ImageRGBA32F renderedHdr;
  auto readCenter = [&] {
    renderedDepth = deferred->readLinearDepth();
    renderedHdr = deferred->readHdrColor();
    report.sanitized.depthPixels = stereo::sanitizeDepth(renderedDepth, parameters.zeroParallaxDistance);
    report.sanitized.colorValues = stereo::sanitizeColor(renderedHdr);
  };
  readCenter();
  // Held at the nearest depth of the whole rendered frame: the band's content reaches the eyes too.
  report.zeroParallaxLimited = comfort::holdZeroParallaxAtNearestDepth(parameters, renderedDepth, options.allowNegativeParallax);
  const comfort::WorldQueries world(worldMeshes(job.scene));  // once per job: the world does not change between views
  const comfort::CrosshairPlacement placement =
      comfort::placeCrosshair(world, job.scene.camera, options.crosshair.distance.value_or(job.scene.crosshairDistance),
                              options.crosshair.margin);
  if (options.disparityBudget != comfort::DisparityBudgetRule::Off) {
    // The frame's depth range, reduced on the GPU, picks maxSeparation and the zero-parallax distance.
    const stereo::DepthRangePass reduction(context);
    comfort::DisparityBudgetController controller(comfort::disparityBudget(options.display), options.allowNegativeParallax);
    report.budget = comfort::applyDisparityBudget(context, reduction, &controller, deferred->linearDepth(),
                                         {placement.depth, comfort::weaponNearestPushed(parameters, weaponDepths)}, 1.0f / 30.0f,
                                         parameters);
    report.budget.imageWidth = width;  // budgetPx and bulkShare in the output eyes' pixels, as the comfort report
    // A larger chosen separation needs a wider band: render the center view again at that width.
    if (const stereo::GuardBand chosen = bandFor(parameters); chosen.columns > band.columns) {
      report.memory = estimateAtRenderedWidth(options, parameters, chosen.renderedWidth(width));
      report.memory.what += " at the separation --disparity-budget chose (" + numberText(parameters.maxSeparation) + ")";
      report.memory.lower += " or give --disparity-budget off";
      frame::requireMemory(context, report.memory, options.memoryLimitBytes);
      renderCenter(chosen);
      readCenter();
    }
  }
  // Nonlinear depth-to-parallax mapping: the final center view's curve, applied to the stereo pass's depth on the
  // GPU and, by the same shared function, to the C++ copy the references and the comfort report read.
  report.disparityMap = comfort::FrameDisparityMapper(context).apply(context, deferred->linearDepth(), parameters);
  const gpu::DisparityMapConstants& map = report.disparityMap.map;
  const DepthImage stereoDepth = stereo::mappedDepthImage(renderedDepth, map);
  if (band.capped)
    report.warnings.push_back("guard band capped at " + std::to_string(band.columns) + " columns per side (" +
                              std::to_string(band.neededColumns) +
                              " needed): the outermost eye columns repeat the band's edge");
  if (guardBand) parameters.edgeCrop = 0.0f;  // the output eyes are full frame
  report.guardBandColumns = band.columns;
  report.renderedWidth = renderedWidth;
  report.cropColumns = guardBand ? 0u : std::uint32_t(stereo::makeStereoConstants(parameters, width, height).cropBegin);
  // The output-size center view's matrices, for per-pixel rays over the output's depth.
  const renderer::ViewMatrices outputCenter = renderer::centerViewMatrices(
      job.scene, float(width) / float(height), {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  const ImageRGBA8 centerColor = output(deferred->readDisplayColor());
  const bool wantsExr = selected("center.exr");
  const std::vector<std::uint8_t> firstPersonMask = outputMask(deferred->readFirstPersonMask());  // weapon conflicts
  report.stereo = parameters;
  if (report.stereo.edgeCrop < 0.0f) report.stereo.edgeCrop = report.stereo.maxSeparation;
  // The pass and the reference cameras on the rendered frame: the same parallax in pixels, the band cropped.
  const stereo::StereoParameters renderedParameters =
      guardBand ? stereo::guardBandParameters(parameters, width, band) : parameters;

  // 3. Both eyes synthesized on the GPU from the renderer's own images.
  // The same gather on the linear HDR center view, by the C++ reference of the method (hdr_gather.h).
  stereo::HdrStereoPair renderedEyesHdr = stereo::synthesizeHdrReference(renderedHdr, stereoDepth, renderedParameters);
  stereo::StereoPair renderedEyes;
  {  // the synthesis (the hybrid's eye renderer) is released before the reference eyes are rendered
    frame::StereoSynthesis synthesis(context, {.width = renderedWidth, .height = height,
                                               .renderer = {options.supersample, options.reversedZ}});
    frame::SynthesizedEyes eyes = synthesis.synthesize({*deferred, job.scene, center, renderedParameters});
    report.stereoPassGpuMs = eyes.gpuMs;
    report.filledPixels = {eyes.filledLeft, eyes.filledRight};
    if (eyes.hybrid) {  // the pixels it rendered from the eye cameras go into the HDR eyes too
      stereo::compositeHybridReference(renderedEyesHdr.left, eyes.hybrid->renderedHdr[0], eyes.hybrid->masks[0]);
      stereo::compositeHybridReference(renderedEyesHdr.right, eyes.hybrid->renderedHdr[1], eyes.hybrid->masks[1]);
      report.hybrid = HybridReport{parameters.hybridBudget, parameters.hybridBase, eyes.hybrid->classifiedPixels,
                                   eyes.hybrid->thresholds, std::move(eyes.hybrid->timings)};
    }
    renderedEyes = std::move(eyes.eyes);
  }
  const stereo::StereoPair synthesized{output(renderedEyes.left), output(renderedEyes.right)};
  const stereo::HdrStereoPair synthesizedHdr{output(renderedEyesHdr.left), output(renderedEyesHdr.right)};
  const DepthImage centerDepth = output(renderedDepth);             // the scene's depth (rays, HUD, center.exr)
  const DepthImage centerStereoDepth = output(stereoDepth);        // what the stereo pass read (parallax)
  const ImageRGBA32F centerHdr = output(renderedHdr);

  // 4. The two-pass reference: each eye rendered with its off-axis camera (on the rendered frame, cropped
  // to the output: the same rays as an output-size eye, tests/stereo/test_guard_band.cpp); a nonlinear map takes one
  // rendering per segment of its curve (layered_reference.h).
  struct OutputReference {  // one reference eye cropped to the output
    frame::ReferenceEye rendered;
    ImageRGBA8 display;
    DepthImage depth;  // mapped as the stereo pass's depth (disocclusion regions)
    ImageRGBA32F hdr;
    std::vector<std::uint8_t> transparent;
    std::vector<std::uint8_t> foliage;
  };
  auto referenceFor = [&](stereo::Eye side) {
    OutputReference eye{frame::renderReferenceEye(*deferred, job.scene, center, side, renderedParameters, map), {}, {}, {}, {}, {}};
    eye.display = output(eye.rendered.display);
    eye.depth = output(stereo::mappedDepthImage(eye.rendered.depth, map));
    eye.hdr = output(eye.rendered.hdr);
    eye.transparent = outputMask(eye.rendered.transparent);
    eye.foliage = outputMask(eye.rendered.foliage);
    return eye;
  };
  const OutputReference leftEye = referenceFor(stereo::Eye::Left);
  const OutputReference rightEye = referenceFor(stereo::Eye::Right);
  const ImageRGBA8& leftReference = leftEye.display;
  const ImageRGBA8& rightReference = rightEye.display;
  report.referenceEyeGpuMs = leftEye.rendered.firstLayerGpuMs;
  report.disparityMap.referenceLayers = leftEye.rendered.layers;
  report.disparityMap.unresolvedPixels = {leftEye.rendered.unresolvedPixels, rightEye.rendered.unresolvedPixels};

  // 5. Synthesized vs reference over the full frame with a guard band, else without the cropped strips.
  // (region masks and comparison: s3d/stereo/eye_comparison.h, shared with s3d bench)
  const std::vector<std::uint8_t> halo = stereo::haloMaskFor(centerStereoDepth, parameters);
  for (auto [eyeError, eye, eyeHdr, reference, side] :
       {std::tuple{&report.left, &synthesized.left, &synthesizedHdr.left, &leftEye, stereo::Eye::Left},
        std::tuple{&report.right, &synthesized.right, &synthesizedHdr.right, &rightEye, stereo::Eye::Right}}) {
    const stereo::RegionMasks masks{halo, stereo::disocclusionMaskFor(reference->depth, centerStereoDepth, parameters, side),
                                    reference->transparent, reference->foliage};
    *eyeError = stereo::compareEye(*eye, reference->display, report.cropColumns, masks, eyeHdr, &reference->hdr);
  }

  // Comfort report: the parallax the stereo pass gave every pixel, as angles on the chosen display, and
  // weapon pixels whose pushed depth lies behind the world surface there (Embree rays).
  report.display = options.display;
  report.comfort = comfort::frameComfort(centerStereoDepth, parameters, report.display);
  report.weaponConflictPixels =
      comfort::countWeaponConflicts(world, job.scene.camera, outputCenter.worldProjection, centerDepth, firstPersonMask).conflictPixels;

  // 6. HUD (s3d/hud/overlay.h, drawn by frame_rules.h's drawHud): the crosshair, placed by an Embree ray cast
  // along the aim (seed 4.6.2), and the static panels, each drawn after stereo synthesis into every view at the
  // parallax of its depth and faded out where the weapon mask (the eyes' alpha) covers an element that lies
  // behind the weapon. Not part
  // of the 3D scene: synthesized eyes and references get the same overlay, after the comparison so it
  // cannot flatter the error.
  ImageRGBA8 centerHud = centerColor;
  stereo::StereoPair eyesHud = synthesized;
  stereo::StereoPair referenceHud{leftReference, rightReference};
  HudFrame overlay = drawHud({parameters, placement.depth, weaponDepths, options.allowNegativeParallax, &centerDepth,
                              &firstPersonMask, resolveHudMode(options.hud, options.scene) == HudMode::Game, map},
                             eyesHud, &centerHud, &referenceHud);
  const float rightOffset = hud::crosshairEyeOffsetPx(parameters, gpu::mappedDepth(map, overlay.crosshairDepth), width,
                                                      stereo::Eye::Right);
  report.crosshair = {overlay.crosshairDepth, placement.hitWorld, rightOffset};
  report.hud = std::move(overlay.elements);
  report.hudConflictPixels = overlay.conflictPixels;

  // 7. Outputs, each written atomically by s3d::io; report.json last so it lists everything before it.
  const fs::path& folder = options.outputFolder;
  auto writeOutputPng = [&](const std::string& name, const ImageRGBA8& image) {
    if (!selected(name)) return;
    io::writePng(folder / name, image);
    report.filesWritten.push_back(name);
  };
  writeOutputPng("center.png", centerHud);
  if (wantsExr) {
    io::writeExr(folder / "center.exr", centerHdr, &centerDepth);
    report.filesWritten.push_back("center.exr");
  }
  writeOutputPng("left.png", eyesHud.left);
  writeOutputPng("right.png", eyesHud.right);
  writeOutputPng("left_reference.png", referenceHud.left);
  writeOutputPng("right_reference.png", referenceHud.right);
  if (selected("anaglyph.png")) writeOutputPng("anaglyph.png", stereo::makeAnaglyphDubois(eyesHud.left, eyesHud.right));
  if (selected("sbs.png"))
    writeOutputPng("sbs.png", stereo::makeSideBySide(eyesHud.left, eyesHud.right, options.sideBySide));
  if (selected("tab.png"))
    writeOutputPng("tab.png", stereo::makeTopAndBottom(eyesHud.left, eyesHud.right, options.topBottom));
  // Heat maps of the error against the reference, without the HUD (as measured).
  if (selected("error_left.png"))
    writeOutputPng("error_left.png", stereo::makeErrorHeatMap(synthesized.left, leftReference, report.cropColumns));
  if (selected("error_right.png"))
    writeOutputPng("error_right.png", stereo::makeErrorHeatMap(synthesized.right, rightReference, report.cropColumns));
  if (selected("report.json")) {
    report.filesWritten.push_back("report.json");  // listed in itself: the document describes the whole output
    try {
      io::writeTextFile(folder / "report.json", toJson(report).dump(2) + "\n");
    } catch (...) {
      report.filesWritten.pop_back();
      throw;
    }
  }
  return report;
}

nlohmann::json toJson(const RenderReport& report) {
  nlohmann::json passes = nlohmann::json::array();
  for (const renderer::PassTiming& pass : report.centerPasses)
    passes.push_back(nlohmann::json{{"name", pass.name}, {"gpuMs", finiteOrNull(pass.gpuMs)}});

  nlohmann::json ratio;  // null unless both times exist and the reference took measurable time
  if (report.stereoPassGpuMs && report.referenceEyeGpuMs && *report.referenceEyeGpuMs > 0.0)
    ratio = finiteOrNull(*report.stereoPassGpuMs / *report.referenceEyeGpuMs);

  return {{"device", report.deviceName},
          {"scene", report.scene},
          {"width", report.width},
          {"height", report.height},
          {"stereo",
           {{"maxSeparation", finiteOrNull(tidy(report.stereo.maxSeparation))},
            {"zeroParallaxDistance", finiteOrNull(tidy(report.stereo.zeroParallaxDistance))},
            {"edgeCrop", finiteOrNull(tidy(report.stereo.edgeCrop))},
            {"cropColumns", report.cropColumns},
            {"guardBandColumns", report.guardBandColumns},
            {"renderedWidth", report.renderedWidth},
            {"method", stereo::methodName(report.stereo.method)},
            {"iterations", report.stereo.method == stereo::StereoMethod::Iterative ? nlohmann::json(report.stereo.iterations)
                                                                                    : nlohmann::json()},
            {"filledPixels", {{"left", report.filledPixels[0]}, {"right", report.filledPixels[1]}}},
            {"weaponDepthOffset", finiteOrNull(tidy(report.stereo.weaponDepthOffset))},
            {"weaponDepthScale", finiteOrNull(tidy(report.stereo.weaponDepthScale))},
            {"searchTaps", report.stereo.method == stereo::StereoMethod::Search ? nlohmann::json(report.stereo.searchTaps)
                                                                                 : nlohmann::json()}}},
          {"gpuTimeMs",
           {{"centerFrame", optionalMs(report.centerFrameGpuMs)},
            {"stereoPass", optionalMs(report.stereoPassGpuMs)},
            {"referenceEye", optionalMs(report.referenceEyeGpuMs)},
            {"depthReduction", optionalMs(report.budget.reductionGpuMs)}}},
          {"disparityBudget", budgetJson(report.budget, report.comfort)},
          {"hybrid", report.hybrid ? hybridJson(*report.hybrid) : nlohmann::json()},
          {"disparityMapping", disparityMapJson(report.disparityMap)},
          {"centerPasses", passes},
          {"ratios", {{"stereoPassToReferenceEye", ratio}}},
          {"error", {{"left", errorJson(report.left)}, {"right", errorJson(report.right)}}},
          {"comfort", [&] {
             nlohmann::json comfort = comfortJson(report.comfort);
             comfort["display"] = displayJson(report.display);
             comfort["zeroParallaxDistance"] = finiteOrNull(tidy(report.stereo.zeroParallaxDistance));
             comfort["zeroParallaxLimited"] = report.zeroParallaxLimited;
             comfort["crosshairDepth"] = finiteOrNull(tidy(report.crosshair.depth));
             comfort["weaponConflictPixels"] = report.weaponConflictPixels;
             comfort["hudConflictPixels"] = report.hudConflictPixels;
             return comfort;
           }()},
          {"crosshair",
           {{"depth", finiteOrNull(tidy(report.crosshair.depth))},
            {"hitWorld", report.crosshair.hitWorld},
            {"parallaxPx", finiteOrNull(tidy(report.crosshair.parallaxPx))}}},
          {"sanitized", {{"colorValues", report.sanitized.colorValues}, {"depthPixels", report.sanitized.depthPixels}}},
          {"warnings", report.warnings},
          {"hud", [&] {
             nlohmann::json elements = nlohmann::json::array();
             for (const HudElementReport& e : report.hud)
               elements.push_back({{"name", e.name},
                                   {"depth", finiteOrNull(tidy(e.depth))},
                                   {"behindWeapon", e.behindWeapon},
                                   {"drawnPixels", {{"left", e.drawnPixels[0]}, {"right", e.drawnPixels[1]}}},
                                   {"fadedPixels", {{"left", e.fadedPixels[0]}, {"right", e.fadedPixels[1]}}},
                                   {"conflictPixels", e.conflictPixels}});
             return elements;
           }()},
          {"memory",
           {{"estimatedBytes", report.memory.totalBytes()},
            {"hostBytes", report.memory.hostBytes},
            {"deviceBytes", report.memory.deviceBytes},
            {"peakResidentBytes", frame::peakResidentBytes()}}},
          {"files", report.filesWritten}};
}

}  // namespace s3d::app
