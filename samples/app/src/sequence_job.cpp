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
#include "s3d/app/scene_world.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/frame/stereo_synthesis.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_animation.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"

namespace s3d::app {
namespace {

// The pushed weapon's farthest point stays within this share of the distance to the nearest surface.
constexpr float kWeaponClearance = 0.9f;

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
  if (options.width == 0 || options.height == 0 || options.width > kMaxImageSize || options.height > kMaxImageSize)
    throw std::invalid_argument("sequence: resolution outside 1.." + std::to_string(kMaxImageSize));
  if (!(options.framesPerSecond > 0.0f) || options.framesPerSecond > 1000.0f)
    throw std::invalid_argument("sequence: frames per second must be in (0, 1000]");
  stereo::validate(options.stereo);
  renderer::Scene scene = renderer::loadScene(options.scene);  // built-in name or .gltf/.glb file
  const std::size_t frameCount = sequenceFrameCount(scene, options.framesPerSecond);
  if (frameCount == 0) throw std::invalid_argument("scene '" + options.scene + "' has no camera path and no animation");
  comfort::ZeroParallaxControlSettings settings = options.zeroParallax;
  settings.restDistance = options.stereo.zeroParallaxDistance;
  settings.minimumDistance = std::min(settings.minimumDistance, settings.restDistance);
  comfort::ZeroParallaxController control(settings);  // validates the settings
  comfort::CrosshairSmoother crosshair(options.crosshair.responseSeconds);
  comfort::validate(options.display);
  const float crosshairDistance = options.crosshair.distance.value_or(scene.crosshairDistance);

  frame::requireMemory(context, sequenceMemoryEstimate(options), options.memoryLimitBytes);  // before any is allocated
  // The world queries see the geometry drawn: rebuilt for every frame of an animated scene.
  std::optional<comfort::WorldQueries> world;
  world.emplace(worldMeshes(scene));
  const glm::vec2 weaponDepths = renderer::firstPersonDepthRange(scene).value_or(glm::vec2(0.0f));
  const bool budgetOn = options.disparityBudget != comfort::DisparityBudgetRule::Off;
  if (!(options.anticipateSeconds >= 0.0f) || options.anticipateSeconds > 10.0f)
    throw std::invalid_argument("sequence: anticipateSeconds must be in [0, 10]");
  std::optional<comfort::DisparityBudgetController> budgetControl;
  std::optional<stereo::DepthRangePass> reduction;
  if (budgetOn) {
    budgetControl.emplace(comfort::disparityBudget(options.display), options.allowNegativeParallax);
    reduction.emplace(context);
  }
  const comfort::FrameDisparityMapper mapper(context);
  glm::vec3 previousPosition(0.0f);

  // Guard band (no edge crop given): the center view is rendered wider by the largest displacement the eyes can
  // need, as in `s3d render`, so both eyes are full frame. The band follows the frame's parameters; the renderer
  // is replaced only when a frame needs a wider one (rare: the separation is bounded by the budget).
  const bool guardBand = options.stereo.edgeCrop < 0.0f;
  const std::uint32_t width = options.width, height = options.height;
  auto bandFor = [&](const stereo::StereoParameters& p) {
    if (!guardBand) return stereo::GuardBand{};
    float nearest = p.zeroParallaxDistance;
    if (options.allowNegativeParallax) {
      nearest = scene.camera.nearPlane;
      if (weaponDepths.x > 0.0f) nearest = std::min(nearest, p.weaponDepthOffset + p.weaponDepthScale * weaponDepths.x);
    }
    return stereo::guardBandFor(p.maxSeparation, p.zeroParallaxDistance, nearest, width,
                                kMaxImageSize / options.supersample);
  };
  stereo::GuardBand band;
  std::unique_ptr<renderer::DeferredRenderer> deferred;
  // The eyes of every frame (the method's switch, the hybrid's eye renderer and the previous-frame fill's history),
  // made with the center view's renderer for its size.
  std::unique_ptr<frame::StereoSynthesis> synthesis;
  auto useBand = [&](const stereo::GuardBand& wanted) {
    if (deferred && wanted.columns <= band.columns) return false;
    band = wanted;
    const renderer::RendererOptions rendererOptions{options.supersample, options.reversedZ};
    deferred = std::make_unique<renderer::DeferredRenderer>(context, band.renderedWidth(width), height, rendererOptions);
    deferred->setScene(scene);
    synthesis = std::make_unique<frame::StereoSynthesis>(
        context, frame::StereoSynthesisDescription{.width = band.renderedWidth(width), .height = height,
                                                   .renderer = rendererOptions,
                                                   .previousFrameFill = options.stereo.previousFrameFill});
    return true;
  };
  auto output = [&](const auto& image) { return stereo::cropColumns(image, band.columns, width); };
  auto outputMask = [&](const std::vector<std::uint8_t>& mask) {
    return stereo::cropColumns(mask, band.renderedWidth(width), band.columns, width);
  };

