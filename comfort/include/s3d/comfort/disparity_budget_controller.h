#pragma once
// Per-frame disparity budget control: from the frame's depth range (stereo/depth_range.h, a GPU reduction)
// it chooses maxSeparation and the zero-parallax distance so every pixel's disparity fits the display's
// budget (disparity_budget.h). Parallax (fraction of the width, both eyes) is 2 m (1 - Z / d) for depth d.
//
// Priorities, highest first (all in fitDepthRange and update below):
//  1. The weapon stays at or behind the screen plane: Z <= the weapon's nearest pushed depth.
//  2. Nothing pops out of the screen unless allowed: Z <= the frame's nearest depth (and the crosshair's).
//  3. Every pixel fits the budget, the aimed-at surface and the crosshair included (they are in the frame's
//     depth range, the crosshair's depth is added to it): parallax in [-crossed, +uncrossed].
//  4. The depth impression is as large as the budget allows: the parameters that map the frame's depth
//     range onto `targetShare` of the budget (the rest is the margin smoothing may lag into).
//  5. Smooth: ln m and ln Z follow their targets through a critically damped filter with a bounded change
//     per frame; a rise (a target that asks for more depth) starts only after the target has exceeded the
//     current goal by `hysteresis` for `holdSeconds` (no oscillation at a depth discontinuity, no reversal at a
//     static camera), then follows the target until it stops rising. When the host says the camera recedes
//     from what it sees (`receding`: the depth range grows as a trend, not a flicker), a rise starts at once
//     and is followed with `risingResponseSeconds`, so the bounded rate, not the filter's lag, limits how fast
//     the depth impression comes back. Rules 1-3 override the bound at once when the filter lags (`forced`
//     when that moves a parameter by more than the bound).
//  6. A camera cut (the frame's depth histogram shares less than `cutOverlap` with the previous one, or the
//     host says so) jumps straight to the target, without a ramp.
#include <cstdint>
#include <optional>
#include <vector>

#include "s3d/comfort/critically_damped.h"
#include "s3d/comfort/disparity_budget.h"
#include "s3d/stereo/depth_range.h"

namespace s3d::comfort {

struct DisparityBudgetSettings {
  float targetShare = 0.9f;          // of the budget the target parameters fill
  float responseSeconds = 0.3f;      // time constant of the critically damped filters (ln m, ln Z)
  float maxLogChangePerSecond = 1.5f;  // bound on |d ln m| and |d ln Z| per second (0.05 per frame at 30 fps)
  float hysteresis = 0.05f;          // ln units a depth-increasing target must exceed the goal by
  float holdSeconds = 0.2f;          // ... for this long
  float risingResponseSeconds = 0.05f;  // time constant of a rise while the camera recedes
  float cutOverlap = 0.25f;          // histogram intersection below which a frame is a cut
  float minimumSeparation = 0.0005f;  // fraction of the width per eye
  float maximumSeparation = 0.1f;
  float minimumZeroParallax = 0.05f;  // world units
};

// Throws std::invalid_argument naming the first setting that is NaN or out of range.
void validate(const DisparityBudgetSettings& settings);

// maxSeparation and zero-parallax distance.
struct BudgetParameters {
  float maxSeparation = 0.0f;
  float zeroParallaxDistance = 0.0f;
};

// What one frame brings.
struct BudgetFrameInput {
  float nearest = 0.0f;   // nearest finite depth the frame shows (weapon pushed), world units
  float farthest = 0.0f;  // farthest depth it shows, +inf with sky
  std::optional<float> crosshairDepth;      // must fit too (it may lie in front of every pixel)
  std::optional<float> weaponNearestPushed;  // rule 1; none: no weapon
  std::optional<float> anticipatedNearest;  // a nearer surface expected soon (e.g. ray casts ahead): the
                                            // target eases toward it early, the hard rules ignore it
  bool receding = false;  // the camera moves away from what it sees (e.g. ray casts from ahead reach farther)
  const std::vector<std::uint32_t>* histogram = nullptr;  // for the cut detector (any binning, same every frame)
  bool cut = false;  // the host knows the camera cut
};

// The parameters that map depths [nearest, farthest] onto [-crossed, +uncrossed] * share of `budget`
// (rules 1-4): without negative parallax, Z at the nearest depth and m filling the uncrossed side; with it,
// the range centred so both sides are filled, Z no deeper than the weapon. m is clamped to the settings' range.
BudgetParameters fitDepthRange(float nearest, float farthest, std::optional<float> weaponNearestPushed,
                               const DisparityBudget& budget, bool allowNegativeParallax, double share,
                               const DisparityBudgetSettings& settings);

// Share of the budget's usable span (uncrossed only, or crossed + uncrossed with negative parallax allowed)
// that depths [nearest, farthest] cover at `parameters`, and whether some depth lies outside the budget.
double usedBudgetShare(float nearest, float farthest, const BudgetParameters& parameters, const DisparityBudget& budget,
                       bool allowNegativeParallax);

struct BudgetChoice {
  BudgetParameters parameters;  // what the stereo pass uses this frame
  BudgetParameters target;      // what the frame alone asks for
  double usedShare = 0.0;       // of the budget, by the frame's depth range at `parameters`
  bool cut = false;             // reset without a ramp
  bool forced = false;          // a hard rule (1-3) moved a parameter by more than the per-frame bound
};

// Share of overlap of two histograms, each normalized to its total (1: identical, 0: disjoint).
double histogramOverlap(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b);

class DisparityBudgetController {
 public:
  DisparityBudgetController(const DisparityBudget& budget, bool allowNegativeParallax,
                            const DisparityBudgetSettings& settings = {});

  // One frame of `seconds`; the first frame behaves as a cut.
  BudgetChoice update(const BudgetFrameInput& frame, float seconds);

  // The frame as a depth range (stereo::DepthRangePass's or the host's own: nearest, farthest, sky, and any
  // histogram for the cut detector) plus `hints` (crosshair, weapon, anticipation, cut; its depth fields are
  // replaced). Nothing to choose when the range has no finite pixel and no sky: returns nothing, the state is
  // left as it was. The pushed weapon's nearest point counts as a depth of the frame.
  std::optional<BudgetChoice> update(const stereo::DepthRange& depth, BudgetFrameInput hints, float seconds);

  const DisparityBudget& budget() const { return budget_; }
  bool allowsNegativeParallax() const { return allowNegativeParallax_; }

 private:
  DisparityBudget budget_;
  bool allowNegativeParallax_;
  DisparityBudgetSettings settings_;
  bool started_ = false;
  CriticallyDamped logSeparation_, logZeroParallax_;
  BudgetParameters goal_;          // what the filters follow (ln of it)
  float raiseHeldSeconds_ = 0.0f;  // how long the target has asked for more depth than the goal
  bool rising_ = false;            // a rise has started: the goal follows the target up until it stops rising
  std::vector<std::uint32_t> previousHistogram_;
};

}  // namespace s3d::comfort
