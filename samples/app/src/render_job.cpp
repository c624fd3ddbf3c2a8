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
#include "s3d/frame/comforted_stereo_frame.h"
#include "s3d/frame/layered_reference.h"
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
  auto eyeJson = [&](const stereo::HybridThreshold& threshold, std::uint64_t maskedPixels) {
    return nlohmann::json{{"thresholdBin", threshold.bin},
                          {"splitBin", threshold.splitBin < S3D_HYBRID_BINS ? nlohmann::json(threshold.splitBin) : nlohmann::json()},
                          {"splitCells", threshold.splitPixels},
                          {"maskedPixels", maskedPixels},
                          {"maskedShare", finiteOrNull(tidy(float(maskedPixels) /
                                                            float(std::max<std::uint64_t>(hybrid.classifiedPixels, 1))))}};
  };
  return {{"budget", finiteOrNull(tidy(hybrid.budget))},
          {"base", stereo::methodName(hybrid.base)},
          {"cell", hybrid.cell},
          {"classifiedPixels", hybrid.classifiedPixels},
          {"left", eyeJson(hybrid.thresholds[0], hybrid.maskedPixels[0])},
          {"right", eyeJson(hybrid.thresholds[1], hybrid.maskedPixels[1])},
          {"gpuTimeMs", toJson(hybrid.timings)}};
}

// The frame's comfort rules as the options ask: a guard band unless --edge-crop, the HUD unless none; a wider band
// chosen by the disparity budget is checked against the memory before it is rendered.
frame::ComfortedStereoFrameDescription frameDescription(vk::Context& context, const RenderJobOptions& options,
                                                        const ValidatedJob& job, RenderReport& report) {
  frame::ComfortedStereoFrameDescription description;
  description.width = options.width;
  description.height = options.height;
  description.renderer = {options.supersample, options.reversedZ};
  description.stereo = job.stereo;
  description.comfort = {.display = options.display, .budget = options.disparityBudget,
                         .allowNegativeParallax = options.allowNegativeParallax, .crosshair = options.crosshair};
  description.guardBand = options.stereo.edgeCrop < 0.0f;
  description.maxRenderedWidth = kMaxImageSize / options.supersample;
  description.hud = resolveHudMode(options.hud, options.scene) == HudMode::Game;
  description.warmUp = true;  // the center frame, the stereo pass and the reference eye are all timed warm
  description.keepHdr = true;
  description.beforeWiderBand = [&context, &options, &report](const stereo::StereoParameters& parameters,
                                                              std::uint32_t renderedWidth) {
    report.memory = estimateAtRenderedWidth(options, parameters, renderedWidth);
    report.memory.what += " at the separation --disparity-budget chose (" + numberText(parameters.maxSeparation) + ")";
    report.memory.lower += " or give --disparity-budget off";
    frame::requireMemory(context, report.memory, options.memoryLimitBytes);
  };
  return description;
}

// What the frame applied and measured, as the report states it.
void reportFrame(const frame::ComfortedFrame& frame, RenderReport& report) {
  report.budget = frame.budget;
  report.zeroParallaxLimited = frame.zeroParallaxLimited;
  report.centerFrameGpuMs = frame.centerTimings.totalGpuMs;
  report.centerPasses = frame.centerTimings.passes;
  report.sanitized.depthPixels = frame.sanitizedDepthPixels;
  report.sanitized.colorValues = frame.sanitizedColorValues;
  report.disparityMap = frame.disparityMap;
  if (frame.band.capped)
    report.warnings.push_back("guard band capped at " + std::to_string(frame.band.columns) + " columns per side (" +
                              std::to_string(frame.band.neededColumns) +
                              " needed): the outermost eye columns repeat the band's edge");
  report.guardBandColumns = frame.band.columns;
  report.renderedWidth = frame.renderedWidth;
  report.cropColumns = frame.cropColumns;
  report.stereo = frame.parameters;
  if (report.stereo.edgeCrop < 0.0f) report.stereo.edgeCrop = report.stereo.maxSeparation;
  report.stereoPassGpuMs = frame.synthesized.gpuMs;
  report.filledPixels = {frame.synthesized.filledLeft, frame.synthesized.filledRight};
  report.comfort = frame.comfort;
  report.weaponConflictPixels = frame.weaponConflicts.conflictPixels;
}

