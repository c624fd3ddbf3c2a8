#pragma once
// JSON documents users hand s3d (profiles, displays, views, manifests, scene descriptions, glTF), parsed in
// one way: from a regular file of bounded size (s3d/input_file.h), with a nesting limit (a 40 KB file nesting
// arrays 20,000 deep overflowed the stack of a recursive reader), and every error naming the file.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "s3d/input_file.h"

namespace s3d {

// Deeper than any document s3d reads needs (glTF extras included), far shallower than a stack overflow.
inline constexpr int kMaxJsonDepth = 128;

// Parses `text`. Throws InputFileError "<name>: not valid JSON: <where and why>" or "<name>: nests deeper than
// 128 levels"; `name` says what the text is, e.g. "display profile 'tv.json'".
inline nlohmann::json parseJsonDocument(const std::string& text, const std::string& name) {
  struct TooDeep {};
  try {
    return nlohmann::json::parse(text, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
      if (depth >= kMaxJsonDepth) throw TooDeep{};  // depth counts from 0 at the top level
      return true;
    });
  } catch (const TooDeep&) {
    throw InputFileError(name + ": nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  } catch (const nlohmann::json::exception& error) {
    // parse_error, and out_of_range for a number beyond double's range (1e400); the library's tag is dropped.
    std::string reason = error.what();
    if (reason.rfind("[json.exception.", 0) == 0 && reason.find("] ") != std::string::npos)
      reason = reason.substr(reason.find("] ") + 2);
    throw InputFileError(name + ": not valid JSON: " + reason);
  }
}

// Reads and parses a JSON file; `what` names its kind ("display profile"). Throws InputFileError.
inline nlohmann::json readJsonDocument(const std::filesystem::path& file, const std::string& what) {
  return parseJsonDocument(readInputFile(file, what), what + " '" + file.string() + "'");
}

}  // namespace s3d
