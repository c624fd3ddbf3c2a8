#pragma once
// Where tests/data/scenes/fetch-scenes puts the public glTF scenes: $S3D_SCENE_CACHE, else
// ${XDG_CACHE_HOME:-~/.cache}/s3d/scenes. Tests and benchmarks that need them look there.
#include <cstdlib>
#include <filesystem>

namespace s3d::test {

inline std::filesystem::path sceneCache() {
  if (const char* cache = std::getenv("S3D_SCENE_CACHE"); cache && *cache) return cache;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "s3d" / "scenes";
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home ? home : "/nonexistent") / ".cache" / "s3d" / "scenes";
}

}  // namespace s3d::test
