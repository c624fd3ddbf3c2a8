#pragma once
// The HUD of a frame from s3d's renderer (hud/overlay.h's panels and crosshair): each element drawn after stereo
// synthesis into every view at the parallax of its depth, by the comfort rules (comfort/frame_comfort_state.h),
// with a per-element report. ComfortedStereoFrame draws it; the tools draw the same HUD over their other images.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/image.h"
#include "s3d/stereo/disparity_map_shared.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/stereo.h"

namespace s3d::frame {

// One HUD element (s3d/hud/overlay.h) as drawn into the synthesized eyes.
struct HudElementReport {
  std::string name;            // "health", "ammo", "crosshair"
  float depth = 0.0f;          // linear view depth it is shown at
  bool behindWeapon = false;   // deeper than the weapon's nearest pushed point: fades where the weapon covers it
  std::array<std::uint64_t, 2> drawnPixels{};  // left, right
  std::array<std::uint64_t, 2> fadedPixels{};  // left, right: pixels the weapon mask faded
  std::uint64_t conflictPixels = 0;  // visible pixels deeper than the scene surface they cover (center view)
};

// What the HUD of one frame is drawn from.
struct HudFrameInput {
  stereo::StereoParameters parameters;    // as the stereo pass used them (push and zero-parallax rules applied)
  float crosshairDepth = 0.0f;            // comfort::placeCrosshair's depth, before the screen-plane rule
  std::optional<glm::vec2> weaponDepths;  // the weapon's unpushed depth range (renderer::firstPersonDepthRange)
  bool allowNegativeParallax = false;     // off: no element is shown in front of the screen plane
  const DepthImage* stereoDepth = nullptr;                   // the center view's linear depth (weapon pushed)
  const std::vector<std::uint8_t>* firstPersonMask = nullptr;  // the renderer's weapon mask of the center view
  bool draw = true;  // false (HudMode::None): no element is drawn or reported, the images are only made opaque
  // The frame's depth-to-parallax curve (stereo/disparity_map.h): elements are shown at the parallax of their
  // mapped depth, as the scene around them.
  gpu::DisparityMapConstants disparityMap{};
};

struct HudFrame {
  std::vector<HudElementReport> elements;  // panels, then the crosshair
  std::uint64_t conflictPixels = 0;        // sum over the elements
  float crosshairDepth = 0.0f;             // as drawn (the screen-plane rule applied)
};

// The HUD (seed 4.6.2): the static panels (hud::defaultPanels) and the crosshair on top, each drawn after
// stereo synthesis into both eyes at the parallax of its depth and faded out where the weapon mask (the eyes'
// alpha) covers an element that lies behind the weapon; then the eyes are made opaque (the mask has served).
// With input.draw false nothing is drawn: no elements, and the crosshair depth is the placement's (screen rule
// applied). Throws std::invalid_argument without the input's depth and weapon mask.
HudFrame drawHud(const HudFrameInput& input, stereo::StereoPair& eyes);

// The same HUD drawn over more images of the frame (a center view, reference eyes), made opaque alike; nothing is
// reported. With input.draw false they are only made opaque.
void drawHudOver(const HudFrameInput& input, ImageRGBA8* center, stereo::StereoPair* eyes);

}  // namespace s3d::frame
