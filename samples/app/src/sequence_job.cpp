#include "s3d/app/sequence_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "s3d/app/comfort_json.h"
#include "s3d/app/render_job.h"
#include "s3d/app/report_json.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/frame/comforted_stereo_frame.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/scene_animation.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::app {
namespace {

nlohmann::json flickerJson(const std::array<stereo::FlickerStats, 2>& flicker) {
  auto region = [](const stereo::FlickerRegion& r) {
    return nlohmann::json{{"meanLevels", r.meanLevels}, {"pixelCount", r.pixelCount}};
  };
  auto eye = [&](const stereo::FlickerStats& f) {
    return nlohmann::json{{"all", region(f.all)},
                          {"halo", region(f.halo)},
                          {"disocclusion", region(f.disocclusion)},
                          {"newlyVisiblePixels", f.newlyVisiblePixels}};
  };
  return {{"left", eye(flicker[0])}, {"right", eye(flicker[1])}};
}

// The sequence's frames: the camera path's; an animated scene without one: one loop of its animation at the rate.
std::size_t sequenceFrameCount(const renderer::Scene& scene, float framesPerSecond) {
  if (!scene.cameraPath.empty()) return scene.cameraPath.size();
  if (!scene.animation) return 0;
  const double frames = std::ceil(scene.animation->duration() * double(framesPerSecond) - 1e-6);
  return std::size_t(std::clamp(frames, 1.0, 1.0e6));
}

// The comfort rules a sequence runs frame by frame: the zero-parallax control, the smoothed crosshair, the budget's
// anticipation; no HUD (the anaglyphs show the eyes as synthesized).
frame::ComfortedStereoFrameDescription frameDescription(const SequenceJobOptions& options,
                                                        const comfort::ZeroParallaxControlSettings& control) {
  frame::ComfortedStereoFrameDescription description;
  description.width = options.width;
  description.height = options.height;
  description.renderer = {options.supersample, options.reversedZ};
  description.stereo = options.stereo;
  description.comfort = {.display = options.display, .budget = options.disparityBudget,
                         .allowNegativeParallax = options.allowNegativeParallax, .zeroParallaxControl = control,
                         .crosshair = options.crosshair, .smoothCrosshair = true,
                         .anticipateFrames = options.anticipateSeconds * options.framesPerSecond};
  description.guardBand = options.stereo.edgeCrop < 0.0f;
  description.maxRenderedWidth = kMaxImageSize / options.supersample;
  description.hud = false;
  description.sanitizeDepth = false;
  return description;
}

// What the frame's rules applied and measured, as the report states it.
SequenceFrame sequenceFrame(std::size_t index, const frame::ComfortedFrame& applied) {
  SequenceFrame frame;
  frame.index = index;
  frame.zeroParallaxDistance = applied.parameters.zeroParallaxDistance;
  frame.nearestSurface = applied.nearestSurface;
  frame.crosshairDepth = applied.crosshairDepth;
  if (applied.crosshair.hitWorld) frame.aimSurface = applied.crosshair.surfaceDistance;
  frame.zeroParallaxLimited = applied.zeroParallaxLimited;
  frame.nearestDepth = applied.nearestDepth.value_or(0.0f);
  frame.comfort = applied.comfort;
  frame.weaponDepthOffset = applied.parameters.weaponDepthOffset;
  frame.weaponDepthScale = applied.parameters.weaponDepthScale;
  frame.weaponPixels = applied.weaponConflicts.weaponPixels;
  frame.weaponConflictPixels = applied.weaponConflicts.conflictPixels;
  frame.budget = applied.budget;
  frame.disparityMap = applied.disparityMap;
  frame.maxSeparation = applied.parameters.maxSeparation;
  frame.cropColumns = applied.cropColumns;
  frame.guardBandColumns = applied.band.columns;
  frame.stereoPassGpuMs = applied.synthesized.gpuMs;
  return frame;
}

// The eyes of a frame (synthesized and reference), the reference's depth and first-person mask, and the eye
// cameras: the flicker metric's other frame.
struct EyeFrames {
  stereo::StereoPair synthesized, reference;
  std::array<DepthImage, 2> referenceDepth;
  std::array<DepthImage, 2> mappedReferenceDepth;  // as the stereo pass's (the disocclusion mask)
  std::array<std::vector<std::uint8_t>, 2> firstPerson;
  std::array<stereo::ReferenceCameras, 2> cameras;  // the output-size eye cameras per layer (the metric's)
  std::uint32_t crop = 0;
};

// The two-pass reference, one rendering per segment of a nonlinear map (layered_reference.h); its depth as rendered
// (the flicker metric's reprojection) and mapped (the disocclusion mask, as the stereo pass's).
EyeFrames eyeFrames(frame::ComfortedStereoFrame& stereoFrame, const frame::ComfortedFrame& applied,
                    const renderer::Scene& scene, SequenceFrame& frame) {
  EyeFrames current;
  current.synthesized = applied.eyes;
  current.crop = applied.cropColumns;
  const gpu::DisparityMapConstants& map = applied.disparityMap.map;
  const std::vector<stereo::DisparityMapSegment> segments = stereo::disparityMapSegments(map);
  for (stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
    const std::size_t e = eye == stereo::Eye::Left ? 0 : 1;
    frame::ReferenceEye reference = frame::renderReferenceEye(stereoFrame.centerRenderer(), scene, applied.center, eye,
                                                              applied.renderedParameters, map);
    (e == 0 ? current.reference.left : current.reference.right) = applied.toOutput(reference.display);
    current.referenceDepth[e] = applied.toOutput(reference.depth);
    current.mappedReferenceDepth[e] = stereo::mappedDepthImage(current.referenceDepth[e], map);
    current.firstPerson[e] = applied.maskToOutput(reference.firstPerson);
    if (e == 0) frame.disparityMap.referenceLayers = reference.layers;
    frame.disparityMap.unresolvedPixels[e] = reference.unresolvedPixels;
    // The metric's cameras: each layer's, on the output-size frame.
    stereo::ReferenceCameras& cameras = current.cameras[e];
    cameras.segments = segments;
    for (const stereo::DisparityMapSegment& segment : segments) {
      const renderer::ViewMatrices eyeView =
          frame::referenceEyeView(scene, applied.outputCenter, eye, applied.parameters, segment);
      cameras.view.push_back(eyeView.worldView);
      cameras.projection.push_back(eyeView.worldProjection);
    }
    if (segments.size() > 1) cameras.layerOfPixel = applied.maskToOutput(reference.layerOfPixel);
  }
  return current;
}

// Left, right: the change of each eye's error since the previous frame along the camera's motion.
std::array<stereo::FlickerStats, 2> flickerSince(const EyeFrames& previous, const EyeFrames& current,
                                                 const frame::ComfortedFrame& applied) {
  const std::vector<std::uint8_t> halo = stereo::haloMaskFor(applied.stereoDepth, applied.parameters);
  std::array<stereo::FlickerStats, 2> flicker;
  for (stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
    const std::size_t e = eye == stereo::Eye::Left ? 0 : 1;
    auto eyeFrame = [&](const EyeFrames& f) {
      return stereo::EyeFrame{e == 0 ? &f.synthesized.left : &f.synthesized.right,
                              e == 0 ? &f.reference.left : &f.reference.right, &f.referenceDepth[e], f.firstPerson[e],
                              f.crop};
    };
    flicker[e] = stereo::temporalFlicker(
        eyeFrame(current), eyeFrame(previous), current.cameras[e], previous.cameras[e], halo,
        stereo::disocclusionMaskFor(current.mappedReferenceDepth[e], applied.stereoDepth, applied.parameters, eye));
  }
  return flicker;
}

// The options a sequence checks before it loads or allocates anything; returns the control's settings.
comfort::ZeroParallaxControlSettings validateSequence(const SequenceJobOptions& options) {
  if (options.width == 0 || options.height == 0 || options.width > kMaxImageSize || options.height > kMaxImageSize)
    throw std::invalid_argument("sequence: resolution outside 1.." + std::to_string(kMaxImageSize));
  if (!(options.framesPerSecond > 0.0f) || options.framesPerSecond > 1000.0f)
    throw std::invalid_argument("sequence: frames per second must be in (0, 1000]");
  stereo::validate(options.stereo);
  comfort::ZeroParallaxControlSettings settings = options.zeroParallax;
  settings.restDistance = options.stereo.zeroParallaxDistance;
  settings.minimumDistance = std::min(settings.minimumDistance, settings.restDistance);
  comfort::validate(settings);
  comfort::validate(options.display);
  if (!(options.anticipateSeconds >= 0.0f) || options.anticipateSeconds > 10.0f)
    throw std::invalid_argument("sequence: anticipateSeconds must be in [0, 10]");
  return settings;
}

void writeAnaglyph(const SequenceJobOptions& options, std::size_t index, const stereo::StereoPair& eyes,
                   SequenceReport& report) {
  char name[48];
  std::snprintf(name, sizeof(name), "anaglyph_%04zu.png", index);
  io::writePng(options.outputFolder / name, stereo::makeAnaglyphDubois(eyes.left, eyes.right));
  report.filesWritten.push_back(name);
}

}  // namespace