  // The previous frame's eyes (synthesized and reference), the reference's depth and first-person mask, and the
  // eye cameras: the flicker metric's other frame.
  struct EyeFrames {
    stereo::StereoPair synthesized, reference;
    std::array<DepthImage, 2> referenceDepth;
    std::array<std::vector<std::uint8_t>, 2> firstPerson;
    std::array<stereo::ReferenceCameras, 2> cameras;  // the output-size eye cameras per layer (the metric's)
    std::uint32_t crop = 0;
  };
  std::optional<EyeFrames> previous;
  SequenceReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  for (std::size_t index = 0; index < frameCount; ++index) {
    if (scene.animation && index > 0) {  // frame N at N / rate seconds; the loaded scene is frame 0's pose
      renderer::poseScene(scene, double(index) / double(options.framesPerSecond));
      world.emplace(worldMeshes(scene));
      if (deferred) deferred->updateGeometry(scene);  // the textures stay uploaded
      if (synthesis) synthesis->updateGeometry(scene);
    }
    SequenceFrame frame;
    frame.index = index;
    scene.camera = renderer::cameraForFrame(scene, options.holdFrame.value_or(index));
    frame.nearestSurface = comfort::nearestSurfaceAhead(*world, scene.camera, settings,
                                                        settings.engageDistance + settings.releaseMargin + 1.0f);
    const float seconds = 1.0f / options.framesPerSecond;
    frame.zeroParallaxDistance = control.update(frame.nearestSurface, seconds);
    // The weapon push shrinks with the zero-parallax distance (pushed = ratio * (offset + scale * depth)),
    // and at once, not smoothed, whenever its farthest pushed point would otherwise reach the nearest
    // surface: the pushed weapon must never appear behind a wall it is in front of.
    float ratio = frame.zeroParallaxDistance / settings.restDistance;
    if (frame.nearestSurface) {
      const float farthestPushed = options.stereo.weaponDepthOffset + options.stereo.weaponDepthScale * weaponDepths.y;
      ratio = std::min(ratio, kWeaponClearance * *frame.nearestSurface / farthestPushed);
    }
    stereo::StereoParameters parameters = options.stereo;
    parameters.weaponDepthOffset = options.stereo.weaponDepthOffset * ratio;
    parameters.weaponDepthScale = options.stereo.weaponDepthScale * ratio;
    parameters.zeroParallaxDistance = frame.zeroParallaxDistance;
    // No negative parallax: the weapon's nearest pushed point may not come in front of the screen plane. The
    // push is squeezed between the plane and its (wall-capped) farthest point; only when the wall leaves no
    // room behind the plane does the zero-parallax distance give way, at once.
    auto limitZeroParallax = [&](float limit) {
      if (options.allowNegativeParallax || !(limit < frame.zeroParallaxDistance)) return;
      frame.zeroParallaxDistance = control.limit(limit);
      parameters.zeroParallaxDistance = frame.zeroParallaxDistance;
      frame.zeroParallaxLimited = true;
    };
    if (!options.allowNegativeParallax && weaponDepths.x > 0.0f) {
      const float pushedFarthest = parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponDepths.y;
      if (pushedFarthest < frame.zeroParallaxDistance) limitZeroParallax(parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponDepths.x);
      parameters = comfort::pushWeaponBehindScreen(parameters, weaponDepths.x, weaponDepths.y);
    }
    frame.weaponDepthOffset = parameters.weaponDepthOffset;
    frame.weaponDepthScale = parameters.weaponDepthScale;
    const comfort::CrosshairPlacement placement =
        comfort::placeCrosshair(*world, scene.camera, crosshairDistance, options.crosshair.margin);
    if (placement.hitWorld) frame.aimSurface = placement.surfaceDistance;
    frame.crosshairDepth = crosshair.update(placement, seconds);

    (void)useBand(bandFor(parameters));
    renderer::ViewMatrices center;
    auto renderCenter = [&] {
      center = renderer::centerViewMatrices(scene, float(band.renderedWidth(width)) / float(height),
                                            {parameters.weaponDepthOffset, parameters.weaponDepthScale});
      deferred->render(center);
    };
    renderCenter();
    DepthImage renderedDepth = deferred->readLinearDepth();
    // ... and no world surface may be nearer than the screen plane either (the control's rays see only a few
    // directions; the depth image sees every pixel, the band's included: its content reaches the eyes).
    if (const std::optional<float> nearest = comfort::nearestDepth(renderedDepth)) {
      frame.nearestDepth = *nearest;
      limitZeroParallax(*nearest);
    }
    parameters.zeroParallaxDistance = frame.zeroParallaxDistance;
    if (budgetOn) {
      // Ray casts from where the camera will be (current velocity) warn of a surface before it is in view.
      comfort::BudgetFrameHints hints{frame.crosshairDepth, comfort::weaponNearestPushed(parameters, weaponDepths), std::nullopt, false};
      if (index > 0 && options.anticipateSeconds > 0.0f) {
        renderer::Camera ahead = scene.camera;
        ahead.position += (scene.camera.position - previousPosition) * (options.anticipateSeconds * options.framesPerSecond);
        hints.anticipatedNearest = comfort::nearestSurfaceAhead(*world, ahead, settings, 8.0f);
        // Receding: the same rays reach farther from there than from here (a trend in the depth range, which
        // the controller follows without its hold).
        const float here = comfort::nearestSurfaceAhead(*world, scene.camera, settings, 8.0f).value_or(INFINITY);
        hints.receding = hints.anticipatedNearest.value_or(INFINITY) > here;
      }
      frame.budget = comfort::applyDisparityBudget(context, *reduction, &*budgetControl, deferred->linearDepth(), hints, seconds,
                                          parameters);
      frame.budget.imageWidth = width;  // budgetPx and bulkShare in the output eyes' pixels, as the comfort report
      frame.zeroParallaxDistance = parameters.zeroParallaxDistance;
      // A larger chosen separation needs a wider band: this frame's center view again at that width.
      if (useBand(bandFor(parameters))) {
        renderCenter();
        renderedDepth = deferred->readLinearDepth();
      }
    }
    previousPosition = scene.camera.position;
    frame.maxSeparation = parameters.maxSeparation;
    if (guardBand) parameters.edgeCrop = 0.0f;  // the output eyes are full frame
    const std::uint32_t crop =
        guardBand ? 0u : std::uint32_t(stereo::makeStereoConstants(parameters, width, height).cropBegin);
    frame.cropColumns = crop;
    frame.guardBandColumns = band.columns;
    // The pass and the reference cameras on the rendered frame: the same parallax in pixels, the band cropped.
    const stereo::StereoParameters renderedParameters =
        guardBand ? stereo::guardBandParameters(parameters, width, band) : parameters;
    const DepthImage pushed = output(renderedDepth);
    // The crosshair not in front of the screen plane either (the plane is never beyond the aimed-at surface).
    if (!options.allowNegativeParallax) frame.crosshairDepth = std::max(frame.crosshairDepth, frame.zeroParallaxDistance);
    // Nonlinear mapping: the frame's curve applied to the stereo pass's depth (GPU) and to the C++ copy alike.
    frame.disparityMap = mapper.apply(context, deferred->linearDepth(), parameters);
    const gpu::DisparityMapConstants& map = frame.disparityMap.map;
    const DepthImage stereoDepth = stereo::mappedDepthImage(pushed, map);
    frame.comfort = comfort::frameComfort(stereoDepth, parameters, options.display);
    // The output-size center view's matrices: per-pixel rays over the output's depth, and the eye cameras the
    // flicker metric moves along.
    const renderer::ViewMatrices outputCenter = renderer::centerViewMatrices(
        scene, float(width) / float(height), {parameters.weaponDepthOffset, parameters.weaponDepthScale});
    const comfort::WeaponConflicts conflicts = comfort::countWeaponConflicts(
        *world, scene.camera, outputCenter.worldProjection, pushed, outputMask(deferred->readFirstPersonMask()));
    frame.weaponPixels = conflicts.weaponPixels;
    frame.weaponConflictPixels = conflicts.conflictPixels;
    EyeFrames current;
    const frame::SynthesizedEyes eyes = synthesis->synthesize({*deferred, scene, center, renderedParameters});
    frame.stereoPassGpuMs = eyes.gpuMs;

    current.synthesized = {output(eyes.eyes.left), output(eyes.eyes.right)};
    current.crop = crop;
    // The two-pass reference, one rendering per segment of a nonlinear map (layered_reference.h); its depth as
    // rendered (the flicker metric's reprojection) and mapped (the disocclusion mask, as the stereo pass's).
    std::array<DepthImage, 2> mappedReferenceDepth;
    const std::vector<stereo::DisparityMapSegment> segments = stereo::disparityMapSegments(map);
    for (stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
      const std::size_t e = eye == stereo::Eye::Left ? 0 : 1;
      frame::ReferenceEye reference = frame::renderReferenceEye(*deferred, scene, center, eye, renderedParameters, map);
      (e == 0 ? current.reference.left : current.reference.right) = output(reference.display);
      current.referenceDepth[e] = output(reference.depth);
      mappedReferenceDepth[e] = stereo::mappedDepthImage(current.referenceDepth[e], map);
      current.firstPerson[e] = outputMask(reference.firstPerson);
      if (e == 0) frame.disparityMap.referenceLayers = reference.layers;
      frame.disparityMap.unresolvedPixels[e] = reference.unresolvedPixels;
      // The metric's cameras: each layer's, on the output-size frame.
      stereo::ReferenceCameras& cameras = current.cameras[e];
      cameras.segments = segments;
      for (const stereo::DisparityMapSegment& segment : segments) {
        const renderer::ViewMatrices eyeView = frame::referenceEyeView(scene, outputCenter, eye, parameters, segment);
        cameras.view.push_back(eyeView.worldView);
        cameras.projection.push_back(eyeView.worldProjection);
      }
      if (segments.size() > 1) cameras.layerOfPixel = outputMask(reference.layerOfPixel);
    }
    frame.psnrLeftDb = stereo::compareDisplayImages(current.synthesized.left, current.reference.left, crop).psnrDb;
    frame.psnrRightDb = stereo::compareDisplayImages(current.synthesized.right, current.reference.right, crop).psnrDb;
    if (previous) {
      const std::vector<std::uint8_t> halo = stereo::haloMaskFor(stereoDepth, parameters);
      std::array<stereo::FlickerStats, 2> flicker;
      for (stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
        const std::size_t e = eye == stereo::Eye::Left ? 0 : 1;
        auto eyeFrame = [&](const EyeFrames& f) {
          return stereo::EyeFrame{e == 0 ? &f.synthesized.left : &f.synthesized.right,
                                  e == 0 ? &f.reference.left : &f.reference.right, &f.referenceDepth[e],
                                  f.firstPerson[e], f.crop};
        };
        flicker[e] = stereo::temporalFlicker(eyeFrame(current), eyeFrame(*previous), current.cameras[e],
                                             previous->cameras[e], halo,
                                             stereo::disocclusionMaskFor(mappedReferenceDepth[e], stereoDepth, parameters, eye));
      }
      frame.flicker = flicker;
    }
    previous = std::move(current);

    if (options.writeFrames) {
      char name[48];
      std::snprintf(name, sizeof(name), "anaglyph_%04zu.png", index);
      io::writePng(options.outputFolder / name, stereo::makeAnaglyphDubois(previous->synthesized.left, previous->synthesized.right));
      report.filesWritten.push_back(name);
    }
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
