#pragma once
// Both eyes from s3d's own renderer's center view, whatever the method: the one place that chooses between the
// displacement methods (stereo::synthesizeTimed), the forward method with the previous-frame fill (its history
// kept here between frames) and the hybrid (a HybridSynthesizer and an eye renderer, both kept here: a hybrid
// frame does not make its pipelines again). Created from a description, called once per frame. A host with its
// own renderer uses stereo::StereoFrame instead.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>

#include "s3d/frame/hybrid_stereo.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/previous_fill_pass.h"
#include "s3d/stereo/stereo.h"
#include "s3d/stereo/synthesis.h"
#include "s3d/vk/context.h"

namespace s3d::frame {

struct StereoSynthesisDescription {
  std::uint32_t width = 0, height = 0;  // the center view's (a guard band included): every frame's
  renderer::RendererOptions renderer;   // the center view's; the hybrid's eye renders are made alike
  // Frames will use the hybrid method: its eye renderer is made now, and takes the scene at setScene (else at the
  // first hybrid frame, with that frame's scene).
  bool hybrid = false;
  HybridSurfaces hybridSurfaces = HybridSurfaces::Automatic;  // how its eye pixels' surfaces are found
  // On a device with a compute queue (vk::Context::hasConcurrentQueue), a second eye renderer so that the
  // hybrid's ray-cast eyes render at once (HybridSynthesizer's two-renderer synthesize): the same eyes, in less
  // time, for a second eye renderer's memory. Elsewhere, or false: one eye renderer renders both eyes in turn.
  bool concurrentEyes = true;
  // Forward frames fill their disocclusions from the previous frame's eyes (the frames' parameters say the same).
  bool previousFrameFill = false;
  int timedRuns = 1;  // every GPU part runs once untimed, then this many times; times are medians
};

// One frame. The method and every other setting come with the parameters, so a frame may change any of them.
struct StereoSynthesisFrame {
  // Its last frame is `center`: the displayColor and linearDepth (vk::kComputeWrite state, left so) the eyes are
  // made from; its shadow maps light the hybrid's eye renders.
  const renderer::DeferredRenderer& centerRenderer;
  const renderer::Scene& scene;  // as the center renderer's (the hybrid's eye cameras render it)
  const renderer::ViewMatrices& center;
  const stereo::StereoParameters& parameters;  // for the center view's size (a guard band's rescaled ones)
};

// The eyes, their GPU time (the hybrid's: its total) and the iterative fills; the hybrid's details besides.
struct SynthesizedEyes : stereo::SynthesisResult {
  std::optional<HybridSynthesis> hybrid;  // method hybrid: masks, rendered pixels, thresholds, timings (eyes empty)
};

class StereoSynthesis {
 public:
  // Throws std::invalid_argument for a zero size or timedRuns below 1.
  StereoSynthesis(vk::Context& context, const StereoSynthesisDescription& description);

  // A new scene, or a new pose of it (DeferredRenderer::setScene / updateGeometry), for the eye renderer if made.
  // A new scene measures the hybrid's surface paths again (HybridSurfaces::Automatic), as does the first frame of
  // each hybrid budget; a new pose keeps the choices.
  void setScene(const renderer::Scene& scene);
  void updateGeometry(const renderer::Scene& scene);

  // Throws std::invalid_argument for a center view of another size, or parameters whose previousFrameFill is not
  // the description's.
  SynthesizedEyes synthesize(const StereoSynthesisFrame& frame);

 private:
  // The hybrid's eye renderers: the center view's size and options, made to shade rays where the description
  // asks; a second one for the right eye where the eyes can render at once (concurrentEyes).
  void makeEyeRenderers();
  SynthesizedEyes synthesizeHybridFrame(const StereoSynthesisFrame& frame);
  // The surface path for this frame: the description's, or with Automatic on an eye renderer that can cast rays,
  // the fastest of rays, raster, the left eye rasterized with the right eye's rays at once (where a second eye
  // renderer exists) and every pixel (by rays, and mixed there) as timed on this scene's first hybrid frame at the
  // frame's budget (that frame's result is the fastest path's).
  HybridSynthesis hybridWithChosenSurfaces(const StereoSynthesisFrame& frame);
  SynthesizedEyes synthesizeFilledFrame(const StereoSynthesisFrame& frame);

  struct EyeCamera {
    glm::mat4 view, projection;
  };
  vk::Context* context_;
  StereoSynthesisDescription description_;
  std::unique_ptr<renderer::DeferredRenderer> eyeRenderer_, rightEyeRenderer_;  // the second: concurrent eyes only
  std::optional<HybridSynthesizer> hybrid_;  // made with the eye renderers
  bool eyeRendererHasScene_ = false;
  struct SurfacePath {
    HybridSurfaces surfaces;
    bool everyPixel;  // budget 1 whatever the frame's
  };
  std::map<float, SurfacePath> measuredSurfaces_;  // Automatic's choice per hybrid budget for the current scene
  std::optional<stereo::PreviousFillPass> fill_;
  std::optional<std::array<EyeCamera, 2>> previousEyes_;  // the last filled frame's eye cameras (the fill's motion)
};

}  // namespace s3d::frame
