// The disparity budget per display (the 1-degree rule) and the per-frame controller that fits each frame's
// depth range into it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "s3d/comfort/disparity_budget.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/stereo/depth_range.h"

namespace s3d::comfort {
namespace {

constexpr float kSky = std::numeric_limits<float>::infinity();

TEST(DisparityBudget, FlatScreensGiveTheHandComputedParallax) {
  // P = e - 2 v tan((2 atan(e / 2v) - 1 deg) / 2), by hand (double precision, then / screen width):
  // tv55 (1.2176 m at 2.5 m): 43.636 mm behind, 43.646 mm in front = 3.584 % of the width;
  // monitor27 (0.5977 m at 0.7 m): 12.238 mm = 2.047 %. Tolerance 2 um: the profile holds floats.
  const DisparityBudget tv = disparityBudget(builtInDisplayProfile("tv55"));
  EXPECT_NEAR(tv.uncrossedMeters, 0.0436365, 2e-6);
  EXPECT_NEAR(tv.crossedMeters, 0.0436461, 2e-6);
  EXPECT_NEAR(tv.uncrossedFraction, 0.0358384, 2e-6);
  const DisparityBudget monitor = disparityBudget(builtInDisplayProfile("monitor27"));
  EXPECT_NEAR(monitor.uncrossedMeters, 0.0122375, 2e-6);
  EXPECT_NEAR(monitor.uncrossedFraction, 0.0204735, 4e-6);
  EXPECT_NEAR(monitor.uncrossedPx(1920), 0.0204735 * 1920, 1e-2);
}

TEST(DisparityBudget, HeadMountedDisplaysUseTheirFocalDistanceAndFieldOfView) {
  // 90 degrees focused at 1.3 m: a 2.6 m virtual screen at 1.3 m: 22.698 mm = 0.873 % of the width.
  const DisparityBudget hmd = disparityBudget(builtInDisplayProfile("hmd"));
  EXPECT_NEAR(hmd.uncrossedMeters, 0.0226984, 2e-6);
  EXPECT_NEAR(hmd.crossedMeters, 0.0227080, 2e-6);
  EXPECT_NEAR(hmd.uncrossedFraction, 0.0087301, 2e-6);
}

TEST(DisparityBudget, ItsLimitsHaveExactlyTheRuleDisparity) {
  for (const std::string& name : builtInDisplayProfileNames()) {
    const DisplayProfile display = builtInDisplayProfile(name);
    const DisparityBudget budget = disparityBudget(display);
    EXPECT_NEAR(disparityArcminutes(display, budget.uncrossedMeters), 60.0, 1e-9) << name;
    EXPECT_NEAR(disparityArcminutes(display, -budget.crossedMeters), -60.0, 1e-9) << name;
  }
}

TEST(DisparityBudget, BehindTheScreenItNeverMakesTheEyesDiverge) {
  // At 50 m the screen's vergence angle (4.3 arcmin) is below 1 degree: the budget stops at the eye distance.
  DisplayProfile far = builtInDisplayProfile("tv55");
  far.viewingDistanceMeters = 50.0f;
  EXPECT_DOUBLE_EQ(disparityBudget(far).uncrossedMeters, double(far.interocularMeters));
}

TEST(DisparityBudget, RuleNamesParseAndUnknownOnesAreRefused) {
  EXPECT_EQ(parseDisparityBudgetRule("1deg"), DisparityBudgetRule::OneDegree);
  EXPECT_EQ(parseDisparityBudgetRule("off"), DisparityBudgetRule::Off);
  EXPECT_THROW(parseDisparityBudgetRule("2deg"), std::invalid_argument);
}

// Total parallax (fraction of the width) of depth d at the chosen parameters.
double parallaxOf(const BudgetParameters& p, float depth) {
  return 2.0 * p.maxSeparation * (1.0 - double(p.zeroParallaxDistance) / double(depth));
}

BudgetFrameInput frameOf(float nearest, float farthest) {
  BudgetFrameInput frame;
  frame.nearest = nearest;
  frame.farthest = farthest;
  return frame;
}

constexpr float kFrameSeconds = 1.0f / 30.0f;

TEST(DisparityBudgetController, AFrameWiderThanTheBudgetGetsParametersThatFitIt) {
  // 0.3 m to sky on a monitor: the default 2 % separation would put the sky at 4 % (budget 2.05 %).
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("monitor27"));
  DisparityBudgetController controller(budget, false);
  const BudgetChoice choice = controller.update(frameOf(0.3f, kSky), kFrameSeconds);
  EXPECT_LE(parallaxOf(choice.parameters, kSky), budget.uncrossedFraction);
  EXPECT_GE(parallaxOf(choice.parameters, 0.3f), -1e-9);
  EXPECT_GE(choice.usedShare, 0.8);
  EXPECT_LE(choice.usedShare, 1.0);
}

TEST(DisparityBudgetController, NothingPopsOutUnlessAllowed) {
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  const BudgetChoice choice = controller.update(frameOf(0.7f, 40.0f), kFrameSeconds);
  EXPECT_LE(choice.parameters.zeroParallaxDistance, 0.7f);
  EXPECT_GE(parallaxOf(choice.parameters, 0.7f), -1e-7);
}

TEST(DisparityBudgetController, WithPopOutAllowedBothSidesOfTheBudgetAreFilled) {
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, true);
  const BudgetChoice choice = controller.update(frameOf(0.7f, 40.0f), kFrameSeconds);
  EXPECT_NEAR(parallaxOf(choice.parameters, 0.7f), -0.9 * budget.crossedFraction, 1e-5);
  EXPECT_NEAR(parallaxOf(choice.parameters, 40.0f), 0.9 * budget.uncrossedFraction, 1e-5);
}

