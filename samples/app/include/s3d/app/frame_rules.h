#pragma once
// The tool options `s3d render` (render_job.h) and `s3d tune` (tune_session.h) share: the HUD mode and the packing
// check. The per-frame comfort rules and the HUD itself are the library's (s3d/frame/comforted_stereo_frame.h).
#include <cstdint>
#include <string>

#include "s3d/frame/frame_hud.h"
#include "s3d/stereo/output_formats.h"

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

using frame::HudElementReport;  // the reports name the library's HUD element

}  // namespace s3d::app
