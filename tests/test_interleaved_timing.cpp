// The schedule of timeInterleaved (which frames run, in which order, and which count), with fake frames that
// log their calls: no GPU and no timing values are involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "s3d/app/interleaved_timing.h"

namespace s3d::app {
namespace {

using std::chrono::milliseconds;

// A series whose n-th frame (from 0) returns `values[n]` (the last value after them) and logs `name`.
TimedFrame loggedFrame(std::vector<std::string>& log, const std::string& name, std::vector<double> values) {
  auto calls = std::make_shared<std::size_t>(0);
  return [&log, name, values, calls]() -> std::optional<double> {
    log.push_back(name);
    const std::size_t n = (*calls)++;
    return values[std::min(n, values.size() - 1)];
  };
}

TEST(InterleavedTiming, RunsWarmUpRoundsBeforeTheTimedRoundsAlternatingTheSeries) {
  std::vector<std::string> log;
  const InterleavedTiming timing = timeInterleaved(
      {loggedFrame(log, "eye", {1.0}), loggedFrame(log, "center", {1.0})}, 3, milliseconds(0), 2);
  EXPECT_EQ(timing.warmUpRounds, 2);
  const std::vector<std::string> expected = {"eye", "center", "eye", "center",                   // warm-up
                                             "eye", "center", "eye", "center", "eye", "center"};  // timed
  EXPECT_EQ(log, expected);
}

TEST(InterleavedTiming, MediansLeaveTheWarmUpFramesOut) {
  // Warm-up frames read slow (a GPU ramping its clocks up): none of them may reach a median.
  std::vector<std::string> log;
  const InterleavedTiming timing =
      timeInterleaved({loggedFrame(log, "eye", {9.0, 9.0, 2.0, 1.0, 3.0}), loggedFrame(log, "center", {8.0, 8.0, 5.0, 4.0, 6.0})},
                      3, milliseconds(0), 2);
  ASSERT_EQ(timing.medians.size(), 2u);
  EXPECT_EQ(timing.medians[0], 2.0);
  EXPECT_EQ(timing.medians[1], 5.0);
}

TEST(InterleavedTiming, WarmsUpForAtLeastTheGivenTime) {
  std::vector<std::string> log;
  const auto start = std::chrono::steady_clock::now();
  const auto frame = [&log]() -> std::optional<double> {
    log.push_back("frame");
    return 1.0;
  };
  const InterleavedTiming timing = timeInterleaved({frame}, 1, milliseconds(20), 0);
  EXPECT_GE(std::chrono::steady_clock::now() - start, milliseconds(20));
  EXPECT_GE(timing.warmUpRounds, 1);
  EXPECT_EQ(log.size(), std::size_t(timing.warmUpRounds) + 1);  // the warm-up rounds, then one timed round
}

TEST(InterleavedTiming, EndsOnTheLastSeriesFrame) {
  // The bench lists the center frame last so the renderer's outputs hold the center view for the stereo settings.
  std::vector<std::string> log;
  (void)timeInterleaved({loggedFrame(log, "eye", {1.0}), loggedFrame(log, "center", {1.0})}, 4, milliseconds(0), 1);
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log.back(), "center");
}

TEST(InterleavedTiming, AMissingTimestampLeavesOnlyThatSampleOut) {
  // A device without timestamps returns none: its series' median is empty, the other series' unaffected.
  std::vector<std::string> log;
  const auto untimed = []() -> std::optional<double> { return std::nullopt; };
  const InterleavedTiming timing = timeInterleaved({untimed, loggedFrame(log, "center", {4.0})}, 3, milliseconds(0), 1);
  EXPECT_FALSE(timing.medians[0].has_value());
  EXPECT_EQ(timing.medians[1], 4.0);
}

TEST(InterleavedTiming, RefusesAnEmptySchedule) {
  const auto frame = []() -> std::optional<double> { return 1.0; };
  EXPECT_THROW((void)timeInterleaved({}, 3, milliseconds(0)), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 0, milliseconds(0)), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame, TimedFrame{}}, 3, milliseconds(0)), std::invalid_argument);
  EXPECT_THROW((void)timeInterleaved({frame}, 3, milliseconds(0), -1), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::app