stereo::GuardBand widestSequenceGuardBand(const SequenceJobOptions& options) {
  if (!(options.stereo.edgeCrop < 0.0f)) return {};
  // The separation's, or the largest the disparity budget's controller may choose (its clamp: a frame of shallow
  // depth gets more than the display's uncrossed budget), from the zero-parallax plane (no negative parallax:
  // nothing is nearer). With negative parallax allowed the controls move the plane and the weapon, so the band
  // may reach its cap (a tiny nearest depth stands for it).
  float separation = options.stereo.maxSeparation;
  if (options.disparityBudget != comfort::DisparityBudgetRule::Off)
    separation = std::max(separation, comfort::DisparityBudgetSettings{}.maximumSeparation);
  const double plane = options.stereo.zeroParallaxDistance;
  const double nearest = options.allowNegativeParallax ? plane * 1.0e-9 : plane;
  return stereo::guardBandFor(separation, plane, nearest, options.width, kMaxImageSize / std::max(options.supersample, 1u));
}

frame::MemoryEstimate sequenceMemoryEstimate(const SequenceJobOptions& options) {
  const std::uint32_t renderedWidth = widestSequenceGuardBand(options).renderedWidth(options.width);
  frame::MemoryEstimate estimate = frame::renderMemoryEstimate(options.width, options.height, renderedWidth, options.supersample,
                                                 options.stereo.method == stereo::StereoMethod::Hybrid,
                                                 frame::maxReferenceLayers(options.stereo.disparityMapping));
  // The previous frame, kept for the flicker metric: eyes and references 16, reference depths 8, first-person
  // masks 2 and (a nonlinear map) reference layers 2 bytes per output pixel; the previous-frame fill's history:
  // two frames of both eyes' colour and depth (RGBA8 and R32F) on the device per rendered pixel.
  const std::uint64_t outputPixels = std::uint64_t(options.width) * options.height;
  const bool layered = options.stereo.disparityMapping == stereo::DisparityMapping::Nonlinear;
  estimate.hostBytes += (layered ? 28 : 26) * outputPixels;
  if (options.stereo.previousFrameFill) estimate.deviceBytes += 32 * std::uint64_t(renderedWidth) * options.height;
  if (!estimate.what.empty() && estimate.what.back() == ')') estimate.what.pop_back();
  estimate.what += options.stereo.previousFrameFill ? "; the previous frame and the fill's history)"
                                                    : "; the previous frame)";
  return estimate;
}

