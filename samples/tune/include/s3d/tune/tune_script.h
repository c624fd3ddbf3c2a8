#pragma once
// Scripted input for `s3d tune --script FILE` (and the CI test): one command per line, '#' starts a comment.
//   set NAME VALUE        a parameter of tune_settings.h (parameterNames())
//   view MODE             anaglyph, sbs, left, right, reference, error, parallax, comfort
//   scene NAME            a built-in scene (its camera at frame 0)
//   frame N               the camera of frame N of the scene's path
//   play on|off           play the scene's camera path
//   reference on|off      render the two-pass reference every frame (error numbers)
//   supersample N         renderer anti-aliasing factor 1..4 (as `s3d render --supersample`)
//   hold KEY N            hold a movement key (w a s d: walk, q e: down/up) for the next N frames
//   look DX DY            mouse-look by DX, DY pixels on the next frame
//   wait N                let N frames pass (the commands above apply to the first of them)
//   save-profile FILE, load-profile FILE, screenshot FILE (after the frame is drawn), quit (after it is shown)
// Commands run in order before a frame is drawn, up to the next `wait`; with no `wait` left, all that remain
// apply to the next frame.
#include <filesystem>
#include <string>
#include <vector>

#include "s3d/tune/tune_state.h"

namespace s3d::tune {

struct ScriptCommand {
  std::string verb;
  std::vector<std::string> arguments;
  int line = 0;  // 1-based line in the script, for error messages
};

// Throws std::invalid_argument "NAME:LINE: <problem>" for an unknown command, a wrong argument count or a bad
// number, key, view or parameter name (values are checked when they run: they may depend on each other).
std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& name = "script");
std::vector<ScriptCommand> loadScript(const std::filesystem::path& path);

// What one frame of a script asks for.
struct ScriptFrame {
  std::vector<ScriptCommand> commands;  // to run before the frame, in order (hold/look/wait already folded in)
  FrameInput input;                     // held keys and mouse look of this frame
};

class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}
  ScriptFrame next();  // the next frame's part of the script
  bool finished() const { return next_ >= commands_.size() && waitFrames_ == 0; }

 private:
  std::vector<ScriptCommand> commands_;
  std::size_t next_ = 0;
  int waitFrames_ = 0;        // frames still to pass before the next command runs
  int heldFrames_[6] = {};    // w a s d q e: frames each key is still held
};

}  // namespace s3d::tune
