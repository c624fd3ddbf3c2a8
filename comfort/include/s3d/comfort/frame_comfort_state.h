#pragma once
// The per-frame comfort rules in one call a host makes each frame, with no s3d renderer type: the weapon push
// capped by the zero-parallax plane, the zero-parallax distance held at the nearest depth, the crosshair placed
// by the host's ray cast, the disparity budget (the host's controller choosing maxSeparation and the
// zero-parallax distance from the frame's depth range), and each HUD element's depth, parallax and fade behind
// the weapon (seed 4.6.2). s3d render and s3d tune apply the same rules (budget_frame.h and the frame library's
// drawHud call these).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/image.h"
#include "s3d/stereo/disparity_map_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

// The weapon mask's linear depth range before the push (the host's first-person layer in view).
struct WeaponMaskStats {
  std::uint64_t pixels = 0;  // 0: no weapon in view
  float nearestDepth = 0.0f;
  float farthestDepth = 0.0f;
};

struct HudElementDepth {
  std::string name;
  float depth = 1.0f;  // linear view depth the element should be shown at
};

// The disparity budget of one frame: the host keeps one controller per view stream (it smooths over frames)
// and gives it the frame's depth range, reduced on the GPU by stereo::DepthRangePass from the linear depth the
// stereo pass reads, or the host's own (nearest, farthest, sky count; a histogram of any fixed binning enables
// the cut detector). The weapon is added from FrameComfortInput::weapon, pushed, when the range lacks it.
struct FrameBudget {
  DisparityBudgetController* controller = nullptr;  // must not be null; its display's budget is used
  const stereo::DepthRange* depth = nullptr;         // must not be null
  float seconds = 1.0f / 60.0f;                      // this frame's duration (the controller's rate bounds)
  bool cut = false;                                  // the host knows the camera cut: no ramp
  std::optional<float> anticipatedNearest;           // a nearer surface expected soon (e.g. ray casts ahead)
  bool receding = false;  // the camera moves away from what it sees: a deeper range is followed without the hold
};

struct FrameComfortInput {
  FrameCamera camera;
  RayCast rayCast;  // empty: no world; the crosshair stays at crosshairDistance
  stereo::StereoParameters parameters;  // the host's settings for this frame
  std::uint32_t width = 0;  // of the eyes, in pixels (parallax in pixels)
  float crosshairDistance = 10.0f;
  float crosshairMargin = 0.25f;
  WeaponMaskStats weapon;
  // The frame's nearest world depth (not the weapon; e.g. from a depth-range reduction): the zero-parallax
  // distance is held at min(it, the pushed weapon's nearest). Or the whole stereo depth (weapon pushed with
  // `parameters`), from which it is taken, and which also gives `statistics` together with a display.
  std::optional<float> nearestWorldDepth;
  const DepthImage* stereoDepth = nullptr;
  const DisplayProfile* display = nullptr;
  std::vector<HudElementDepth> hud;
  bool allowNegativeParallax = false;  // off: nothing is shown in front of the screen plane
  // The curve a nonlinear depth-to-parallax mapping applied to the stereo pass's depth (stereo::DisparityMapPass
  // on the host's linear depth): the crosshair and HUD get the parallax of their mapped depth. Identity: linear.
  gpu::DisparityMapConstants disparityMap{};
  // With it, maxSeparation and the zero-parallax distance are the controller's choice (its negative-parallax
  // setting must equal allowNegativeParallax); without it, the host's.
  std::optional<FrameBudget> budget;
};

struct HudElementState {
  std::string name;
  float depth = 0.0f;       // as shown: not in front of the zero-parallax plane unless allowed
  float parallaxPx = 0.0f;  // the right eye's offset in pixels (the left eye's is minus this)
  bool fadesBehindWeapon = false;  // deeper than the pushed weapon's nearest point: fade where the mask covers it
};

struct FrameComfortState {
  stereo::StereoParameters parameters;  // for the stereo pass: weapon push and zero-parallax distance applied
  bool weaponPushed = false;            // the push was changed to keep the weapon behind the screen plane
  bool zeroParallaxLimited = false;     // the zero-parallax distance was lowered to the nearest depth
  float crosshairDepth = 0.0f;
  bool crosshairHitWorld = false;
  HudElementState crosshair;            // the crosshair as a HUD element
  std::vector<HudElementState> hud;     // in the order given
  std::optional<FrameComfort> statistics;  // with stereoDepth and display
  std::optional<BudgetChoice> budget;      // with a budget whose depth range has pixels
};

// Throws std::invalid_argument for a width of 0, a non-positive crosshair distance or HUD depth, a budget
// without controller or depth range, or one whose controller disagrees on negative parallax.
FrameComfortState frameComfortState(const FrameComfortInput& input);

// The pieces, for tools that apply them at different points of their frame.
// Without negative parallax allowed and with a weapon in view, pushWeaponBehindScreen (comfort_report.h).
stereo::StereoParameters weaponPushForFrame(stereo::StereoParameters parameters, const WeaponMaskStats& weapon,
                                            bool allowNegativeParallax);
// Without negative parallax allowed, the zero-parallax distance lowered to `nearest` when that is nearer.
bool holdZeroParallax(stereo::StereoParameters& parameters, std::optional<float> nearest, bool allowNegativeParallax);
// One HUD element at `depth` for the frame's final parameters, at the parallax of its depth mapped by the
// frame's depth-to-parallax curve (stereo/disparity_map.h; the identity by default), as the scene around it.
HudElementState hudElementState(const std::string& name, float depth, const stereo::StereoParameters& parameters,
                                const WeaponMaskStats& weapon, std::uint32_t width, bool allowNegativeParallax,
                                const gpu::DisparityMapConstants& disparityMap = {});

}  // namespace s3d::comfort
