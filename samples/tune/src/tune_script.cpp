#include "s3d/tune/tune_script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "s3d/input_file.h"
#include "s3d/renderer/scene.h"

namespace s3d::tune {
namespace {

constexpr const char* kKeys = "wasdqe";  // FrameInput order: forward, left, back, right, down, up

struct VerbShape {
  const char* verb;
  std::size_t arguments;
};
constexpr VerbShape kVerbs[] = {{"set", 2},          {"view", 1},         {"scene", 1},      {"frame", 1},
                                {"play", 1},         {"reference", 1},    {"hold", 2},       {"look", 2},
                                {"wait", 1},         {"save-profile", 1}, {"load-profile", 1}, {"screenshot", 1},
                                {"supersample", 1},  {"quit", 0}};

bool parseWhole(const std::string& text, long long& value) {
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && ec == std::errc() && ptr == text.data() + text.size();
}

bool parseFinite(const std::string& text, double& value) {
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(value);
}

void checkCommand(const ScriptCommand& command) {
  const auto shape = std::find_if(std::begin(kVerbs), std::end(kVerbs),
                                  [&](const VerbShape& s) { return command.verb == s.verb; });
  if (shape == std::end(kVerbs)) throw std::invalid_argument("unknown command '" + command.verb + "'");
  if (command.arguments.size() != shape->arguments)
    throw std::invalid_argument("'" + command.verb + "' takes " + std::to_string(shape->arguments) + " argument(s), got " +
                                std::to_string(command.arguments.size()));
  const std::vector<std::string>& a = command.arguments;
  long long whole = 0;
  double number = 0.0;
  if (command.verb == "set") {
    const std::vector<std::string>& names = parameterNames();
    if (std::find(names.begin(), names.end(), a[0]) == names.end())
      throw std::invalid_argument("unknown parameter '" + a[0] + "'");
  } else if (command.verb == "view") {
    (void)parseViewMode(a[0]);
  } else if (command.verb == "scene") {
    (void)renderer::makeBuiltInScene(a[0]);  // throws naming the choices
  } else if (command.verb == "frame" || command.verb == "wait") {
    if (!parseWhole(a[0], whole) || whole < (command.verb == "wait" ? 1 : 0) || whole > 1000000)
      throw std::invalid_argument("'" + command.verb + "' expects a whole number" +
                                  (command.verb == "wait" ? " >= 1" : " >= 0") + " (got '" + a[0] + "')");
  } else if (command.verb == "supersample") {
    if (!parseWhole(a[0], whole) || whole < 1 || whole > 4)
      throw std::invalid_argument("'supersample' expects 1, 2, 3 or 4 (got '" + a[0] + "')");
  } else if (command.verb == "play" || command.verb == "reference") {
    if (a[0] != "on" && a[0] != "off") throw std::invalid_argument("'" + command.verb + "' expects on or off");
  } else if (command.verb == "hold") {
    if (a[0].size() != 1 || std::string(kKeys).find(a[0][0]) == std::string::npos)
      throw std::invalid_argument("'hold' expects one of the keys w a s d q e (got '" + a[0] + "')");
    if (!parseWhole(a[1], whole) || whole < 1 || whole > 1000000)
      throw std::invalid_argument("'hold' expects a frame count >= 1 (got '" + a[1] + "')");
  } else if (command.verb == "look") {
    if (!parseFinite(a[0], number) || !parseFinite(a[1], number))
      throw std::invalid_argument("'look' expects two numbers of pixels");
  }
}

}  // namespace

std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& name) {
  std::vector<ScriptCommand> commands;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    ScriptCommand command;
    command.line = number;
    if (!(words >> command.verb)) continue;
    for (std::string word; words >> word;) command.arguments.push_back(word);
    try {
      checkCommand(command);
    } catch (const std::exception& error) {
      throw std::invalid_argument(name + ":" + std::to_string(number) + ": " + error.what());
    }
    commands.push_back(std::move(command));
  }
  return commands;
}

std::vector<ScriptCommand> loadScript(const std::filesystem::path& path) {
  return parseScript(readInputFile(path, "script"), path.string());
}

ScriptFrame ScriptPlayer::next() {
  ScriptFrame frame;
  if (waitFrames_ > 0) {
    --waitFrames_;
  } else {
    while (next_ < commands_.size()) {
      const ScriptCommand& command = commands_[next_++];
      if (command.verb == "wait") {
        waitFrames_ = std::stoi(command.arguments[0]) - 1;  // this frame is the first of them
        break;
      }
      if (command.verb == "hold") {
        heldFrames_[std::string(kKeys).find(command.arguments[0][0])] = std::stoi(command.arguments[1]);
      } else if (command.verb == "look") {
        frame.input.lookPx += glm::vec2(std::stof(command.arguments[0]), std::stof(command.arguments[1]));
      } else {
        frame.commands.push_back(command);
      }
    }
  }
  bool* keys[6] = {&frame.input.forward, &frame.input.left, &frame.input.back,
                   &frame.input.right,   &frame.input.down, &frame.input.up};
  for (int key = 0; key < 6; ++key)
    if (heldFrames_[key] > 0) {
      *keys[key] = true;
      --heldFrames_[key];
    }
  return frame;
}

}  // namespace s3d::tune
