// The schedule of timeInterleaved (which frames run, in which order, which count, when warm-up ends), with fake
// frames that log their calls and move a fake clock: no GPU and no real time are involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "s3d/stereo/interleaved_timing.h"

namespace s3d::stereo {
namespace {

using std::chrono::milliseconds;
using TimePoint = std::chrono::steady_clock::time_point;

// A fake clock that the frames move by the time they report.
struct FakeClock {
  TimePoint time{};
  SteadyNow now() {
    return [this] { return time; };
  }
};

// A series whose n-th frame (from 0) returns `values[n]` (the last value after them), logs `name` and moves the
// clock by the returned milliseconds.
TimedFrame loggedFrame(std::vector<std::string>& log, FakeClock& clock, const std::string& name, std::vector<double> values) {
  auto calls = std::make_shared<std::size_t>(0);
  return [&log, &clock, name, values, calls]() -> std::optional<double> {
    log.push_back(name);
    const double ms = values[std::min((*calls)++, values.size() - 1)];
    clock.time += std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double, std::milli>(ms));
    return ms;
  };
}

WarmUp roundsOnly(int rounds) {  // no time minimum: warm-up ends on the rounds and the first settled window
  WarmUp warmUp;
  warmUp.minimum = milliseconds(0);
  warmUp.window = milliseconds(1);
  warmUp.minRounds = rounds;
  return warmUp;
}

TEST(InterleavedTiming, RunsWarmUpRoundsBeforeTheTimedRoundsAlternatingTheSeries) {
  std::vector<std::string> log;
  FakeClock clock;
  const InterleavedTiming timing = timeInterleaved(
      {loggedFrame(log, clock, "eye", {1.0}), loggedFrame(log, clock, "center", {1.0})}, 3, roundsOnly(2), clock.now());
  EXPECT_EQ(timing.warmUpRounds, 2);
  const std::vector<std::string> expected = {"eye", "center", "eye", "center",                   // warm-up
                                             "eye", "center", "eye", "center", "eye", "center"};  // timed
  EXPECT_EQ(log, expected);
}

TEST(InterleavedTiming, MediansLeaveTheWarmUpFramesOut) {
  // Warm-up frames read slow (a GPU raising its clocks): none of them may reach a median.
  std::vector<std::string> log;
  FakeClock clock;
  const InterleavedTiming timing =
      timeInterleaved({loggedFrame(log, clock, "eye", {9.0, 9.0, 2.0, 1.0, 3.0}),
                       loggedFrame(log, clock, "center", {8.0, 8.0, 5.0, 4.0, 6.0})},
                      3, roundsOnly(2), clock.now());
  ASSERT_EQ(timing.warmUpRounds, 2);
  ASSERT_EQ(timing.medians.size(), 2u);
  EXPECT_EQ(timing.medians[0], 2.0);
  EXPECT_EQ(timing.medians[1], 5.0);
}

TEST(InterleavedTiming, WarmsUpForAtLeastTheMinimumTime) {
  // Frames already at their speed: warm-up ends at the minimum (10 frames of 50 ms = 500 ms), not before.
  std::vector<std::string> log;
  FakeClock clock;
  const InterleavedTiming timing = timeInterleaved({loggedFrame(log, clock, "frame", {50.0})}, 1, WarmUp{}, clock.now());
  EXPECT_EQ(timing.warmUpRounds, 10);
  EXPECT_TRUE(timing.settled);
  EXPECT_DOUBLE_EQ(timing.warmUpMs, 500.0);
  EXPECT_EQ(log.size(), 11u);  // the warm-up rounds, then one timed round
}

TEST(InterleavedTiming, KeepsWarmingUpWhileTheFramesGetFaster) {
  // A GPU raising its clocks in steps of 200 ms (as an H200 did after idling): 25, 20, 15 and 12 ms frames for
  // 200 ms each, then 10 ms frames. Warm-up runs on past the 500 ms minimum until a 250 ms window is no faster
  // than the one before, and no frame of the ramp is timed.
  std::vector<double> ramp;
  for (double ms : {25.0, 20.0, 15.0, 12.5})
    for (int i = 0; i < int(200.0 / ms); ++i) ramp.push_back(ms);
  ramp.push_back(10.0);
  std::vector<std::string> log;
  FakeClock clock;
  const InterleavedTiming timing = timeInterleaved({loggedFrame(log, clock, "frame", ramp)}, 5, WarmUp{}, clock.now());
  EXPECT_TRUE(timing.settled);
  EXPECT_GE(timing.warmUpMs, 800.0 + 250.0);  // the ramp, then a window of fast frames at least
  EXPECT_EQ(timing.medians[0], 10.0);
}

TEST(InterleavedTiming, KeepsWarmingUpWhileTheFramesGetSlower) {
  // A GPU lowering its clocks at a low duty cycle and raising them again: 10 ms frames for 500 ms, 30 ms frames
  // for 300 ms, then 10 ms frames. A window slower than the one before does not end the warm-up.
  std::vector<double> dip(50, 10.0);
  dip.insert(dip.end(), 10, 30.0);
  dip.push_back(10.0);
  std::vector<std::string> log;
  FakeClock clock;
  WarmUp warmUp;
  warmUp.minimum = milliseconds(750);
  const InterleavedTiming timing = timeInterleaved({loggedFrame(log, clock, "frame", dip)}, 5, warmUp, clock.now());
  EXPECT_TRUE(timing.settled);
  EXPECT_GE(timing.warmUpMs, 800.0 + 250.0);  // past the dip, then a window of fast frames at least
  EXPECT_EQ(timing.medians[0], 10.0);
}

TEST(InterleavedTiming, GivesUpSettlingAtTheMaximum) {
  // Frames 0.5 % faster each (over 2 % faster each window) without end: warm-up stops at the maximum and says
  // it did not settle.
  std::vector<double> falling = {20.0};
  while (falling.size() < 1000) falling.push_back(falling.back() * 0.995);
  std::vector<std::string> log;
  FakeClock clock;
  WarmUp warmUp;
  warmUp.maximum = milliseconds(2000);
  const InterleavedTiming timing = timeInterleaved({loggedFrame(log, clock, "frame", falling)}, 1, warmUp, clock.now());
  EXPECT_FALSE(timing.settled);
  EXPECT_GE(timing.warmUpMs, 2000.0);
  EXPECT_LT(timing.warmUpMs, 2000.0 + 20.0);  // within one frame of it
}

TEST(InterleavedTiming, EndsOnTheLastSeriesFrame) {
  // The bench lists the center frame last so the renderer's outputs hold the center view for the stereo settings.
  std::vector<std::string> log;
  FakeClock clock;
  (void)timeInterleaved({loggedFrame(log, clock, "eye", {1.0}), loggedFrame(log, clock, "center", {1.0})}, 4,
                        roundsOnly(1), clock.now());
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log.back(), "center");
}

