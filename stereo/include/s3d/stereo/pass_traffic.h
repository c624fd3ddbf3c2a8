#pragma once
// The stereo pass's memory traffic per frame, a model counted from its shaders: what a method setting moves, so
// methods and kernels compare in bytes as well as in time (`s3d bench`'s traffic table).
#include <cstdint>

#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// What the stereo pass moves per frame, counted from the shaders (shaders/). Per-pixel kernel: per
// interior pixel and eye the depth imageLoads (4 B each: seed/search tapCount, iterative startTapCount + 2 x
// iterations), two color imageLoads (4 B, the horizontal filter) and one imageStore (4 B); a cropped pixel only
// stores both eyes. Row tiles: each tile's run plus its margin each side, a depth and a color texel per column,
// once (shared memory serves every tap); fetches of near surfaces beyond the margin are not counted.
struct StereoTraffic {
  bool rowTiles = false;  // the kernel the parameters run on
  std::uint64_t bytesRead = 0;
  std::uint64_t bytesWritten = 0;
  std::uint64_t compulsoryBytes = 0;  // each input texel read once and each eye written once: 16 B per pixel
  std::uint64_t total() const { return bytesRead + bytesWritten; }
};
// cpuDevice: the kernel Auto picks on a CPU device (usesRowTiles).
StereoTraffic stereoPassTraffic(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height,
                                bool cpuDevice = false);

}  // namespace s3d::stereo
