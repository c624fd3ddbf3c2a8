#include "s3d/frame/comforted_stereo_frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "s3d/comfort/disparity_budget.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/frame/scene_world.h"
#include "s3d/renderer/view_matrices.h"
#include "s3d/stereo/disparity_map.h"
#include "s3d/stereo/sanitize.h"

namespace s3d::frame {
namespace {

// The pushed weapon's farthest point stays within this share of the distance to the nearest surface.
constexpr float kWeaponClearance = 0.9f;
// How far the anticipation's rays look from where the camera will be (world units).
constexpr float kAnticipationRange = 8.0f;

// The control's settings as a frame runs them: resting at the parameters' plane, never above it.
std::optional<comfort::ZeroParallaxControlSettings> controlSettings(const ComfortedStereoFrameDescription& description) {
  std::optional<comfort::ZeroParallaxControlSettings> settings = description.comfort.zeroParallaxControl;
  if (!settings) return settings;
  settings->restDistance = description.stereo.zeroParallaxDistance;
  settings->minimumDistance = std::min(settings->minimumDistance, settings->restDistance);
  return settings;
}

}  // namespace

// The state the rules carry from frame to frame, and the passes they run.
struct ComfortedStereoFrame::Controls {
  Controls(vk::Context& context, const ComfortedStereoFrameDescription& description)
      : settings(controlSettings(description)), mapper(context) {
    makeBudget(context, description);
  }
  // The budget's controller from rest (none with the rule off).
  void makeBudget(vk::Context& context, const ComfortedStereoFrameDescription& description) {
    budget.reset();
    if (description.comfort.budget == comfort::DisparityBudgetRule::Off) return;
    budget.emplace(comfort::disparityBudget(description.comfort.display), description.comfort.allowNegativeParallax);
    if (!reduction) reduction.emplace(context);
  }
  // From rest: the zero-parallax control, the crosshair smoother and the camera's last position.
  void restart(const ComfortedStereoFrameDescription& description) {
    zeroParallax.reset();
    if (settings) zeroParallax.emplace(*settings);  // validates the settings
    crosshair.reset();
    if (description.comfort.smoothCrosshair) crosshair.emplace(description.comfort.crosshair.responseSeconds);
    previousPosition.reset();
  }

