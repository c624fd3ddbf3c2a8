#pragma once
// Reading one JSON object of a profile strictly: every key must be known, every number finite and within
// its range, and every error names the key by its full path ("stereo.maxSeparation").
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace s3d::comfort::detail {

struct Range {
  double low, high;
  bool lowOpen = false, highOpen = false;
};

class ObjectReader {
 public:
  // Throws std::invalid_argument unless `object` is a JSON object. `path` prefixes the keys in messages.
  ObjectReader(const nlohmann::json& object, std::string path);

  // Each reads the key when present (absent: `value` keeps its default) and remembers it as known.
  void number(const char* key, float& value, Range range);
  void integer(const char* key, int& value, int low, int high);
  void boolean(const char* key, bool& value);
  void choice(const char* key, std::string& value, const std::vector<std::string>& choices);
  // The raw value, or nullptr when absent; the key counts as known.
  const nlohmann::json* find(const char* key);
  std::string pathOf(const char* key) const;

  // Throws std::invalid_argument naming the first key that no call above asked for, listing the known ones.
  void finish() const;

 private:
  const nlohmann::json& object_;
  std::string path_;
  std::vector<std::string> known_;
};

// Parses a JSON file. Throws std::runtime_error "<what> '<file>': ..." when it cannot be read or is not JSON.
nlohmann::json readJsonFile(const std::filesystem::path& file, const char* what);
// Writes "<file>.tmp" and renames it over `file`: readers never see a partial file. Throws std::runtime_error.
void writeTextAtomically(const std::filesystem::path& file, const std::string& text, const char* what);

// The shortest decimal that reads back as the same float (0.03f is written 0.03, not 0.029999999329447746).
double shortest(float value);

// "0.5 is outside [0, 0.25]"-style text for a range.
std::string describe(Range range);

}  // namespace s3d::comfort::detail