TEST(DisparityBudgetController, TheWeaponNeverEndsInFrontOfTheScreen) {
  // Pop-out allowed would centre the range around ~1.3 m; the weapon's pushed nearest point at 1 m holds it.
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, true);
  BudgetFrameInput frame = frameOf(0.7f, 40.0f);
  frame.weaponNearestPushed = 1.0f;
  const BudgetChoice choice = controller.update(frame, kFrameSeconds);
  EXPECT_LE(choice.parameters.zeroParallaxDistance, 1.0f);
  EXPECT_GE(parallaxOf(choice.parameters, 1.0f), -1e-7);
  EXPECT_GE(parallaxOf(choice.parameters, 0.7f), -budget.crossedFraction);
  EXPECT_LE(parallaxOf(choice.parameters, 40.0f), budget.uncrossedFraction);
}

TEST(DisparityBudgetController, ACrosshairInFrontOfEverythingStaysWithinTheBudget) {
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, true);
  BudgetFrameInput frame = frameOf(2.0f, kSky);
  frame.crosshairDepth = 0.4f;
  const BudgetChoice choice = controller.update(frame, kFrameSeconds);
  EXPECT_GE(parallaxOf(choice.parameters, 0.4f), -budget.crossedFraction);
  EXPECT_LE(parallaxOf(choice.parameters, kSky), budget.uncrossedFraction);
}

TEST(DisparityBudgetController, ANarrowDepthRangeGetsMoreSeparationThanAWideOne) {
  // Indoors (0.5 to 5 m) the whole uncrossed budget goes to a small depth range: more depth impression.
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController indoors(budget, false), outdoors(budget, false);
  const BudgetChoice narrow = indoors.update(frameOf(0.5f, 5.0f), kFrameSeconds);
  const BudgetChoice wide = outdoors.update(frameOf(0.5f, kSky), kFrameSeconds);
  EXPECT_GT(narrow.parameters.maxSeparation, wide.parameters.maxSeparation);
  EXPECT_NEAR(narrow.usedShare, 0.9, 1e-5);
  EXPECT_NEAR(wide.usedShare, 0.9, 1e-5);
}