// The same gather on the linear HDR center view, by the C++ reference of the method (hdr_gather.h); the hybrid's
// pixels rendered from the eye cameras go into the HDR eyes too.
stereo::HdrStereoPair outputHdrEyes(frame::ComfortedFrame& frame, RenderReport& report) {
  stereo::HdrStereoPair eyes =
      stereo::synthesizeHdrReference(frame.renderedHdr, frame.renderedStereoDepth, frame.renderedParameters);
  if (const std::optional<frame::HybridSynthesis>& hybrid = frame.synthesized.hybrid) {
    stereo::compositeHybridReference(eyes.left, hybrid->renderedHdr[0], hybrid->masks[0]);
    stereo::compositeHybridReference(eyes.right, hybrid->renderedHdr[1], hybrid->masks[1]);
    report.hybrid = HybridReport{frame.parameters.hybridBudget, frame.parameters.hybridBase, hybrid->classifiedPixels,
                                 hybrid->cell, hybrid->thresholds, hybrid->maskedPixels,
                                 std::move(frame.synthesized.hybrid->timings)};
  }
  return {frame.toOutput(eyes.left), frame.toOutput(eyes.right)};
}

struct OutputReference {  // one reference eye cropped to the output
  frame::ReferenceEye rendered;
  ImageRGBA8 display;
  DepthImage depth;  // mapped as the stereo pass's depth (disocclusion regions)
  ImageRGBA32F hdr;
  std::vector<std::uint8_t> transparent;
  std::vector<std::uint8_t> foliage;
};

// The two-pass reference: each eye rendered with its off-axis camera on the rendered frame, cropped to the output
// (the same rays as an output-size eye, tests/stereo/test_guard_band.cpp); a nonlinear map takes one rendering per
// segment of its curve (layered_reference.h).
std::array<OutputReference, 2> outputReferences(frame::ComfortedStereoFrame& stereoFrame,
                                                const frame::ComfortedFrame& frame, const renderer::Scene& scene,
                                                RenderReport& report) {
  const gpu::DisparityMapConstants& map = frame.disparityMap.map;
  auto referenceFor = [&](stereo::Eye side) {
    OutputReference eye{frame::renderReferenceEye(stereoFrame.centerRenderer(), scene, frame.center, side,
                                                  frame.renderedParameters, map),
                        {}, {}, {}, {}, {}};
    eye.display = frame.toOutput(eye.rendered.display);
    eye.depth = frame.toOutput(stereo::mappedDepthImage(eye.rendered.depth, map));
    eye.hdr = frame.toOutput(eye.rendered.hdr);
    eye.transparent = frame.maskToOutput(eye.rendered.transparent);
    eye.foliage = frame.maskToOutput(eye.rendered.foliage);
    return eye;
  };
  std::array<OutputReference, 2> eyes{referenceFor(stereo::Eye::Left), referenceFor(stereo::Eye::Right)};
  report.referenceEyeGpuMs = eyes[0].rendered.firstLayerGpuMs;
  report.disparityMap.referenceLayers = eyes[0].rendered.layers;
  report.disparityMap.unresolvedPixels = {eyes[0].rendered.unresolvedPixels, eyes[1].rendered.unresolvedPixels};
  return eyes;
}

// Synthesized vs reference over the full frame with a guard band, else without the cropped strips (region masks
// and comparison: s3d/stereo/eye_comparison.h, shared with s3d bench).
void compareEyes(const frame::ComfortedFrame& frame, const stereo::HdrStereoPair& eyesHdr,
                 const std::array<OutputReference, 2>& references, RenderReport& report) {
  const std::vector<std::uint8_t> halo = stereo::haloMaskFor(frame.stereoDepth, frame.parameters);
  for (auto [eyeError, eye, eyeHdr, reference, side] :
       {std::tuple{&report.left, &frame.eyes.left, &eyesHdr.left, &references[0], stereo::Eye::Left},
        std::tuple{&report.right, &frame.eyes.right, &eyesHdr.right, &references[1], stereo::Eye::Right}}) {
    const stereo::RegionMasks masks{halo,
                                    stereo::disocclusionMaskFor(reference->depth, frame.stereoDepth, frame.parameters, side),
                                    reference->transparent, reference->foliage};
    *eyeError = stereo::compareEye(*eye, reference->display, report.cropColumns, masks, eyeHdr, &reference->hdr);
  }
}

// The images the outputs show: the HUD (drawn by the frame into its eyes) drawn over the center view and the
// references too, after the comparison so it cannot flatter the error.
struct OutputImages {
  ImageRGBA8 center;
  ImageRGBA32F centerHdr;
  stereo::StereoPair eyes, references;
  const stereo::StereoPair* eyesWithoutHud;  // the error heat maps' (as measured)
  const std::array<OutputReference, 2>* referencesWithoutHud;
  const DepthImage* centerDepth;
};

