#pragma once
// `s3d tune`'s state besides the parameters: scene, camera, view, playback; and the camera control
// (mouse look, WASD) as a pure function of one frame's input.
#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "s3d/app/frame_rules.h"
#include "s3d/comfort/disparity_budget.h"
#include "s3d/renderer/scene.h"
#include "s3d/tune/tune_settings.h"

namespace s3d::tune {

// One frame of input, from the keyboard and mouse or from a script.
struct FrameInput {
  bool forward = false, back = false, left = false, right = false, down = false, up = false;  // w s a d q e
  glm::vec2 lookPx{0.0f};  // mouse movement while looking (right, down: positive)
};

inline constexpr float kWalkSpeed = 2.0f;            // metres per second, the scenes' path speed
inline constexpr float kLookRadiansPerPixel = 0.004f;
inline constexpr float kMaxPitchRadians = 1.5f;      // just short of straight up or down

// Mouse look turns (right: yaw decreases, so the camera turns clockwise seen from above; down: pitch
// decreases), then WASD walks in the horizontal plane of the new yaw and q/e move down/up, kWalkSpeed * seconds.
void moveCamera(renderer::Camera& camera, const FrameInput& input, float seconds);

struct TuneState {
  TuneSettings settings;
  std::string scene = "courtyard";
  std::size_t pathFrame = 0;  // the camera path frame the camera was last set from
  renderer::Camera camera;    // the live camera (moved by the input, or following the path when playing)
  ViewMode view = ViewMode::Anaglyph;
  bool playPath = false;      // advance along the scene's camera path one frame per frame
  bool reference = true;      // render the two-pass reference eyes (error numbers); forced by the views needing it
  std::uint32_t supersample = 1;  // renderer anti-aliasing, 1..4 (renderer::RendererOptions), as `s3d render`
  // OneDegree: maxSeparation and the zero-parallax distance chosen per frame (s3d/comfort/budget_frame.h), as
  // `s3d render`.
  comfort::DisparityBudgetRule disparityBudget = comfort::DisparityBudgetRule::Off;
  app::HudMode hud = app::HudMode::Auto;  // the game HUD (panels, crosshair), as `s3d render --hud`
};

}  // namespace s3d::tune
