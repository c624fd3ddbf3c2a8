#include "s3d/tune/tune_session.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "s3d/app/frame_rules.h"
#include "s3d/app/render_job.h"
#include "s3d/frame/scene_world.h"
#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/comfort_views.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/frame/stereo_synthesis.h"
#include "s3d/stereo/sanitize.h"

namespace s3d::tune {
namespace {

// As the sequence job: the pushed weapon's farthest point stays within this share of the nearest surface.
constexpr float kWeaponClearance = 0.9f;

bool sameControl(const comfort::ZeroParallaxControlSettings& a, const comfort::ZeroParallaxControlSettings& b) {
  return std::memcmp(&a, &b, sizeof(a)) == 0;  // plain floats and ints: a change of any slider restarts the control
}

}  // namespace

struct TuneSession::Loaded {
  std::string sceneName;
  renderer::Scene scene;
  std::unique_ptr<comfort::WorldQueries> world;
  std::unique_ptr<renderer::DeferredRenderer> deferred;
  std::unique_ptr<frame::StereoSynthesis> synthesis;  // the eyes (with the hybrid's eye renderer, made at first use)
  std::uint32_t supersample = 0;  // of `deferred`
  comfort::ZeroParallaxControlSettings controlSettings;
  std::unique_ptr<comfort::ZeroParallaxController> control;
  std::unique_ptr<stereo::DepthRangePass> reduction;
  std::unique_ptr<comfort::DisparityBudgetController> budget;
  nlohmann::json budgetKey;  // the display and rule the controller was made for
  std::unique_ptr<comfort::FrameDisparityMapper> mapper;
};

TuneSession::TuneSession(vk::Context& context, std::uint32_t width, std::uint32_t height)
    : context_(context), width_(width), height_(height) {
  if (width == 0 || height == 0 || width > app::kMaxImageSize || height > app::kMaxImageSize)
    throw std::invalid_argument("tune: view size outside 1.." + std::to_string(app::kMaxImageSize));
}

TuneSession::~TuneSession() = default;

void TuneSession::loadScene(TuneState& state) {
  auto loaded = std::make_unique<Loaded>();
  loaded->sceneName = state.scene;
  loaded->scene = renderer::makeBuiltInScene(state.scene);
  loaded->world = std::make_unique<comfort::WorldQueries>(frame::worldMeshes(loaded->scene));
  if (loaded_ && loaded_->deferred && loaded_->supersample == state.supersample) {
    loaded->deferred = std::move(loaded_->deferred);
    loaded->supersample = loaded_->supersample;
  } else {
    loaded->deferred = std::make_unique<renderer::DeferredRenderer>(context_, width_, height_,
                                                                    renderer::RendererOptions{state.supersample});
    loaded->supersample = state.supersample;
  }
  loaded->deferred->setScene(loaded->scene);
  loaded_ = std::move(loaded);
  state.pathFrame = std::min(state.pathFrame, pathLength() - 1);
  setPathFrame(state, state.pathFrame);
}

std::size_t TuneSession::pathLength() const {
  return loaded_ ? std::max<std::size_t>(loaded_->scene.cameraPath.size(), 1) : 0;
}

float TuneSession::sceneCrosshairDistance() const {
  return loaded_ ? loaded_->scene.crosshairDistance : renderer::Scene{}.crosshairDistance;
}

void TuneSession::setPathFrame(TuneState& state, std::size_t frame) {
  if (!loaded_ || loaded_->sceneName != state.scene) loadScene(state);
  state.camera = renderer::cameraForFrame(loaded_->scene, frame);
  state.pathFrame = frame;
  loaded_->control.reset();  // the control starts again from rest at a jump
}

TuneFrame TuneSession::renderFrame(TuneState& state, const FrameInput& input, float seconds) {
  validate(state.settings);
  if (!loaded_ || loaded_->sceneName != state.scene) loadScene(state);
  Loaded& loaded = *loaded_;
  if (loaded.supersample != state.supersample) {  // a new renderer (its images are sized by the factor)
    auto deferred = std::make_unique<renderer::DeferredRenderer>(context_, width_, height_,
                                                                 renderer::RendererOptions{state.supersample});
    deferred->setScene(loaded.scene);
    loaded.deferred = std::move(deferred);
    loaded.synthesis.reset();
    loaded.supersample = state.supersample;
  }
  if (state.playPath) state.camera = renderer::cameraForFrame(loaded.scene, state.pathFrame);
  else moveCamera(state.camera, input, seconds);
  renderer::Scene& scene = loaded.scene;
  scene.camera = state.camera;

  TuneFrame frame;
  FrameNumbers& numbers = frame.numbers;
  const comfort::ComfortProfile& profile = state.settings.profile;
  stereo::StereoParameters parameters = profile.stereo;

  // Zero-parallax control and weapon push, as `s3d render --sequence` runs them (sequence_job.cpp).
  if (state.settings.zeroParallaxControl) {
    const comfort::ZeroParallaxControlSettings settings = profile.zeroParallaxSettings();
    if (!loaded.control || !sameControl(settings, loaded.controlSettings)) {
      loaded.control = std::make_unique<comfort::ZeroParallaxController>(settings);
      loaded.controlSettings = settings;
    }
    numbers.nearestSurface = comfort::nearestSurfaceAhead(*loaded.world, scene.camera, settings,
                                                          settings.engageDistance + settings.releaseMargin + 1.0f);
    parameters.zeroParallaxDistance = loaded.control->update(numbers.nearestSurface, seconds);
    float ratio = parameters.zeroParallaxDistance / settings.restDistance;
    const glm::vec2 weaponDepths = renderer::firstPersonDepthRange(scene).value_or(glm::vec2(0.0f));
    const float farthestPushed = parameters.weaponDepthOffset + parameters.weaponDepthScale * weaponDepths.y;
    if (numbers.nearestSurface && farthestPushed > 0.0f)
      ratio = std::min(ratio, kWeaponClearance * *numbers.nearestSurface / farthestPushed);
    parameters.weaponDepthOffset *= ratio;
    parameters.weaponDepthScale *= ratio;
  } else {
    loaded.control.reset();
  }
  // As `s3d render`: a zero-parallax plane outside the camera's depth range is clamped, with a warning.
  const stereo::ClampedZeroParallax clamped = stereo::clampZeroParallaxDistance(
      parameters.zeroParallaxDistance, scene.camera.nearPlane, scene.camera.farPlane);
  parameters.zeroParallaxDistance = clamped.zeroParallaxDistance;
  numbers.warning = clamped.warning;
  // The no-negative-parallax rules as runRenderJob applies them (s3d/comfort/budget_frame.h): the weapon pushed
  // to the screen plane before the center view, the plane held at the frame's nearest depth after it.
  const bool allowNegativeParallax = profile.allowNegativeParallax;
  const std::optional<glm::vec2> weaponDepths = renderer::firstPersonDepthRange(scene);
  parameters = comfort::pushWeaponUnlessNegativeParallaxAllowed(parameters, weaponDepths, allowNegativeParallax);

  // The center view and both synthesized eyes (as runRenderJob).
  renderer::DeferredRenderer& deferred = *loaded.deferred;
  const renderer::ViewMatrices center = renderer::centerViewMatrices(
      scene, float(width_) / float(height_), {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  renderer::FrameTimings timings = deferred.render(center);
  numbers.centerFrameGpuMs = timings.totalGpuMs;
  numbers.centerPasses = std::move(timings.passes);
  FrameImages images;
  images.stereoDepth = deferred.readLinearDepth();
  // Invalid depth reads as the zero-parallax plane, as in the stereo pass, for the views and comfort numbers.
  numbers.sanitizedDepthPixels = stereo::sanitizeDepth(images.stereoDepth, parameters.zeroParallaxDistance);
  const std::vector<std::uint8_t> firstPersonMask = deferred.readFirstPersonMask();  // weapon and HUD conflicts
  numbers.zeroParallaxLimited = comfort::holdZeroParallaxAtNearestDepth(parameters, images.stereoDepth, allowNegativeParallax);
  if (numbers.zeroParallaxLimited && loaded.control)  // the control goes on smoothly from the limit
    parameters.zeroParallaxDistance = loaded.control->limit(parameters.zeroParallaxDistance);
  if (state.disparityBudget != comfort::DisparityBudgetRule::Off) {
    // The disparity budget, as `s3d render` runs it; a new controller when the display or the rule changes.
    const nlohmann::json key{comfort::toJson(profile.display), allowNegativeParallax};
    if (!loaded.budget || loaded.budgetKey != key) {
      loaded.budget = std::make_unique<comfort::DisparityBudgetController>(comfort::disparityBudget(profile.display),
                                                                           allowNegativeParallax);
      loaded.budgetKey = key;
    }
    if (!loaded.reduction) loaded.reduction = std::make_unique<stereo::DepthRangePass>(context_);
    numbers.budget = comfort::applyDisparityBudget(context_, *loaded.reduction, loaded.budget.get(), deferred.linearDepth(),
                                               {std::nullopt, comfort::weaponNearestPushed(parameters, weaponDepths)},
                                               seconds, parameters);
  } else {
    loaded.budget.reset();
  }
  // The depth-to-parallax mapping, as `s3d render` applies it: the views and comfort numbers read the mapped depth,
  // the weapon and HUD conflicts the scene's.
  if (!loaded.mapper) loaded.mapper = std::make_unique<comfort::FrameDisparityMapper>(context_);
  numbers.disparityMap = loaded.mapper->apply(context_, deferred.linearDepth(), parameters);
  const gpu::DisparityMapConstants& map = numbers.disparityMap.map;
  const DepthImage sceneDepth = images.stereoDepth;
  stereo::mapDepthReference(images.stereoDepth, map);
  numbers.maxSeparation = parameters.maxSeparation;
  numbers.zeroParallaxDistance = parameters.zeroParallaxDistance;
  numbers.weaponDepthOffset = parameters.weaponDepthOffset;
  numbers.weaponDepthScale = parameters.weaponDepthScale;
  if (!loaded.synthesis)
    loaded.synthesis = std::make_unique<frame::StereoSynthesis>(
        context_, frame::StereoSynthesisDescription{.width = width_, .height = height_,
                                                    .renderer = {loaded.supersample}});
  frame::SynthesizedEyes eyes = loaded.synthesis->synthesize({deferred, scene, center, parameters});
  numbers.stereoPassGpuMs = eyes.gpuMs;
  images.eyes = std::move(eyes.eyes);
  images.parameters = parameters;
  images.cropColumns = std::uint32_t(stereo::makeStereoConstants(parameters, width_, height_).cropBegin);

  // The two-pass reference, when asked for or shown.
  if (state.reference || viewNeedsReference(state.view)) {
    stereo::StereoPair reference;
    double referenceMs = 0.0;
    bool timed = true;
    for (auto [eye, image] : {std::pair{stereo::Eye::Left, &reference.left}, std::pair{stereo::Eye::Right, &reference.right}}) {
      frame::ReferenceEye rendered = frame::renderReferenceEye(deferred, scene, center, eye, parameters, map);
      if (rendered.firstLayerGpuMs) referenceMs += *rendered.firstLayerGpuMs;
      else timed = false;
      *image = std::move(rendered.display);
      numbers.disparityMap.referenceLayers = rendered.layers;
      numbers.disparityMap.unresolvedPixels[eye == stereo::Eye::Left ? 0 : 1] = rendered.unresolvedPixels;
    }
    if (timed) numbers.referenceEyesGpuMs = referenceMs;
    if (images.cropColumns * 2 < width_) {
      numbers.errorLeft = stereo::compareDisplayImages(images.eyes.left, reference.left, images.cropColumns);
      numbers.errorRight = stereo::compareDisplayImages(images.eyes.right, reference.right, images.cropColumns);
    }
    images.reference = std::move(reference);
  }

  // Comfort numbers on the chosen display (the comfort report of `s3d render`, comfort_report.h).
  images.display = profile.display;
  numbers.comfort = comfort::frameComfort(images.stereoDepth, parameters, images.display);
  const std::vector<std::uint8_t> beyond = comfort::comfortViolationMask(images.stereoDepth, parameters, images.display);
  numbers.shareBeyondComfort = double(std::count(beyond.begin(), beyond.end(), std::uint8_t(1))) / double(beyond.size());
  numbers.weaponConflictPixels = comfort::countWeaponConflicts(*loaded.world, scene.camera, center.worldProjection,
                                                               sceneDepth, firstPersonMask).conflictPixels;

  // HUD: the crosshair, placed by an Embree ray cast along the aim (seed 4.6.2), and the panels, drawn into
  // each eye at its depth's parallax with the weapon-mask fade, by the same code as `s3d render` (drawHud).
  const comfort::CrosshairPlacement placement =
      comfort::placeCrosshair(*loaded.world, scene.camera, profile.crosshair.distance.value_or(scene.crosshairDistance),
                              profile.crosshair.margin);
  images.eyesWithHud = images.eyes;
  if (images.reference) images.referenceWithHud = images.reference;
  const frame::HudFrameInput hudInput{parameters, placement.depth, weaponDepths, allowNegativeParallax, &sceneDepth,
                                      &firstPersonMask, app::resolveHudMode(state.hud, state.scene) == app::HudMode::Game,
                                      map};
  const frame::HudFrame overlay = frame::drawHud(hudInput, *images.eyesWithHud);
  if (images.referenceWithHud) frame::drawHudOver(hudInput, nullptr, &*images.referenceWithHud);
  numbers.crosshairDepth = overlay.crosshairDepth;
  numbers.crosshairHitWorld = placement.hitWorld;
  numbers.hudConflictPixels = overlay.conflictPixels;

  frame.view = composeView(state.view, images);
  if (state.playPath) {
    state.pathFrame = (state.pathFrame + 1) % pathLength();
    if (state.pathFrame == 0) loaded.control.reset();  // the path starts over
  }
  return frame;
}

void runScriptCommand(TuneSession& session, TuneState& state, const ScriptCommand& command, WindowRequests& requests) {
  const std::vector<std::string>& a = command.arguments;
  try {
    if (command.verb == "set") setParameter(state.settings, a[0], a[1]);
    else if (command.verb == "view") state.view = parseViewMode(a[0]);
    else if (command.verb == "scene") {
      state.scene = a[0];
      state.pathFrame = 0;
      session.loadScene(state);
    } else if (command.verb == "frame") session.setPathFrame(state, std::stoul(a[0]));
    else if (command.verb == "play") state.playPath = a[0] == "on";
    else if (command.verb == "reference") state.reference = a[0] == "on";
    else if (command.verb == "supersample") state.supersample = std::uint32_t(std::stoul(a[0]));
    else if (command.verb == "save-profile") saveProfile(a[0], state.settings);
    else if (command.verb == "load-profile") state.settings = loadProfile(a[0], state.settings);
    else if (command.verb == "screenshot") requests.screenshot = a[0];
    else if (command.verb == "quit") requests.quit = true;
    else throw std::invalid_argument("'" + command.verb + "' is not a command that runs on its own");
  } catch (const std::exception& error) {
    throw std::invalid_argument("script line " + std::to_string(command.line) + " (" + command.verb + "): " + error.what());
  }
}

}  // namespace s3d::tune