  std::optional<comfort::ZeroParallaxControlSettings> settings;
  std::optional<comfort::ZeroParallaxController> zeroParallax;
  std::optional<comfort::CrosshairSmoother> crosshair;
  std::optional<comfort::DisparityBudgetController> budget;
  std::optional<stereo::DepthRangePass> reduction;
  comfort::FrameDisparityMapper mapper;
  std::optional<glm::vec3> previousPosition;
};

HudFrameInput ComfortedFrame::hudInput() const {
  return {parameters, crosshairDepth, weaponDepths, allowNegativeParallax, &depth, &firstPersonMask, drawHud,
          disparityMap.map};
}

ComfortedStereoFrame::ComfortedStereoFrame(vk::Context& context, const ComfortedStereoFrameDescription& description)
    : context_(context), description_(description) {
  if (description.width == 0 || description.height == 0 || description.width > description.maxRenderedWidth)
    throw std::invalid_argument("the frame's size must be at least 1x1 and its width at most the largest rendered width (" +
                                std::to_string(description.maxRenderedWidth) + ")");
  comfort::validate(description.comfort.display);
  controls_ = std::make_unique<Controls>(context, description);
  controls_->restart(description_);
}

ComfortedStereoFrame::~ComfortedStereoFrame() = default;

void ComfortedStereoFrame::setScene(const renderer::Scene& scene) {
  world_ = std::make_unique<comfort::WorldQueries>(worldMeshes(scene));
  worldScene_ = &scene;
  if (deferred_) deferred_->setScene(scene);
  if (synthesis_) synthesis_->setScene(scene);
}

void ComfortedStereoFrame::setRules(const stereo::StereoParameters& stereo, const FrameComfortSettings& comfort,
                                    bool hud) {
  const FrameComfortSettings old = description_.comfort;
  const bool fillChanged = stereo.previousFrameFill != description_.stereo.previousFrameFill;
  description_.stereo = stereo;
  description_.comfort = comfort;
  description_.hud = hud;
  if (fillChanged) synthesis_.reset();
  Controls& controls = *controls_;
  const std::optional<comfort::ZeroParallaxControlSettings> settings = controlSettings(description_);
  if (settings.has_value() != controls.settings.has_value() ||
      (settings && std::memcmp(&*settings, &*controls.settings, sizeof(*settings)) != 0)) {  // plain numbers
    controls.settings = settings;
    controls.zeroParallax.reset();
    if (settings) controls.zeroParallax.emplace(*settings);
  }
  if (comfort.smoothCrosshair != old.smoothCrosshair || comfort.crosshair.responseSeconds != old.crosshair.responseSeconds) {
    controls.crosshair.reset();
    if (comfort.smoothCrosshair) controls.crosshair.emplace(comfort.crosshair.responseSeconds);
  }
  if (comfort.budget != old.budget || comfort.allowNegativeParallax != old.allowNegativeParallax ||
      comfort::toJson(comfort.display) != comfort::toJson(old.display))
    controls.makeBudget(context_, description_);
}

void ComfortedStereoFrame::updateGeometry(const renderer::Scene& scene) {
  world_ = std::make_unique<comfort::WorldQueries>(worldMeshes(scene));
  worldScene_ = &scene;
  if (deferred_) deferred_->updateGeometry(scene);  // the textures stay uploaded
  if (synthesis_) synthesis_->updateGeometry(scene);
}

ComfortedFrame ComfortedStereoFrame::render(const renderer::Scene& scene, float seconds, bool cut) {
  if (!world_ || worldScene_ != &scene) setScene(scene);
  if (cut) controls_->restart(description_);
  ComfortedFrame frame;
  frame.width = description_.width;
  stereo::StereoParameters parameters = parametersBeforeCenter(scene, seconds, frame);
  (void)useBand(bandFor(parameters, scene), scene);
  renderCenter(scene, parameters, frame);
  holdAtNearestDepth(parameters, frame);
  applyBudget(scene, seconds, cut, parameters, frame);
  controls_->previousPosition = scene.camera.position;
  finishFrame(scene, parameters, frame);
  synthesizeEyes(scene, frame);
  frame.eyesWithHud = frame.eyes;
  frame.hud = drawHud(frame.hudInput(), frame.eyesWithHud);
  return frame;
}

// The zero-parallax control and the weapon push (which shrinks with the plane, and at once whenever its farthest
// pushed point would reach the nearest surface), then the crosshair's placement.
stereo::StereoParameters ComfortedStereoFrame::parametersBeforeCenter(const renderer::Scene& scene, float seconds,
                                                                      ComfortedFrame& frame) {
  const bool allowNegativeParallax = description_.comfort.allowNegativeParallax;
  frame.allowNegativeParallax = allowNegativeParallax;
  frame.drawHud = description_.hud;
  frame.weaponDepths = renderer::firstPersonDepthRange(scene);
  const glm::vec2 weapon = frame.weaponDepths.value_or(glm::vec2(0.0f));
  stereo::StereoParameters parameters = description_.stereo;
  if (comfort::ZeroParallaxController* control = controls_->zeroParallax ? &*controls_->zeroParallax : nullptr) {
    const comfort::ZeroParallaxControlSettings& settings = *controls_->settings;
    frame.nearestSurface = comfort::nearestSurfaceAhead(*world_, scene.camera, settings,
                                                        settings.engageDistance + settings.releaseMargin + 1.0f);
    parameters.zeroParallaxDistance = control->update(frame.nearestSurface, seconds);
    float ratio = parameters.zeroParallaxDistance / settings.restDistance;
    const float farthestPushed = parameters.weaponDepthOffset + parameters.weaponDepthScale * weapon.y;
    if (frame.nearestSurface && farthestPushed > 0.0f)
      ratio = std::min(ratio, kWeaponClearance * *frame.nearestSurface / farthestPushed);
    parameters.weaponDepthOffset *= ratio;
    parameters.weaponDepthScale *= ratio;
    // The push is squeezed between the plane and its (wall-capped) farthest point; only when the wall leaves no
    // room behind the plane does the plane give way, at once.
    const float pushedFarthest = parameters.weaponDepthOffset + parameters.weaponDepthScale * weapon.y;
    const float pushedNearest = parameters.weaponDepthOffset + parameters.weaponDepthScale * weapon.x;
    if (!allowNegativeParallax && frame.weaponDepths && pushedFarthest < parameters.zeroParallaxDistance &&
        pushedNearest < parameters.zeroParallaxDistance) {
      parameters.zeroParallaxDistance = control->limit(pushedNearest);
      frame.zeroParallaxLimited = true;
    }
  }
  // A plane outside the camera's depth range is clamped, with a warning.
  const stereo::ClampedZeroParallax clamped = stereo::clampZeroParallaxDistance(
      parameters.zeroParallaxDistance, scene.camera.nearPlane, scene.camera.farPlane);
  parameters.zeroParallaxDistance = clamped.zeroParallaxDistance;
  frame.zeroParallaxWarning = clamped.warning;
  parameters = comfort::pushWeaponUnlessNegativeParallaxAllowed(parameters, frame.weaponDepths, allowNegativeParallax);
  const comfort::CrosshairSettings& crosshair = description_.comfort.crosshair;
  frame.crosshair = comfort::placeCrosshair(*world_, scene.camera, crosshair.distance.value_or(scene.crosshairDistance),
                                            crosshair.margin);
  frame.crosshairDepth =
      controls_->crosshair ? controls_->crosshair->update(frame.crosshair, seconds) : frame.crosshair.depth;
  return parameters;
}

// The nearest depth the eyes can show is the plane (held there) unless negative parallax is allowed: then the
// near plane or the pushed weapon's nearest.
stereo::GuardBand ComfortedStereoFrame::bandFor(const stereo::StereoParameters& p, const renderer::Scene& scene) const {
  if (!description_.guardBand) return {};
  float nearest = p.zeroParallaxDistance;
  if (description_.comfort.allowNegativeParallax) {
    nearest = scene.camera.nearPlane;
    if (const std::optional<glm::vec2> weapon = renderer::firstPersonDepthRange(scene); weapon && weapon->x > 0.0f)
      nearest = std::min(nearest, p.weaponDepthOffset + p.weaponDepthScale * weapon->x);
  }
  return stereo::guardBandFor(p.maxSeparation, p.zeroParallaxDistance, nearest, description_.width,
                              description_.maxRenderedWidth);
}

// The renderers are replaced only when a frame needs a wider band than they have.
bool ComfortedStereoFrame::useBand(const stereo::GuardBand& wanted, const renderer::Scene& scene) {
  if (deferred_ && wanted.columns <= band_.columns) return false;
  band_ = wanted;
  const std::uint32_t renderedWidth = band_.renderedWidth(description_.width);
  deferred_ = std::make_unique<renderer::DeferredRenderer>(context_, renderedWidth, description_.height,
                                                           description_.renderer);
  deferred_->setScene(scene);
  freshRenderer_ = true;
  synthesis_.reset();
  return true;
}

void ComfortedStereoFrame::renderCenter(const renderer::Scene& scene, const stereo::StereoParameters& parameters,
                                        ComfortedFrame& frame) {
  frame.band = band_;
  frame.renderedWidth = band_.renderedWidth(description_.width);
  frame.center = renderer::centerViewMatrices(scene, float(frame.renderedWidth) / float(description_.height),
                                              {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  // A new renderer's first frame includes shader compilation (lavapipe compiles at first use).
  if (description_.warmUp && std::exchange(freshRenderer_, false)) (void)deferred_->render(frame.center);
  frame.centerTimings = deferred_->render(frame.center);
  frame.renderedDepth = deferred_->readLinearDepth();
  if (description_.keepHdr) frame.renderedHdr = deferred_->readHdrColor();
  if (!description_.sanitizeDepth) return;
  frame.sanitizedDepthPixels = stereo::sanitizeDepth(frame.renderedDepth, parameters.zeroParallaxDistance);
  if (description_.keepHdr) frame.sanitizedColorValues = stereo::sanitizeColor(frame.renderedHdr);
}

// No world surface nearer than the screen plane either, the band's content included (it reaches the eyes).
void ComfortedStereoFrame::holdAtNearestDepth(stereo::StereoParameters& parameters, ComfortedFrame& frame) {
  frame.nearestDepth = comfort::nearestDepth(frame.renderedDepth);
  if (description_.comfort.allowNegativeParallax || !frame.nearestDepth ||
      !(*frame.nearestDepth < parameters.zeroParallaxDistance))
    return;
  parameters.zeroParallaxDistance =
      controls_->zeroParallax ? controls_->zeroParallax->limit(*frame.nearestDepth) : *frame.nearestDepth;
  frame.zeroParallaxLimited = true;
}

// The frame's depth range, reduced on the GPU, picks maxSeparation and the plane; a wider separation than the band
// allows renders the center view again at the wider band.
void ComfortedStereoFrame::applyBudget(const renderer::Scene& scene, float seconds, bool cut,
                                       stereo::StereoParameters& parameters, ComfortedFrame& frame) {
  if (!controls_->budget) return;
  const FrameComfortSettings& comfort = description_.comfort;
  comfort::BudgetFrameHints hints{comfort.crosshairHintsBudget ? std::optional(frame.crosshairDepth) : std::nullopt,
                                  comfort::weaponNearestPushed(parameters, frame.weaponDepths), std::nullopt, cut, false};
  if (controls_->previousPosition && comfort.anticipateFrames > 0.0f) {
    // Ray casts from where the camera will be (its current velocity) warn of a surface before it is in view;
    // receding: they reach farther from there than from here (a trend the controller follows without its hold).
    const comfort::ZeroParallaxControlSettings settings = controls_->settings.value_or(comfort::ZeroParallaxControlSettings{});
    renderer::Camera ahead = scene.camera;
    ahead.position += (scene.camera.position - *controls_->previousPosition) * comfort.anticipateFrames;
    hints.anticipatedNearest = comfort::nearestSurfaceAhead(*world_, ahead, settings, kAnticipationRange);
    const float here = comfort::nearestSurfaceAhead(*world_, scene.camera, settings, kAnticipationRange).value_or(INFINITY);
    hints.receding = hints.anticipatedNearest.value_or(INFINITY) > here;
  }
  frame.budget = comfort::applyDisparityBudget(context_, *controls_->reduction, &*controls_->budget,
                                               deferred_->linearDepth(), hints, seconds, parameters);
  frame.budget.imageWidth = description_.width;  // budgetPx and bulkShare in the output eyes' pixels
  const stereo::GuardBand chosen = bandFor(parameters, scene);
  if (chosen.columns <= band_.columns) return;
  if (description_.beforeWiderBand) description_.beforeWiderBand(parameters, chosen.renderedWidth(description_.width));
  (void)useBand(chosen, scene);
  renderCenter(scene, parameters, frame);
}

// The output's parameters, the depth-to-parallax map (applied to the GPU depth the pass reads and to the C++
// copy alike), the comfort report and the weapon's conflicts with the world.
void ComfortedStereoFrame::finishFrame(const renderer::Scene& scene, stereo::StereoParameters parameters,
                                       ComfortedFrame& frame) {
  const std::uint32_t width = description_.width, height = description_.height;
  if (!description_.comfort.allowNegativeParallax)  // the crosshair not in front of the screen plane either
    frame.crosshairDepth = std::max(frame.crosshairDepth, parameters.zeroParallaxDistance);
  if (description_.guardBand) parameters.edgeCrop = 0.0f;  // the output eyes are full frame
  frame.cropColumns =
      description_.guardBand ? 0u : std::uint32_t(stereo::makeStereoConstants(parameters, width, height).cropBegin);
  frame.parameters = parameters;
  frame.renderedParameters =
      description_.guardBand ? stereo::guardBandParameters(parameters, width, band_) : parameters;
  frame.disparityMap = controls_->mapper.apply(context_, deferred_->linearDepth(), parameters);
  frame.renderedStereoDepth = stereo::mappedDepthImage(frame.renderedDepth, frame.disparityMap.map);
  frame.depth = frame.toOutput(frame.renderedDepth);
  frame.stereoDepth = frame.toOutput(frame.renderedStereoDepth);
  frame.comfort = comfort::frameComfort(frame.stereoDepth, parameters, description_.comfort.display);
  frame.outputCenter = renderer::centerViewMatrices(scene, float(width) / float(height),
                                                    {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  frame.firstPersonMask = frame.maskToOutput(deferred_->readFirstPersonMask());
  frame.weaponConflicts = comfort::countWeaponConflicts(*world_, scene.camera, frame.outputCenter.worldProjection,
                                                        frame.depth, frame.firstPersonMask);
}

void ComfortedStereoFrame::synthesizeEyes(const renderer::Scene& scene, ComfortedFrame& frame) {
  if (!synthesis_) {
    synthesis_ = std::make_unique<StereoSynthesis>(
        context_, StereoSynthesisDescription{.width = frame.renderedWidth, .height = description_.height,
                                             .renderer = description_.renderer,
                                             .previousFrameFill = description_.stereo.previousFrameFill});
  }
  frame.synthesized = synthesis_->synthesize({*deferred_, scene, frame.center, frame.renderedParameters});
  frame.eyes = {frame.toOutput(frame.synthesized.eyes.left), frame.toOutput(frame.synthesized.eyes.right)};
}

}  // namespace s3d::frame
