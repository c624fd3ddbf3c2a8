#pragma once
// One frame of s3d's own renderer with every per-frame comfort rule, in the order the tools apply them: the weapon
// push, the zero-parallax control and the crosshair smoother (state kept between frames), the center view (wider
// by a guard band), the zero-parallax plane held at the nearest depth, the disparity budget (the band widened and
// the center view rendered again when it picks a wider separation), the nonlinear depth-to-parallax map, the
// crosshair placement, the stereo synthesis, the comfort report and the HUD. Created from a description, called
// once per frame; a tool configures it, runs it and compares or writes what it returns.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/comfort_profile.h"
#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/comfort/zero_parallax_control.h"
#include "s3d/frame/frame_hud.h"
#include "s3d/frame/stereo_synthesis.h"
#include "s3d/image.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::frame {

// The comfort rules a frame runs.
struct FrameComfortSettings {
  comfort::DisplayProfile display = comfort::builtInDisplayProfile("tv55");  // of the budget and the comfort report
  comfort::DisparityBudgetRule budget = comfort::DisparityBudgetRule::Off;
  bool allowNegativeParallax = false;  // off: the weapon pushed to the screen plane, the plane held at the nearest depth
  // The zero-parallax control (its restDistance is the stereo parameters' distance); none: the plane stays there.
  std::optional<comfort::ZeroParallaxControlSettings> zeroParallaxControl;
  comfort::CrosshairSettings crosshair;  // distance (nullopt: the scene's) and margin
  bool smoothCrosshair = false;          // crosshair.responseSeconds smooths its depth over frames
  bool crosshairHintsBudget = true;      // the budget controller keeps the crosshair's depth comfortable
  // The budget's anticipation: the control's rays cast from where the camera will be this many frames ahead at its
  // current velocity (0: none).
  float anticipateFrames = 0.0f;
};

struct ComfortedStereoFrameDescription {
  std::uint32_t width = 0, height = 0;  // the output eyes'
  renderer::RendererOptions renderer;
  stereo::StereoParameters stereo;  // the method's settings and the rest values the rules start from each frame
  FrameComfortSettings comfort;
  // The center view rendered wider by the largest displacement the eyes can need, so both eyes are full frame
  // (edgeCrop then 0); off: the output-size center view and the parameters' edge crop.
  bool guardBand = true;
  std::uint32_t maxRenderedWidth = 16384;  // the band's cap
  bool hud = true;                         // the game HUD's panels and crosshair; off: the eyes only made opaque
  bool warmUp = false;          // a new center renderer renders once untimed (shader compilation out of the times)
  bool sanitizeDepth = true;    // invalid depth reads as the zero-parallax plane (counted), as the stereo pass reads it
  bool keepHdr = false;         // read the center view's HDR color back (sanitized)
  // Called before the center view is rendered again at a wider band with the parameters that need it (a memory
  // check may throw).
  std::function<void(const stereo::StereoParameters&, std::uint32_t renderedWidth)> beforeWiderBand;
};

// Everything one frame applied and made.
struct ComfortedFrame {
  stereo::StereoParameters parameters;          // as applied, for the output size (edgeCrop 0 with a band)
  stereo::StereoParameters renderedParameters;  // the same for the rendered frame (the pass's, the references')
  stereo::GuardBand band;
  std::uint32_t width = 0, renderedWidth = 0;
  std::uint32_t cropColumns = 0;  // per side, blacked out (0 with a band)
  std::optional<std::string> zeroParallaxWarning;  // the plane clamped into the camera's depth range, and why
  std::optional<float> nearestSurface;  // what the zero-parallax control's rays saw
  std::optional<float> nearestDepth;    // nearest finite depth of the center view (weapon pushed)
  bool zeroParallaxLimited = false;     // the no-negative-parallax rule lowered the plane this frame
  comfort::BudgetFrame budget;
  comfort::DisparityMapReport disparityMap;
  comfort::CrosshairPlacement crosshair;  // the aim ray's placement
  float crosshairDepth = 0.0f;            // smoothed when asked, not in front of the screen plane unless allowed
  renderer::ViewMatrices center, outputCenter;  // the rendered and the output-size center view's matrices
  renderer::FrameTimings centerTimings;         // the last center render
  std::uint64_t sanitizedDepthPixels = 0, sanitizedColorValues = 0;
  DepthImage renderedDepth;        // the rendered frame's linear depth (the scene's, weapon pushed)
  DepthImage renderedStereoDepth;  // mapped (what the stereo pass read)
  ImageRGBA32F renderedHdr;        // when the description keeps it
  DepthImage depth, stereoDepth;   // the same cropped to the output
  std::vector<std::uint8_t> firstPersonMask;  // the output's weapon mask
  SynthesizedEyes synthesized;     // on the rendered frame, with the hybrid's details
  stereo::StereoPair eyes;         // cropped to the output, without the HUD
  stereo::StereoPair eyesWithHud;  // and with it (opaque)
  HudFrame hud;
  comfort::FrameComfort comfort;
  comfort::WeaponConflicts weaponConflicts;
  std::optional<glm::vec2> weaponDepths;  // the weapon's unpushed depth range (none: no weapon)
  bool allowNegativeParallax = false;     // as the description's rules (the HUD's input)
  bool drawHud = true;