TEST(InterleavedTiming, WithoutTimestampsWarmsUpForTheMinimumAndTimesTheOtherSeries) {
  // A device without timestamps cannot tell when frames settle: warm-up ends at the minimum; the untimed
  // series' median is empty, the other series' unaffected.
  std::vector<std::string> log;
  FakeClock clock;
  const auto untimed = [&clock]() -> std::optional<double> {
    clock.time += milliseconds(10);
    return std::nullopt;
  };
  const InterleavedTiming timing =
      timeInterleaved({untimed, loggedFrame(log, clock, "center", {40.0})}, 3, WarmUp{}, clock.now());
  EXPECT_EQ(timing.warmUpRounds, 10);  // 10 rounds of 50 ms
  EXPECT_FALSE(timing.medians[0].has_value());
  EXPECT_EQ(timing.medians[1], 40.0);
}

TEST(InterleavedTiming, RefusesAnEmptyOrInconsistentSchedule) {
  const auto frame = []() -> std::optional<double> { return 1.0; };
  WarmUp noWindow;
  noWindow.window = milliseconds(0);
  WarmUp maximumBelowMinimum;
  maximumBelowMinimum.maximum = milliseconds(100);
  WarmUp badTolerance;
  badTolerance.tolerance = 1.0;
  WarmUp negativeRounds;
  negativeRounds.minRounds = -1;
  EXPECT_THROW((void)timeInterleaved({}, 3), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 0), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame, TimedFrame{}}, 3), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 3, noWindow), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 3, maximumBelowMinimum), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 3, badTolerance), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 3, negativeRounds), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::stereo
