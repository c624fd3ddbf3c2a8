#include "s3d/app/sequence_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "s3d/app/comfort_json.h"
#include "s3d/app/eye_comparison.h"
#include "s3d/app/hybrid_stereo.h"
#include "s3d/app/memory_budget.h"
#include "s3d/app/render_job.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app {
namespace {

// The pushed weapon's farthest point stays within this share of the distance to the nearest surface.
constexpr float kWeaponClearance = 0.9f;

nlohmann::json flickerJson(const std::array<stereo::FlickerStats, 2>& flicker) {
  auto region = [](const stereo::FlickerRegion& r) {
    return nlohmann::json{{"meanLevels", r.meanLevels}, {"pixelCount", r.pixelCount}};
  };
  auto eye = [&](const stereo::FlickerStats& f) {
    return nlohmann::json{{"all", region(f.all)}, {"halo", region(f.halo)}, {"disocclusion", region(f.disocclusion)}};
  };
  return {{"left", eye(flicker[0])}, {"right", eye(flicker[1])}};
}

}  // namespace

SequenceReport runSequenceJob(vk::Context& context, const SequenceJobOptions& options) {
  if (options.width == 0 || options.height == 0 || options.width > kMaxImageSize || options.height > kMaxImageSize)
    throw std::invalid_argument("sequence: resolution outside 1.." + std::to_string(kMaxImageSize));
  if (!(options.framesPerSecond > 0.0f) || options.framesPerSecond > 1000.0f)
    throw std::invalid_argument("sequence: frames per second must be in (0, 1000]");
  stereo::validate(options.stereo);
  renderer::Scene scene = renderer::loadScene(options.scene);  // built-in name or .gltf/.glb file
  if (scene.cameraPath.empty()) throw std::invalid_argument("scene '" + options.scene + "' has no camera path");
  comfort::ZeroParallaxControlSettings settings = options.zeroParallax;
  settings.restDistance = options.stereo.zeroParallaxDistance;
  settings.minimumDistance = std::min(settings.minimumDistance, settings.restDistance);
  comfort::ZeroParallaxController control(settings);  // validates the settings
  comfort::CrosshairSmoother crosshair(options.crosshair.responseSeconds);
  comfort::validate(options.display);
  const float crosshairDistance = options.crosshair.distance.value_or(scene.crosshairDistance);

  // One frame's images at a time (no guard band: the sequence crops its edges), checked before any is allocated.
  requireMemory(context,
                renderMemoryEstimate(options.width, options.height, options.width, options.supersample,
                                     options.stereo.method == stereo::StereoMethod::Hybrid),
                options.memoryLimitBytes);
  const comfort::WorldQueries world(scene);
  renderer::DeferredRenderer deferred(context, options.width, options.height, {options.supersample, options.reversedZ});
  deferred.setScene(scene);
  std::unique_ptr<renderer::DeferredRenderer> eyeRenderer;  // the hybrid method's masked eye renders
  const float aspect = float(options.width) / float(options.height);
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
  glm::vec3 previousPosition(0.0f);

  // The previous frame's eyes, synthesized and reference, and its crop: the flicker metric's other frame.
  struct EyeFrames {
    stereo::StereoPair synthesized, reference;
    std::uint32_t crop = 0;
  };
  std::optional<EyeFrames> previous;
  SequenceReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  for (std::size_t index = 0; index < scene.cameraPath.size(); ++index) {
    SequenceFrame frame;
    frame.index = index;
    scene.camera = renderer::cameraForFrame(scene, index);
    frame.nearestSurface = comfort::nearestSurfaceAhead(world, scene.camera, settings,
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
        comfort::placeCrosshair(world, scene.camera, crosshairDistance, options.crosshair.margin);
    if (placement.hitWorld) frame.aimSurface = placement.surfaceDistance;
    frame.crosshairDepth = crosshair.update(placement, seconds);

    const renderer::ViewMatrices center =
        renderer::centerViewMatrices(scene, aspect, {parameters.weaponDepthOffset, parameters.weaponDepthScale});
    deferred.render(center);
    const DepthImage pushed = deferred.readLinearDepth();
    // ... and no world surface may be nearer than the screen plane either (the control's rays see only a few
    // directions; the depth image sees every pixel).
    if (const std::optional<float> nearest = comfort::nearestDepth(pushed)) {
      frame.nearestDepth = *nearest;
      limitZeroParallax(*nearest);
    }
    parameters.zeroParallaxDistance = frame.zeroParallaxDistance;
    if (budgetOn) {
      // Ray casts from where the camera will be (current velocity) warn of a surface before it is in view.
      BudgetFrameHints hints{frame.crosshairDepth, weaponNearestPushed(parameters, weaponDepths), std::nullopt, false};
      if (index > 0 && options.anticipateSeconds > 0.0f) {
        renderer::Camera ahead = scene.camera;
        ahead.position += (scene.camera.position - previousPosition) * (options.anticipateSeconds * options.framesPerSecond);
        hints.anticipatedNearest = comfort::nearestSurfaceAhead(world, ahead, settings, 8.0f);
      }
      frame.budget = applyDisparityBudget(context, *reduction, &*budgetControl, deferred.linearDepth(), hints, seconds,
                                          parameters);
      frame.zeroParallaxDistance = parameters.zeroParallaxDistance;
    }
    previousPosition = scene.camera.position;
    frame.maxSeparation = parameters.maxSeparation;
    const std::uint32_t crop = std::uint32_t(stereo::makeStereoConstants(parameters, options.width, options.height).cropBegin);
    // The crosshair not in front of the screen plane either (the plane is never beyond the aimed-at surface).
    if (!options.allowNegativeParallax) frame.crosshairDepth = std::max(frame.crosshairDepth, frame.zeroParallaxDistance);
    frame.comfort = comfort::frameComfort(pushed, parameters, options.display);
    const comfort::WeaponConflicts conflicts =
        comfort::countWeaponConflicts(world, scene.camera, center, pushed, deferred.readFirstPersonMask());
    frame.weaponPixels = conflicts.weaponPixels;
    frame.weaponConflictPixels = conflicts.conflictPixels;
    stereo::SynthesisResult eyes;
    if (parameters.method == stereo::StereoMethod::Hybrid) {
      if (!eyeRenderer) {
        eyeRenderer = std::make_unique<renderer::DeferredRenderer>(
            context, options.width, options.height, renderer::RendererOptions{options.supersample, options.reversedZ});
        eyeRenderer->setScene(scene);
      }
      HybridSynthesis hybrid = synthesizeHybrid(context, deferred.displayColor(), deferred.linearDepth(), *eyeRenderer,
                                                scene, center, parameters);
      eyes.eyes = std::move(hybrid.eyes);
      eyes.gpuMs = hybrid.timings.total;
    } else {
      eyes = stereo::synthesizeTimed(context, deferred.displayColor(), deferred.linearDepth(), parameters);
    }

    EyeFrames current{eyes.eyes, {}, crop};
    std::array<DepthImage, 2> referenceDepth;
    deferred.render(referenceEyeView(scene, center, stereo::Eye::Left, parameters));
    current.reference.left = deferred.readDisplayColor();
    referenceDepth[0] = deferred.readLinearDepth();
    frame.psnrLeftDb = stereo::compareDisplayImages(eyes.eyes.left, current.reference.left, crop).psnrDb;
    deferred.render(referenceEyeView(scene, center, stereo::Eye::Right, parameters));
    current.reference.right = deferred.readDisplayColor();
    referenceDepth[1] = deferred.readLinearDepth();
    frame.psnrRightDb = stereo::compareDisplayImages(eyes.eyes.right, current.reference.right, crop).psnrDb;
    if (previous) {
      const std::vector<std::uint8_t> halo = haloMaskFor(pushed, parameters);
      const std::uint32_t bothCrops = std::max(crop, previous->crop);
      frame.flicker = std::array<stereo::FlickerStats, 2>{
          stereo::temporalFlicker(current.synthesized.left, previous->synthesized.left, current.reference.left,
                                  previous->reference.left, bothCrops, halo,
                                  disocclusionMaskFor(referenceDepth[0], pushed, parameters, stereo::Eye::Left)),
          stereo::temporalFlicker(current.synthesized.right, previous->synthesized.right, current.reference.right,
                                  previous->reference.right, bothCrops, halo,
                                  disocclusionMaskFor(referenceDepth[1], pushed, parameters, stereo::Eye::Right))};
    }
    previous = std::move(current);

    if (options.writeFrames) {
      char name[48];
      std::snprintf(name, sizeof(name), "anaglyph_%04zu.png", index);
      io::writePng(options.outputFolder / name, stereo::makeAnaglyphDubois(eyes.eyes.left, eyes.eyes.right));
      report.filesWritten.push_back(name);
    }
    report.frames.push_back(frame);
  }
  report.filesWritten.push_back("report.json");
  io::writeTextFile(options.outputFolder / "report.json", toJson(report).dump(2) + "\n");
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
                      {"disparityBudget", budgetJson(frame.budget, frame.comfort)},
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
    }
  }
  for (stereo::FlickerStats& eye : mean)
    for (stereo::FlickerRegion* region : {&eye.all, &eye.halo, &eye.disocclusion})
      region->meanLevels = count ? region->meanLevels / double(count) : 0.0;
  return mean;
}

}  // namespace s3d::app
