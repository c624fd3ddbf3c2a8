#pragma once
// The per-frame tool rules `s3d render` (render_job.h) and `s3d tune` (tune_session.h) share, so the tool shows
// what the offscreen render writes: the HUD overlay (s3d/hud/overlay.h) with its per-element report and the
// packing check; the comfort rules on the parameters are the library's (s3d/comfort/budget_frame.h).
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

namespace s3d::app {

// Before a run: throws std::invalid_argument naming --sbs / --tab when half packing cannot squeeze eyes of this
// size (it needs 2 columns / rows), so a size the options accept cannot fail after the whole run. `writes...`:
// whether sbs.png / tab.png are written; `outputsSelectable`: whether --outputs can leave them out.
void requirePackableEyes(std::uint32_t width, std::uint32_t height, bool writesSideBySide, stereo::PackingMode sideBySide,
                         bool writesTopBottom, stereo::PackingMode topBottom, bool outputsSelectable);

// The game HUD of the built-in scenes (health and ammo panels, crosshair). A glTF file is the user's own scene:
// a game's HUD drawn over it would be ours, not theirs, so Auto leaves it out there.
enum class HudMode {
  Auto,  // Game on the built-in scenes, None on scene files
  Game,  // the panels and the crosshair
  None,  // nothing drawn; the eyes are the stereo pass's (made opaque)
};
HudMode parseHudMode(const std::string& name);  // "auto", "game", "none"; throws std::invalid_argument otherwise
const char* hudModeName(HudMode mode);
// Auto resolved for `scene` (a built-in name or a .gltf/.glb file).
HudMode resolveHudMode(HudMode mode, const std::string& scene);

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
// stereo synthesis into every view at the parallax of its depth and faded out where the weapon mask (the eyes'
// alpha) covers an element that lies behind the weapon. Drawn into `eyes` (counted in the report) and into
// `center` and `reference` when given; then every one of them is made opaque (the mask has served). With
// input.draw false nothing is drawn: no elements, and the crosshair depth is the placement's (screen rule applied).
HudFrame drawHud(const HudFrameInput& input, stereo::StereoPair& eyes, ImageRGBA8* center = nullptr,
                 stereo::StereoPair* reference = nullptr);

}  // namespace s3d::app
