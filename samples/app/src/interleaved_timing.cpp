#include "s3d/app/interleaved_timing.h"

#include <stdexcept>

#include "s3d/stereo/synthesis.h"

namespace s3d::app {

InterleavedTiming timeInterleaved(const std::vector<TimedFrame>& series, int repeat, std::chrono::milliseconds warmUp,
                                  int minWarmUpRounds) {
  if (series.empty()) throw std::invalid_argument("timeInterleaved: no series to time");
  for (const TimedFrame& frame : series)
    if (!frame) throw std::invalid_argument("timeInterleaved: a series has no frame");
  if (repeat < 1) throw std::invalid_argument("timeInterleaved: repeat must be at least 1");
  if (minWarmUpRounds < 0) throw std::invalid_argument("timeInterleaved: minWarmUpRounds must not be negative");

  InterleavedTiming timing;
  const auto start = std::chrono::steady_clock::now();
  while (timing.warmUpRounds < minWarmUpRounds || std::chrono::steady_clock::now() - start < warmUp) {
    for (const TimedFrame& frame : series) (void)frame();
    ++timing.warmUpRounds;
  }
  std::vector<std::vector<double>> samples(series.size());
  for (int round = 0; round < repeat; ++round)
    for (std::size_t i = 0; i < series.size(); ++i)
      if (const std::optional<double> ms = series[i]()) samples[i].push_back(*ms);
  for (std::vector<double>& present : samples) timing.medians.push_back(stereo::medianMs(std::move(present)));
  return timing;
}

}  // namespace s3d::app