// Each selected output written atomically by s3d::io; report.json last so it lists everything before it.
void writeOutputs(const RenderJobOptions& options, const OutputImages& images, RenderReport& report) {
  auto selected = [&](const std::string& name) { return options.outputs.count(name) != 0; };
  const fs::path& folder = options.outputFolder;
  auto writeOutputPng = [&](const std::string& name, const ImageRGBA8& image) {
    if (!selected(name)) return;
    io::writePng(folder / name, image);
    report.filesWritten.push_back(name);
  };
  writeOutputPng("center.png", images.center);
  if (selected("center.exr")) {
    io::writeExr(folder / "center.exr", images.centerHdr, images.centerDepth);
    report.filesWritten.push_back("center.exr");
  }
  const stereo::StereoPair& eyes = images.eyes;
  writeOutputPng("left.png", eyes.left);
  writeOutputPng("right.png", eyes.right);
  writeOutputPng("left_reference.png", images.references.left);
  writeOutputPng("right_reference.png", images.references.right);
  if (selected("anaglyph.png")) writeOutputPng("anaglyph.png", stereo::makeAnaglyphDubois(eyes.left, eyes.right));
  if (selected("sbs.png")) writeOutputPng("sbs.png", stereo::makeSideBySide(eyes.left, eyes.right, options.sideBySide));
  if (selected("tab.png")) writeOutputPng("tab.png", stereo::makeTopAndBottom(eyes.left, eyes.right, options.topBottom));
  const std::array<OutputReference, 2>& references = *images.referencesWithoutHud;
  if (selected("error_left.png"))
    writeOutputPng("error_left.png", stereo::makeErrorHeatMap(images.eyesWithoutHud->left, references[0].display,
                                                              report.cropColumns));
  if (selected("error_right.png"))
    writeOutputPng("error_right.png", stereo::makeErrorHeatMap(images.eyesWithoutHud->right, references[1].display,
                                                               report.cropColumns));
  if (!selected("report.json")) return;
  report.filesWritten.push_back("report.json");  // listed in itself: the document describes the whole output
  try {
    io::writeTextFile(folder / "report.json", toJson(report).dump(2) + "\n");
  } catch (...) {
    report.filesWritten.pop_back();
    throw;
  }
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
  RenderReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  report.width = options.width;
  report.height = options.height;
  report.warnings = job.warnings;
  report.memory = memory;
  report.display = options.display;

  // 2. The center view, the comfort rules and both eyes synthesized on the GPU (s3d/frame/comforted_stereo_frame.h);
  // a single frame: the budget's controller from rest, at 30 frames per second.
  frame::ComfortedStereoFrame stereoFrame(context, frameDescription(context, options, job, report));
  frame::ComfortedFrame frame = stereoFrame.render(job.scene, 1.0f / 30.0f);
  reportFrame(frame, report);
  const stereo::HdrStereoPair eyesHdr = outputHdrEyes(frame, report);
  OutputImages images{frame.toOutput(stereoFrame.centerRenderer().readDisplayColor()), frame.toOutput(frame.renderedHdr),
                      frame.eyesWithHud, {}, &frame.eyes, nullptr, &frame.depth};
  stereoFrame.releaseSynthesis();  // the hybrid's eye renderer is released before the reference eyes are rendered

  // 3. The two-pass reference and the comparison.
  const std::array<OutputReference, 2> references = outputReferences(stereoFrame, frame, job.scene, report);
  compareEyes(frame, eyesHdr, references, report);

  // 4. The HUD as drawn (s3d/frame/frame_hud.h), over the center view and the references too.
  report.crosshair = {frame.hud.crosshairDepth, frame.crosshair.hitWorld,
                      hud::crosshairEyeOffsetPx(frame.parameters, gpu::mappedDepth(frame.disparityMap.map,
                                                                                   frame.hud.crosshairDepth),
                                                options.width, stereo::Eye::Right)};
  report.hud = frame.hud.elements;
  report.hudConflictPixels = frame.hud.conflictPixels;
  images.references = {references[0].display, references[1].display};
  images.referencesWithoutHud = &references;
  frame::drawHudOver(frame.hudInput(), &images.center, &images.references);

  // 5. Outputs.
  writeOutputs(options, images, report);
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
