#pragma once
// Timing GPU frames that a bench compares with each other (a reference eye and the center frame): every series
// is measured in the same rounds, one frame of each back to back, right after untimed warm-up rounds. Series
// timed one after another, the first right after host-side work and a scene upload, read unlike each other on
// an H200 (the first up to twice the second) although both frames cost the same.
#include <chrono>
#include <functional>
#include <optional>
#include <vector>

namespace s3d::app {

// One frame of a series: records and submits it, waits, and returns its GPU milliseconds (empty when the device
// gives no timestamps).
using TimedFrame = std::function<std::optional<double>()>;

struct InterleavedTiming {
  std::vector<std::optional<double>> medians;  // per series: the median of its timed frames (empty when none had a time)
  int warmUpRounds = 0;                        // untimed rounds run first
};

// Rounds of every frame in `series` order: untimed rounds until `warmUp` has passed and at least `minWarmUpRounds`
// ran, then `repeat` timed rounds. The last frame run is the last series' (a renderer's outputs hold its view).
// Throws std::invalid_argument for no series, an empty frame, repeat < 1 or minWarmUpRounds < 0.
InterleavedTiming timeInterleaved(const std::vector<TimedFrame>& series, int repeat, std::chrono::milliseconds warmUp,
                                  int minWarmUpRounds = 1);

}  // namespace s3d::app