SequenceReport runSequenceJob(vk::Context& context, const SequenceJobOptions& options) {
  const comfort::ZeroParallaxControlSettings control = validateSequence(options);
  renderer::Scene scene = renderer::loadScene(options.scene);  // built-in name or .gltf/.glb file
  const std::size_t frameCount = sequenceFrameCount(scene, options.framesPerSecond);
  if (frameCount == 0) throw std::invalid_argument("scene '" + options.scene + "' has no camera path and no animation");
  frame::requireMemory(context, sequenceMemoryEstimate(options), options.memoryLimitBytes);  // before any is allocated
  // The comfort rules and the eyes of every frame (s3d/frame/comforted_stereo_frame.h), their state kept between
  // frames; a guard band (no edge crop given) follows the frames' parameters and widens only when one needs it.
  frame::ComfortedStereoFrame stereoFrame(context, frameDescription(options, control));
  std::optional<EyeFrames> previous;
  SequenceReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  for (std::size_t index = 0; index < frameCount; ++index) {
    if (scene.animation && index > 0) {  // frame N at N / rate seconds; the loaded scene is frame 0's pose
      renderer::poseScene(scene, double(index) / double(options.framesPerSecond));
      stereoFrame.updateGeometry(scene);
    }
    scene.camera = renderer::cameraForFrame(scene, options.holdFrame.value_or(index));
    const frame::ComfortedFrame applied = stereoFrame.render(scene, 1.0f / options.framesPerSecond);
    SequenceFrame frame = sequenceFrame(index, applied);
    EyeFrames current = eyeFrames(stereoFrame, applied, scene, frame);
    frame.psnrLeftDb = stereo::compareDisplayImages(current.synthesized.left, current.reference.left, current.crop).psnrDb;
    frame.psnrRightDb = stereo::compareDisplayImages(current.synthesized.right, current.reference.right, current.crop).psnrDb;
    if (previous) frame.flicker = flickerSince(*previous, current, applied);
    previous = std::move(current);
    if (options.writeFrames) writeAnaglyph(options, index, previous->synthesized, report);
    report.frames.push_back(frame);
  }
  if (options.writeReport) {
    report.filesWritten.push_back("report.json");
    io::writeTextFile(options.outputFolder / "report.json", toJson(report).dump(2) + "\n");
  }
  return report;
}

