#include "s3d/frame/stereo_synthesis.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "s3d/frame/layered_reference.h"
#include "s3d/stereo/reprojection.h"

namespace s3d::frame {
namespace {

std::string sizeText(std::uint32_t width, std::uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// Where a surface path's time goes in the automatic choice's record.
std::optional<double>& timedPath(HybridSynthesis::SurfaceChoice& choice, HybridSurfaces surfaces, bool everyPixel) {
  if (surfaces == HybridSurfaces::Mixed) return everyPixel ? choice.everyPixelMixedMs : choice.mixedMs;
  if (everyPixel) return choice.everyPixelRaycastMs;
  return surfaces == HybridSurfaces::Raster ? choice.rasterMs : choice.raycastMs;
}

}  // namespace

StereoSynthesis::StereoSynthesis(vk::Context& context, const StereoSynthesisDescription& description)
    : context_(&context), description_(description) {
  if (description.width == 0 || description.height == 0)
    throw std::invalid_argument("stereo synthesis: the center view's size must not be 0 (got " +
                                sizeText(description.width, description.height) + ")");
  if (description.timedRuns < 1)
    throw std::invalid_argument("stereo synthesis: timedRuns must be at least 1 (got " +
                                std::to_string(description.timedRuns) + ")");
  if (description.hybrid) makeEyeRenderers();
  if (description.previousFrameFill) fill_.emplace(context);
}

void StereoSynthesis::makeEyeRenderers() {
  const renderer::RendererOptions options = eyeRendererOptions(description_.renderer, description_.hybridSurfaces);
  eyeRenderer_ = std::make_unique<renderer::DeferredRenderer>(*context_, description_.width, description_.height, options);
  // Rasterized eyes need the graphics queue: they render in turn.
  if (description_.concurrentEyes && context_->hasConcurrentQueue() && description_.hybridSurfaces != HybridSurfaces::Raster)
    rightEyeRenderer_ =
        std::make_unique<renderer::DeferredRenderer>(*context_, description_.width, description_.height, options);
  hybrid_.emplace(*context_);
}

void StereoSynthesis::setScene(const renderer::Scene& scene) {
  if (!eyeRenderer_) return;
  eyeRenderer_->setScene(scene);
  if (rightEyeRenderer_) rightEyeRenderer_->setScene(scene);
  eyeRendererHasScene_ = true;
  measuredSurfaces_.clear();
}

void StereoSynthesis::updateGeometry(const renderer::Scene& scene) {
  if (!eyeRenderer_ || !eyeRendererHasScene_) return;
  eyeRenderer_->updateGeometry(scene);
  if (rightEyeRenderer_) rightEyeRenderer_->updateGeometry(scene);
}

SynthesizedEyes StereoSynthesis::synthesize(const StereoSynthesisFrame& frame) {
  const renderer::DeferredRenderer& center = frame.centerRenderer;
  if (center.width() != description_.width || center.height() != description_.height)
    throw std::invalid_argument("stereo synthesis: the center view is " + sizeText(center.width(), center.height()) +
                                ", the synthesis was made for " + sizeText(description_.width, description_.height));
  if (frame.parameters.previousFrameFill != description_.previousFrameFill)
    throw std::invalid_argument(std::string("stereo synthesis: the frame's parameters ") +
                                (frame.parameters.previousFrameFill ? "ask for" : "leave out") +
                                " the previous-frame fill, the synthesis was made " +
                                (description_.previousFrameFill ? "with" : "without") + " it");
  if (frame.parameters.method == stereo::StereoMethod::Hybrid) return synthesizeHybridFrame(frame);
  if (fill_) return synthesizeFilledFrame(frame);
  return {stereo::synthesizeTimed(*context_, center.displayColor(), center.linearDepth(), frame.parameters,
                                  description_.timedRuns),
          std::nullopt};
}

SynthesizedEyes StereoSynthesis::synthesizeHybridFrame(const StereoSynthesisFrame& frame) {
  if (!eyeRenderer_) makeEyeRenderers();
  if (!eyeRendererHasScene_) setScene(frame.scene);
  HybridSynthesis hybrid = hybridWithChosenSurfaces(frame);
  SynthesizedEyes result;
  result.eyes = std::move(hybrid.eyes);
  result.gpuMs = hybrid.timings.total;
  result.filledLeft = hybrid.filledLeft;
  result.filledRight = hybrid.filledRight;
  result.hybrid = std::move(hybrid);
  return result;
}

HybridSynthesis StereoSynthesis::hybridWithChosenSurfaces(const StereoSynthesisFrame& frame) {
  auto run = [&](HybridSurfaces surfaces, bool everyPixel = false) {
    stereo::StereoParameters parameters = frame.parameters;
    if (everyPixel) parameters.hybridBudget = 1.0f;
    renderer::DeferredRenderer* right = rightEyeRenderer_ ? rightEyeRenderer_.get() : eyeRenderer_.get();
    return hybrid_->synthesize(frame.centerRenderer, {eyeRenderer_.get(), right}, frame.scene, frame.center, parameters,
                               description_.timedRuns, surfaces);
  };
  if (description_.hybridSurfaces != HybridSurfaces::Automatic || eyeRenderer_->raycastSurfacesRefusal())
    return run(description_.hybridSurfaces);
  const float budget = frame.parameters.hybridBudget;
  if (const auto measured = measuredSurfaces_.find(budget); measured != measuredSurfaces_.end())
    return run(measured->second.surfaces, measured->second.everyPixel);
  // Each path timed once, in this order (a tie keeps the earlier): masked rays, raster, the left eye's raster beside
  // the right eye's rays (it pays only where the two render at once), and below budget 1 every pixel (the exact
  // eyes) by rays and mixed.
  std::vector<SurfacePath> paths = {{HybridSurfaces::RayCast, false}, {HybridSurfaces::Raster, false}};
  if (rightEyeRenderer_) paths.push_back({HybridSurfaces::Mixed, false});
  if (budget < 1.0f) {
    paths.push_back({HybridSurfaces::RayCast, true});
    if (rightEyeRenderer_) paths.push_back({HybridSurfaces::Mixed, true});
  }
  // Only the fastest run so far is kept (each holds its eyes and HDR renders). Without timestamps nothing is known:
  // rays at the frame's budget, as synthesizeHybrid's Automatic.
  std::optional<HybridSynthesis> chosen;
  SurfacePath path = paths.front();
  HybridSynthesis::SurfaceChoice choice;
  for (const SurfacePath& candidate : paths) {
    HybridSynthesis result = run(candidate.surfaces, candidate.everyPixel);
    const std::optional<double> ms = result.timings.total;
    timedPath(choice, candidate.surfaces, candidate.everyPixel) = ms;
    if (!chosen || (ms && chosen->timings.total && *ms < *chosen->timings.total)) {
      chosen = std::move(result);
      path = candidate;
    }
  }
  measuredSurfaces_[budget] = path;
  chosen->surfaceChoice = choice;
  return std::move(*chosen);
}

// The fill reprojects the previous frame's eyes with each eye camera's motion since then: the two-pass reference's
// cameras on this frame (the formula's exact eyes), against the last filled frame's.
SynthesizedEyes StereoSynthesis::synthesizeFilledFrame(const StereoSynthesisFrame& frame) {
  std::array<EyeCamera, 2> eyes;
  std::array<gpu::EyeMotion, 2> motion{};
  for (const stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
    const std::size_t e = eye == stereo::Eye::Left ? 0 : 1;
    const renderer::ViewMatrices view = referenceEyeView(frame.scene, frame.center, eye, frame.parameters);
    eyes[e] = {view.worldView, view.worldProjection};
    if (previousEyes_)
      motion[e] = stereo::eyeMotion(eyes[e].view, eyes[e].projection, (*previousEyes_)[e].view,
                                    (*previousEyes_)[e].projection);
  }
  const renderer::DeferredRenderer& center = frame.centerRenderer;
  SynthesizedEyes result{stereo::synthesizeTimed(*context_, center.displayColor(), center.linearDepth(),
                                                 frame.parameters, *fill_, motion, description_.timedRuns),
                         std::nullopt};
  previousEyes_ = eyes;
  return result;
}

}  // namespace s3d::frame
