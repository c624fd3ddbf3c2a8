#pragma once
// `s3d tune`'s window: GLFW on a Vulkan swapchain, the view at the left (1:1 when it fits), a Dear ImGui panel
// at the right with every parameter, the view modes, camera and scene controls and the live numbers.
// Everything it shows comes from TuneSession (tune_session.h); this file only draws and takes input.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "s3d/tune/tune_state.h"
#include "s3d/vk/context.h"

namespace s3d::tune {

// No window could be opened (no display, or no Vulkan device that can present to it).
class NoDisplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kPanelWidth = 360;       // pixels right of the view
inline constexpr int kMinWindowHeight = 720;  // room for the panel
// Seconds per frame under --script or --frames (frame times would make runs differ): the scenes' path rate.
inline constexpr float kScriptedFrameSeconds = 1.0f / 12.0f;

struct TuneWindowOptions {
  std::uint32_t width = 960;  // the view: rendered (and shown) size
  std::uint32_t height = 540;
  TuneState state;            // initial state (scene, parameters, view)
  std::optional<std::filesystem::path> script;      // tune_script.h
  std::optional<std::size_t> frames;                // quit after this many frames
  std::optional<std::filesystem::path> screenshot;  // of the last frame (with frames), or at quit
  std::filesystem::path profileFile = "comfort_profile.json";  // the panel's Save / Load file
  vk::ContextOptions context;  // device and validation; presentation is added by the window
};

struct TuneWindowResult {
  std::size_t frames = 0;
  std::string deviceName;
  std::vector<std::string> validationMessages;
};

// Runs until the window closes, the script quits or `frames` have been shown.
// Throws NoDisplayError when no window can be opened, std::invalid_argument for bad options or scripts.
TuneWindowResult runTuneWindow(const TuneWindowOptions& options);

}  // namespace s3d::tune
