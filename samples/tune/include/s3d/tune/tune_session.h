#pragma once
// One `s3d tune` frame without the window: move the camera (input or camera path), run the zero-parallax
// control, render the center view, synthesize the eyes, optionally render the two-pass reference, measure, and
// compose the chosen view. The GLFW/ImGui shell (tune_window.h) only shows the result and edits the state.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/comfort/zero_parallax_control.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/metrics.h"
#include "s3d/tune/tune_script.h"
#include "s3d/tune/tune_state.h"
#include "s3d/tune/tune_views.h"
#include "s3d/vk/context.h"

namespace s3d::tune {

// The live numbers of one frame.
struct FrameNumbers {
  std::optional<double> centerFrameGpuMs;    // whole deferred frame of the center view
  std::vector<renderer::PassTiming> centerPasses;
  std::optional<double> stereoPassGpuMs;     // the stereo dispatch producing both eyes
  std::optional<double> referenceEyesGpuMs;  // both two-pass reference eyes (when rendered)
  std::optional<stereo::ErrorStats> errorLeft, errorRight;  // synthesized vs reference (when rendered)
  // On the display profile, as `s3d render`'s comfort report: parallax range, share beyond the 1-degree rule,
  // stereo window violations (comfort_report.h).
  comfort::FrameComfort comfort;
  double shareBeyondComfort = 0.0;           // pixels beyond comfort::kComfortLimitArcmin
  std::uint64_t weaponConflictPixels = 0;    // weapon pixels pushed behind the world surface there
  std::uint64_t hudConflictPixels = 0;       // HUD pixels deeper than the surface they cover
  float zeroParallaxDistance = 0.0f;         // as used (the control's output when it runs, the rules applied)
  bool zeroParallaxLimited = false;          // held at the frame's nearest depth (negative parallax disallowed)
  std::optional<float> nearestSurface;       // what the control's ray casts saw
  float weaponDepthOffset = 0.0f, weaponDepthScale = 0.0f;  // the push as used
  float crosshairDepth = 0.0f;              // as drawn (not in front of the screen plane unless allowed)
  bool crosshairHitWorld = false;
  std::uint64_t sanitizedDepthPixels = 0;  // NaN / non-positive depths read as the zero-parallax plane
  std::optional<std::string> warning;      // e.g. the zero-parallax distance clamped into the camera's range
  comfort::BudgetFrame budget;               // the disparity budget's reduction and choice (rule off: empty)
  comfort::DisparityMapReport disparityMap;  // the depth-to-parallax curve (identity: linear)
  float maxSeparation = 0.0f;              // as used
};

struct TuneFrame {
  ImageRGBA8 view;  // what the view area shows (composeView)
  FrameNumbers numbers;
};

class TuneSession {
 public:
  TuneSession(vk::Context& context, std::uint32_t width, std::uint32_t height);
  ~TuneSession();

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

  // Loads state.scene (throws naming the choices), puts the camera at state.pathFrame of its path and restarts
  // the zero-parallax control.
  void loadScene(TuneState& state);
  // The camera of this frame of the scene's path (throws std::out_of_range naming the frame count).
  void setPathFrame(TuneState& state, std::size_t frame);
  std::size_t pathLength() const;
  float sceneCrosshairDistance() const;  // the loaded scene's default crosshair depth

  // One frame: playing, the camera is the path's current frame and the path advances after it; otherwise the
  // input moves the camera by `seconds`. Loads the scene first when state.scene changed.
  TuneFrame renderFrame(TuneState& state, const FrameInput& input, float seconds);

 private:
  struct Loaded;
  vk::Context& context_;
  std::uint32_t width_, height_;
  std::unique_ptr<Loaded> loaded_;
};

// What a script asks of the window itself.
struct WindowRequests {
  std::optional<std::filesystem::path> screenshot;  // after this frame is drawn
  bool quit = false;                                // after this frame is shown
};

// Runs one script command (tune_script.h) on the state and the session: set, view, scene, frame, play, reference,
// save-profile, load-profile; screenshot and quit go to `requests`. Throws naming the script line.
void runScriptCommand(TuneSession& session, TuneState& state, const ScriptCommand& command, WindowRequests& requests);

}  // namespace s3d::tune