// Frame-to-frame changes of ln m and ln Z over a run of frames.
struct ChoiceRun {
  std::vector<BudgetChoice> choices;
  int reversals(bool separation) const {
    int count = 0;
    double previousStep = 0.0;
    for (std::size_t i = 1; i < choices.size(); ++i) {
      const auto value = [&](std::size_t k) {
        return std::log(separation ? choices[k].parameters.maxSeparation : choices[k].parameters.zeroParallaxDistance);
      };
      const double step = value(i) - value(i - 1);
      if (std::abs(step) < 1e-6) continue;
      if (step * previousStep < 0.0) ++count;
      previousStep = step;
    }
    return count;
  }
};

TEST(DisparityBudgetController, AStaticCameraConvergesAndStays) {
  // The first frame takes the target of an indoor view; the view then widens to the sky and stays.
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  ChoiceRun run;
  run.choices.push_back(controller.update(frameOf(1.0f, 6.0f), kFrameSeconds));
  for (int i = 0; i < 120; ++i) run.choices.push_back(controller.update(frameOf(1.0f, kSky), kFrameSeconds));
  EXPECT_EQ(run.reversals(true), 0);
  EXPECT_EQ(run.reversals(false), 0);
  const BudgetChoice& last = run.choices.back();
  EXPECT_NEAR(last.parameters.maxSeparation, last.target.maxSeparation, 1e-6);
  EXPECT_NEAR(last.usedShare, 0.9, 1e-4);
  // Stays: the last 30 frames are identical.
  for (std::size_t i = run.choices.size() - 30; i < run.choices.size(); ++i)
    EXPECT_EQ(run.choices[i].parameters.maxSeparation, last.parameters.maxSeparation);
}

TEST(DisparityBudgetController, ChangesStayWithinTheBoundPerFrame) {
  // Sky to indoors and back: the target of m moves by a factor of 8; ln m may move 1.5 / s * 1/30 s per frame.
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  ChoiceRun run;
  run.choices.push_back(controller.update(frameOf(1.0f, kSky), kFrameSeconds));
  for (int i = 0; i < 90; ++i) run.choices.push_back(controller.update(frameOf(1.0f, 1.2f), kFrameSeconds));
  for (int i = 0; i < 90; ++i) run.choices.push_back(controller.update(frameOf(1.0f, kSky), kFrameSeconds));
  const double bound = 1.5 * kFrameSeconds;
  for (std::size_t i = 1; i < run.choices.size(); ++i) {
    if (run.choices[i].forced) continue;  // a hard rule may cut m at once (to the sky: counted, tested below)
    EXPECT_LE(std::abs(std::log(run.choices[i].parameters.maxSeparation / run.choices[i - 1].parameters.maxSeparation)),
              bound + 1e-6)
        << "frame " << i;
  }
  EXPECT_GT(run.choices[91].parameters.maxSeparation, 0.0f);
}

TEST(DisparityBudgetController, AHardRuleOverridesTheBoundAndSaysSo) {
  // Indoors at a large separation, then the sky appears: m must drop at once to keep the sky within budget.
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  for (int i = 0; i < 60; ++i) controller.update(frameOf(1.0f, 1.5f), kFrameSeconds);
  BudgetFrameInput sky = frameOf(1.0f, kSky);
  const BudgetChoice choice = controller.update(sky, kFrameSeconds);
  EXPECT_TRUE(choice.forced);
  EXPECT_FALSE(choice.cut);
  EXPECT_LE(parallaxOf(choice.parameters, kSky), budget.uncrossedFraction);
}

TEST(DisparityBudgetController, ADepthDiscontinuityDoesNotMakeItOscillate) {
  // A thin pole flickers in and out of view every other frame (nearest 0.8 m or 3 m, far 30 m).
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  ChoiceRun run;
  for (int i = 0; i < 120; ++i) run.choices.push_back(controller.update(frameOf(i % 2 ? 0.8f : 3.0f, 30.0f), kFrameSeconds));
  EXPECT_EQ(run.reversals(true), 0);
  EXPECT_EQ(run.reversals(false), 0);
  for (const BudgetChoice& choice : run.choices) EXPECT_LE(parallaxOf(choice.parameters, 30.0f), budget.uncrossedFraction);
}

