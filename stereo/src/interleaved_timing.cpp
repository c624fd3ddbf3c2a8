#include "s3d/stereo/interleaved_timing.h"

#include <cmath>
#include <stdexcept>

#include "s3d/stereo/synthesis.h"

namespace s3d::stereo {

InterleavedTiming timeInterleaved(const std::vector<TimedFrame>& series, int repeat, const WarmUp& warmUp,
                                  const SteadyNow& now) {
  if (series.empty()) throw std::invalid_argument("timeInterleaved: no series to time");
  for (const TimedFrame& frame : series)
    if (!frame) throw std::invalid_argument("timeInterleaved: a series has no frame");
  if (repeat < 1) throw std::invalid_argument("timeInterleaved: repeat must be at least 1");
  if (warmUp.minRounds < 0) throw std::invalid_argument("timeInterleaved: minRounds must not be negative");
  if (warmUp.window.count() <= 0) throw std::invalid_argument("timeInterleaved: the warm-up window must be positive");
  if (!(warmUp.tolerance >= 0.0 && warmUp.tolerance < 1.0))
    throw std::invalid_argument("timeInterleaved: the warm-up tolerance must be in [0, 1)");
  if (warmUp.maximum < warmUp.minimum) throw std::invalid_argument("timeInterleaved: the warm-up maximum is below its minimum");

  // One round: every series' frame; its summed GPU time (empty when a frame gave none).
  auto runRound = [&]() -> std::optional<double> {
    std::optional<double> sum = 0.0;
    for (const TimedFrame& frame : series) {
      const std::optional<double> ms = frame();
      sum = sum && ms ? std::optional(*sum + *ms) : std::nullopt;
    }
    return sum;
  };

  InterleavedTiming timing;
  const auto start = now();
  auto windowEnd = start + warmUp.window;
  std::vector<double> window;
  std::optional<double> previousWindowMs;
  bool timesMissing = false;
  while (true) {
    const std::optional<double> roundMs = runRound();
    ++timing.warmUpRounds;
    if (roundMs) window.push_back(*roundMs);
    else timesMissing = true;
    const auto at = now();
    const bool pastMinimum = at - start >= warmUp.minimum && timing.warmUpRounds >= warmUp.minRounds;
    if (at - start >= warmUp.maximum && timing.warmUpRounds >= warmUp.minRounds) break;
    if (at < windowEnd) continue;
    // A window closed: compare its median round with the previous window's.
    const std::optional<double> windowMs = medianMs(std::move(window));
    window.clear();
    while (windowEnd <= at) windowEnd += warmUp.window;
    timing.settled = windowMs && previousWindowMs && std::abs(*windowMs - *previousWindowMs) <= *previousWindowMs * warmUp.tolerance;
    previousWindowMs = windowMs;
    if (pastMinimum && (timing.settled || timesMissing)) break;  // without timestamps nothing can settle
  }
  timing.warmUpMs = std::chrono::duration<double, std::milli>(now() - start).count();

  std::vector<std::vector<double>> samples(series.size());
  for (int round = 0; round < repeat; ++round)
    for (std::size_t i = 0; i < series.size(); ++i)
      if (const std::optional<double> ms = series[i]()) samples[i].push_back(*ms);
  for (std::vector<double>& present : samples) timing.medians.push_back(stereo::medianMs(std::move(present)));
  return timing;
}

}  // namespace s3d::stereo