  // What the HUD was drawn from (valid while this frame is): for drawHudOver on the tools' other images.
  HudFrameInput hudInput() const;
  // A rendered-frame image or mask cropped to the output's columns.
  template <class Image>
  Image toOutput(const Image& image) const { return stereo::cropColumns(image, band.columns, width); }
  std::vector<std::uint8_t> maskToOutput(const std::vector<std::uint8_t>& mask) const {
    return stereo::cropColumns(mask, renderedWidth, band.columns, width);
  }
};

class ComfortedStereoFrame {
 public:
  // Throws std::invalid_argument naming a size, display or control setting out of range.
  ComfortedStereoFrame(vk::Context& context, const ComfortedStereoFrameDescription& description);
  ~ComfortedStereoFrame();

  // A new scene (render takes a scene it has not seen itself): the world queries and the renderers take it. The
  // caller keeps it alive while this object uses it.
  void setScene(const renderer::Scene& scene);
  // A new pose of the scene (an animation's frame): the renderers' geometry and the world queries follow.
  void updateGeometry(const renderer::Scene& scene);
  // New parameters and rules between frames (a tuning tool's): a controller whose settings changed starts from
  // rest, the others keep their state.
  void setRules(const stereo::StereoParameters& stereo, const FrameComfortSettings& comfort, bool hud);

  // One frame of `scene` (posed, its camera set) after `seconds`; a cut starts the controllers again from rest.
  ComfortedFrame render(const renderer::Scene& scene, float seconds, bool cut = false);

  // The last frame's center renderer (its view is the frame's `center`), for the two-pass reference eyes (which
  // render with it: read its images first).
  renderer::DeferredRenderer& centerRenderer() { return *deferred_; }
  // Frees the synthesis (the hybrid's eye renderer, the fill's history) until the next frame.
  void releaseSynthesis() { synthesis_.reset(); }

 private:
  struct Controls;
  stereo::StereoParameters parametersBeforeCenter(const renderer::Scene& scene, float seconds, ComfortedFrame& frame);
  stereo::GuardBand bandFor(const stereo::StereoParameters& parameters, const renderer::Scene& scene) const;
  bool useBand(const stereo::GuardBand& wanted, const renderer::Scene& scene);
  void renderCenter(const renderer::Scene& scene, const stereo::StereoParameters& parameters, ComfortedFrame& frame);
  void holdAtNearestDepth(stereo::StereoParameters& parameters, ComfortedFrame& frame);
  void applyBudget(const renderer::Scene& scene, float seconds, bool cut, stereo::StereoParameters& parameters,
                   ComfortedFrame& frame);
  void finishFrame(const renderer::Scene& scene, stereo::StereoParameters parameters, ComfortedFrame& frame);
  void synthesizeEyes(const renderer::Scene& scene, ComfortedFrame& frame);

  vk::Context& context_;
  ComfortedStereoFrameDescription description_;
  std::unique_ptr<renderer::DeferredRenderer> deferred_;
  std::unique_ptr<StereoSynthesis> synthesis_;
  std::unique_ptr<comfort::WorldQueries> world_;
  const renderer::Scene* worldScene_ = nullptr;  // the scene the world queries view
  stereo::GuardBand band_;
  bool freshRenderer_ = false;  // made since the last center render
  std::unique_ptr<Controls> controls_;
};

}  // namespace s3d::frame