TEST(DisparityBudgetController, WhileTheCameraRecedesMoreDepthIsFollowedAtTheBoundWithoutTheHold) {
  // Walking back from a wall: the nearest depth recedes by 10 % per frame at 30 fps (ln 0.095, above the
  // 0.05 bound). Without `receding` the rise waits for the 0.2 s hold; with it ln Z rises from the next frame
  // on, at the bound, never above the nearest depth.
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  for (const bool receding : {false, true}) {
    DisparityBudgetController controller(budget, false);
    float nearest = 0.4f;
    BudgetChoice previous = controller.update(frameOf(nearest, kSky), kFrameSeconds);
    int framesWaited = 0;
    for (int i = 0; i < 20; ++i) {
      nearest *= 1.1f;
      BudgetFrameInput frame = frameOf(nearest, kSky);
      frame.receding = receding;
      const BudgetChoice choice = controller.update(frame, kFrameSeconds);
      const double step = std::log(choice.parameters.zeroParallaxDistance / previous.parameters.zeroParallaxDistance);
      EXPECT_LE(step, 1.5 * kFrameSeconds + 1e-6) << i;
      EXPECT_LE(choice.parameters.zeroParallaxDistance, nearest) << i;
      if (step < 1e-6) ++framesWaited;
      if (receding && i > 0) {
        EXPECT_NEAR(step, 1.5 * kFrameSeconds, 1e-4) << i;  // at the bound
      }
      previous = choice;
    }
    if (receding) {
      EXPECT_LE(framesWaited, 1);
    } else {
      EXPECT_GE(framesWaited, 5);  // the hold (0.2 s = 6 frames) before the first rise
    }
  }
}

TEST(DisparityBudgetController, ACutResetsWithoutARamp) {
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  std::vector<std::uint32_t> indoors(8, 0), outdoors(8, 0);
  indoors[1] = 100;
  outdoors[6] = 100;
  BudgetFrameInput before = frameOf(0.5f, 2.0f);
  before.histogram = &indoors;
  for (int i = 0; i < 30; ++i) controller.update(before, kFrameSeconds);
  BudgetFrameInput after = frameOf(20.0f, kSky);
  after.histogram = &outdoors;
  const BudgetChoice choice = controller.update(after, kFrameSeconds);
  EXPECT_TRUE(choice.cut);
  EXPECT_EQ(choice.parameters.maxSeparation, choice.target.maxSeparation);
  EXPECT_EQ(choice.parameters.zeroParallaxDistance, choice.target.zeroParallaxDistance);
}

TEST(DisparityBudgetController, ASurfaceExpectedAheadLowersTheTargetEarly) {
  const DisparityBudget budget = disparityBudget(builtInDisplayProfile("tv55"));
  DisparityBudgetController controller(budget, false);
  BudgetFrameInput frame = frameOf(2.0f, kSky);
  frame.anticipatedNearest = 0.6f;
  const BudgetChoice choice = controller.update(frame, kFrameSeconds);
  EXPECT_FLOAT_EQ(choice.target.zeroParallaxDistance, 0.6f);
  EXPECT_LE(parallaxOf(choice.parameters, kSky), budget.uncrossedFraction);
}

TEST(HistogramOverlap, IdenticalIsOneAndDisjointIsZero) {
  EXPECT_DOUBLE_EQ(histogramOverlap({1, 2, 3}, {2, 4, 6}), 1.0);
  EXPECT_DOUBLE_EQ(histogramOverlap({1, 0, 0}, {0, 0, 5}), 0.0);
  EXPECT_DOUBLE_EQ(histogramOverlap({1, 1, 0}, {0, 1, 1}), 0.5);
}

}  // namespace
}  // namespace s3d::comfort
