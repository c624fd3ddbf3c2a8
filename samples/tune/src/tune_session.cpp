#include "s3d/tune/tune_session.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "s3d/app/frame_rules.h"
#include "s3d/app/render_job.h"
#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/comfort_views.h"
#include "s3d/frame/comforted_stereo_frame.h"
#include "s3d/frame/layered_reference.h"

namespace s3d::tune {
namespace {

// The comfort rules of the state's profile, as `s3d render` and `--sequence` run them; the crosshair is placed
// (unsmoothed) but not a hint to the budget.
frame::FrameComfortSettings comfortRules(const TuneState& state) {
  const comfort::ComfortProfile& profile = state.settings.profile;
  frame::FrameComfortSettings rules{.display = profile.display, .budget = state.disparityBudget,
                                    .allowNegativeParallax = profile.allowNegativeParallax,
                                    .crosshair = profile.crosshair, .crosshairHintsBudget = false};
  if (state.settings.zeroParallaxControl) rules.zeroParallaxControl = profile.zeroParallaxSettings();
  return rules;
}

bool drawsHud(const TuneState& state) { return app::resolveHudMode(state.hud, state.scene) == app::HudMode::Game; }

// The numbers the panel shows, from what the frame applied and measured.
FrameNumbers frameNumbers(const frame::ComfortedFrame& applied, const comfort::DisplayProfile& display) {
  FrameNumbers numbers;
  numbers.centerFrameGpuMs = applied.centerTimings.totalGpuMs;
  numbers.centerPasses = applied.centerTimings.passes;
  numbers.stereoPassGpuMs = applied.synthesized.gpuMs;
  numbers.comfort = applied.comfort;
  const std::vector<std::uint8_t> beyond = comfort::comfortViolationMask(applied.stereoDepth, applied.parameters, display);
  numbers.shareBeyondComfort = double(std::count(beyond.begin(), beyond.end(), std::uint8_t(1))) / double(beyond.size());
  numbers.weaponConflictPixels = applied.weaponConflicts.conflictPixels;
  numbers.hudConflictPixels = applied.hud.conflictPixels;
  numbers.zeroParallaxDistance = applied.parameters.zeroParallaxDistance;
  numbers.zeroParallaxLimited = applied.zeroParallaxLimited;
  numbers.nearestSurface = applied.nearestSurface;
  numbers.weaponDepthOffset = applied.parameters.weaponDepthOffset;
  numbers.weaponDepthScale = applied.parameters.weaponDepthScale;
  numbers.crosshairDepth = applied.hud.crosshairDepth;
  numbers.crosshairHitWorld = applied.crosshair.hitWorld;
  numbers.sanitizedDepthPixels = applied.sanitizedDepthPixels;
  numbers.warning = applied.zeroParallaxWarning;
  numbers.budget = applied.budget;
  numbers.disparityMap = applied.disparityMap;
  numbers.maxSeparation = applied.parameters.maxSeparation;
  return numbers;
}

// The two-pass reference eyes, their time and error, and the same with the frame's HUD drawn over them.
void addReference(frame::ComfortedStereoFrame& stereoFrame, const frame::ComfortedFrame& applied,
                  const renderer::Scene& scene, FrameImages& images, FrameNumbers& numbers) {
  stereo::StereoPair reference;
  double referenceMs = 0.0;
  bool timed = true;
  for (auto [eye, image] : {std::pair{stereo::Eye::Left, &reference.left}, std::pair{stereo::Eye::Right, &reference.right}}) {
    frame::ReferenceEye rendered = frame::renderReferenceEye(stereoFrame.centerRenderer(), scene, applied.center, eye,
                                                             applied.renderedParameters, applied.disparityMap.map);
    if (rendered.firstLayerGpuMs) referenceMs += *rendered.firstLayerGpuMs;
    else timed = false;
    *image = std::move(rendered.display);
    numbers.disparityMap.referenceLayers = rendered.layers;
    numbers.disparityMap.unresolvedPixels[eye == stereo::Eye::Left ? 0 : 1] = rendered.unresolvedPixels;
  }
  if (timed) numbers.referenceEyesGpuMs = referenceMs;
  if (images.cropColumns * 2 < applied.width) {
    numbers.errorLeft = stereo::compareDisplayImages(images.eyes.left, reference.left, images.cropColumns);
    numbers.errorRight = stereo::compareDisplayImages(images.eyes.right, reference.right, images.cropColumns);
  }
  images.referenceWithHud = reference;
  frame::drawHudOver(applied.hudInput(), nullptr, &*images.referenceWithHud);
  images.reference = std::move(reference);
}

}  // namespace

struct TuneSession::Loaded {
  std::string sceneName;
  renderer::Scene scene;
  // The frame's comfort rules and eyes (s3d/frame/comforted_stereo_frame.h), made for `supersample`.
  std::unique_ptr<frame::ComfortedStereoFrame> stereoFrame;
  std::uint32_t supersample = 0;
  bool cut = true;  // the next frame starts the controls from rest (a jump on the path)
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
  if (loaded_ && loaded_->stereoFrame) {  // its renderer (and compiled pipelines) takes the new scene
    loaded->stereoFrame = std::move(loaded_->stereoFrame);
    loaded->supersample = loaded_->supersample;
    loaded->stereoFrame->setScene(loaded->scene);
  }
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
  loaded_->cut = true;  // the control starts again from rest at a jump
}

TuneFrame TuneSession::renderFrame(TuneState& state, const FrameInput& input, float seconds) {
  validate(state.settings);
  if (!loaded_ || loaded_->sceneName != state.scene) loadScene(state);
  Loaded& loaded = *loaded_;
  const comfort::ComfortProfile& profile = state.settings.profile;
  if (!loaded.stereoFrame || loaded.supersample != state.supersample) {  // its images are sized by the factor
    loaded.stereoFrame = std::make_unique<frame::ComfortedStereoFrame>(
        context_, frame::ComfortedStereoFrameDescription{.width = width_, .height = height_,
                                                         .renderer = {state.supersample}, .stereo = profile.stereo,
                                                         .comfort = comfortRules(state), .guardBand = false,
                                                         .maxRenderedWidth = app::kMaxImageSize, .hud = drawsHud(state)});
    loaded.stereoFrame->setScene(loaded.scene);
    loaded.supersample = state.supersample;
  }
  loaded.stereoFrame->setRules(profile.stereo, comfortRules(state), drawsHud(state));
  if (state.playPath) state.camera = renderer::cameraForFrame(loaded.scene, state.pathFrame);
  else moveCamera(state.camera, input, seconds);
  loaded.scene.camera = state.camera;

  // The center view, the comfort rules, the eyes and the HUD, as `s3d render` and `--sequence` run them.
  const frame::ComfortedFrame applied = loaded.stereoFrame->render(loaded.scene, seconds, std::exchange(loaded.cut, false));
  TuneFrame frame;
  frame.numbers = frameNumbers(applied, profile.display);
  FrameImages images{applied.eyes, std::nullopt, applied.eyesWithHud, std::nullopt, applied.stereoDepth,
                     applied.parameters, applied.cropColumns, profile.display};
  if (state.reference || viewNeedsReference(state.view))
    addReference(*loaded.stereoFrame, applied, loaded.scene, images, frame.numbers);
  frame.view = composeView(state.view, images);
  if (state.playPath) {
    state.pathFrame = (state.pathFrame + 1) % pathLength();
    if (state.pathFrame == 0) loaded.cut = true;  // the path starts over
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
