#include "s3d/app/frame_rules.h"

#include <algorithm>
#include <stdexcept>

#include "s3d/renderer/scene_file.h"

namespace s3d::app {
HudMode parseHudMode(const std::string& name) {
  if (name == "auto") return HudMode::Auto;
  if (name == "game") return HudMode::Game;
  if (name == "none") return HudMode::None;
  throw std::invalid_argument("unknown HUD '" + name + "' (choices: auto, game, none)");
}

const char* hudModeName(HudMode mode) {
  switch (mode) {
    case HudMode::Auto: return "auto";
    case HudMode::Game: return "game";
    case HudMode::None: return "none";
  }
  return "auto";
}

HudMode resolveHudMode(HudMode mode, const std::string& scene) {
  if (mode != HudMode::Auto) return mode;
  return renderer::isSceneFile(scene) ? HudMode::None : HudMode::Game;
}

void requirePackableEyes(std::uint32_t width, std::uint32_t height, bool writesSideBySide, stereo::PackingMode sideBySide,
                         bool writesTopBottom, stereo::PackingMode topBottom, bool outputsSelectable) {
  auto require = [&](bool squeezed, std::uint32_t size, const char* option, const char* across, const char* units,
                     const char* file) {
    if (!squeezed || size >= 2) return;
    throw std::invalid_argument(std::string(option) + " half squeezes each eye to half its " + across +
                                ", which needs at least 2 " + units + " (the " + across + " is " + std::to_string(size) +
                                "): use " + option + " full" +
                                (outputsSelectable ? std::string(" or leave ") + file + " out of --outputs" : ""));
  };
  require(writesSideBySide && sideBySide == stereo::PackingMode::Half, width, "--sbs", "width", "columns", "sbs.png");
  require(writesTopBottom && topBottom == stereo::PackingMode::Half, height, "--tab", "height", "rows", "tab.png");
}

}  // namespace s3d::app
