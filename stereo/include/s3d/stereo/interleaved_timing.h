#pragma once
// Timing GPU frames that a bench compares with each other (a reference eye and the center frame): every series
// is measured in the same rounds, one frame of each back to back, right after untimed warm-up rounds that last
// until the frames run at a steady speed. A GPU idle through seconds of host-side work drops its clocks and takes
// frames to raise them again; a series timed during that ramp reads too high (docs/RESULTS.md, its opening notes).
#include <chrono>
#include <functional>
#include <optional>
#include <vector>

namespace s3d::stereo {

// One frame of a series: records and submits it, waits, and returns its GPU milliseconds (empty when the device
// gives no timestamps).
using TimedFrame = std::function<std::optional<double>()>;

// When warm-up ends: untimed rounds (at least one) for at least `minimum` and `minRounds`, then until a `window`
// of rounds runs as fast as the window before it (medians of the rounds' summed GPU times, within `tolerance`
// either way: clocks rising or falling go on), or `maximum` has passed. Windows count from the first round, so a
// GPU already at steady clocks stops at `minimum`.
struct WarmUp {
  std::chrono::milliseconds minimum{500};
  std::chrono::milliseconds window{250};  // longer than the steps a GPU takes its clocks up in
  double tolerance = 0.02;
  std::chrono::milliseconds maximum{4000};
  int minRounds = 1;
};

struct InterleavedTiming {
  std::vector<std::optional<double>> medians;  // per series: the median of its timed frames (empty when none had a time)
  int warmUpRounds = 0;                        // untimed rounds run first
  double warmUpMs = 0.0;                       // how long they took (host clock)
  bool settled = false;                        // the last warm-up window ran as fast as the one before
};

using SteadyNow = std::function<std::chrono::steady_clock::time_point()>;

// Rounds of every frame in `series` order: warm-up rounds as `warmUp` says, then `repeat` timed rounds. The last
// frame run is the last series' (a renderer's outputs hold its view). `now` is the clock warm-up is measured on.
// Throws std::invalid_argument for no series, an empty frame, repeat < 1, minRounds < 0, a window that is not
// positive, a tolerance outside [0, 1) or a maximum below the minimum.
InterleavedTiming timeInterleaved(const std::vector<TimedFrame>& series, int repeat, const WarmUp& warmUp = {},
                                  const SteadyNow& now = std::chrono::steady_clock::now);

}  // namespace s3d::stereo