nlohmann::json toJson(const SequenceReport& report) {
  nlohmann::json frames = nlohmann::json::array();
  for (const SequenceFrame& frame : report.frames)
    frames.push_back({{"frame", frame.index},
                      {"zeroParallaxDistance", frame.zeroParallaxDistance},
                      {"nearestSurface", frame.nearestSurface ? nlohmann::json(*frame.nearestSurface) : nullptr},
                      {"zeroParallaxLimited", frame.zeroParallaxLimited},
                      {"nearestDepth", frame.nearestDepth},
                      {"crosshairDepth", frame.crosshairDepth},
                      {"aimSurface", frame.aimSurface ? nlohmann::json(*frame.aimSurface) : nullptr},
                      {"comfort", comfortJson(frame.comfort)},
                      {"weaponDepthOffset", frame.weaponDepthOffset},
                      {"weaponDepthScale", frame.weaponDepthScale},
                      {"weaponPixels", frame.weaponPixels},
                      {"weaponConflictPixels", frame.weaponConflictPixels},
                      {"psnrDb", {{"left", frame.psnrLeftDb}, {"right", frame.psnrRightDb}}},
                      {"maxSeparation", frame.maxSeparation},
                      {"cropColumns", frame.cropColumns},
                      {"guardBandColumns", frame.guardBandColumns},
                      {"stereoPassGpuMs", optionalMs(frame.stereoPassGpuMs)},
                      {"disparityBudget", budgetJson(frame.budget, frame.comfort)},
                      {"disparityMapping", disparityMapJson(frame.disparityMap)},
                      {"flicker", frame.flicker ? flickerJson(*frame.flicker) : nlohmann::json()}});
  return {{"device", report.deviceName}, {"scene", report.scene}, {"frames", frames},
          {"flicker", flickerJson(meanFlicker(report))}, {"files", report.filesWritten}};
}

std::array<stereo::FlickerStats, 2> meanFlicker(const SequenceReport& report) {
  std::array<stereo::FlickerStats, 2> mean{};
  std::size_t count = 0;
  for (const SequenceFrame& frame : report.frames) {
    if (!frame.flicker) continue;
    ++count;
    for (std::size_t eye = 0; eye < 2; ++eye) {
      const stereo::FlickerStats& f = (*frame.flicker)[eye];
      mean[eye].all.meanLevels += f.all.meanLevels, mean[eye].all.pixelCount += f.all.pixelCount;
      mean[eye].halo.meanLevels += f.halo.meanLevels, mean[eye].halo.pixelCount += f.halo.pixelCount;
      mean[eye].disocclusion.meanLevels += f.disocclusion.meanLevels;
      mean[eye].disocclusion.pixelCount += f.disocclusion.pixelCount;
      mean[eye].newlyVisiblePixels += f.newlyVisiblePixels;
    }
  }
  for (stereo::FlickerStats& eye : mean)
    for (stereo::FlickerRegion* region : {&eye.all, &eye.halo, &eye.disocclusion})
      region->meanLevels = count ? region->meanLevels / double(count) : 0.0;
  return mean;
}

}  // namespace s3d::app
