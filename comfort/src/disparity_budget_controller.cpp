#include "s3d/comfort/disparity_budget_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "s3d/number_text.h"

namespace s3d::comfort {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// The hard rules keep this share of the budget: float rounding of the parallax must not tip a pixel over.
constexpr double kHardShare = 0.998;

void requireIn(float value, float low, float high, const char* name) {
  if (!(value >= low && value <= high))
    throw std::invalid_argument(std::string("disparity budget control: ") + name + " must be in [" +
                                numberText(low) + ", " + numberText(high) + "] (got " + numberText(value) + ")");
}

double inverse(float depth) { return std::isinf(depth) ? 0.0 : 1.0 / double(depth); }

// The largest m at zero-parallax distance z that keeps depths [nearest, farthest] within share of the budget.
double largestSeparation(double z, float nearest, float farthest, const DisparityBudget& budget, double share) {
  double m = std::numeric_limits<double>::infinity();
  const double farSpan = 1.0 - z * inverse(farthest);  // parallax at the far end is 2 m farSpan
  if (farSpan > 0.0) m = share * budget.uncrossedFraction / (2.0 * farSpan);
  const double nearSpan = z * inverse(nearest) - 1.0;  // parallax at the near end is -2 m nearSpan
  if (nearSpan > 0.0) m = std::min(m, share * budget.crossedFraction / (2.0 * nearSpan));
  return m;
}

}  // namespace

void validate(const DisparityBudgetSettings& s) {
  requireIn(s.targetShare, 0.05f, 0.99f, "targetShare");
  requireIn(s.responseSeconds, 1e-3f, 10.0f, "responseSeconds");
  requireIn(s.maxLogChangePerSecond, 1e-3f, 100.0f, "maxLogChangePerSecond");
  requireIn(s.hysteresis, 0.0f, 1.0f, "hysteresis");
  requireIn(s.holdSeconds, 0.0f, 10.0f, "holdSeconds");
  requireIn(s.risingResponseSeconds, 1e-3f, 10.0f, "risingResponseSeconds");
  requireIn(s.cutOverlap, 0.0f, 1.0f, "cutOverlap");
  requireIn(s.minimumSeparation, 1e-5f, 0.25f, "minimumSeparation");
  requireIn(s.maximumSeparation, s.minimumSeparation, 0.25f, "maximumSeparation");
  requireIn(s.minimumZeroParallax, 1e-4f, 1e4f, "minimumZeroParallax");
}

BudgetParameters fitDepthRange(float nearest, float farthest, std::optional<float> weaponNearestPushed,
                               const DisparityBudget& budget, bool allowNegativeParallax, double share,
                               const DisparityBudgetSettings& settings) {
  const float weaponLimit = weaponNearestPushed.value_or(kInfinity);
  double z = 0.0;
  if (std::isinf(nearest)) {
    z = std::isinf(weaponLimit) ? 1.0 : weaponLimit;  // sky only: every pixel has parallax 2 m whatever z is
  } else if (!allowNegativeParallax) {
    z = std::min(nearest, weaponLimit);  // rules 1 and 2; m then fills the uncrossed side
  } else {
    // Rule 3 with both sides filled: 2 m (1 - z a) = -c and 2 m (1 - z b) = u.
    const double a = inverse(nearest), b = inverse(farthest);
    const double u = share * budget.uncrossedFraction, c = share * budget.crossedFraction;
    z = a > b ? (u + c) / ((u + (u + c) * b / (a - b)) * (a - b)) : double(nearest);
    z = std::min(z, double(weaponLimit));  // rule 1
  }
  z = std::max(z, double(settings.minimumZeroParallax));
  const double m = largestSeparation(z, nearest, farthest, budget, share);
  return {float(std::clamp(m, double(settings.minimumSeparation), double(settings.maximumSeparation))), float(z)};
}

double usedBudgetShare(float nearest, float farthest, const BudgetParameters& p, const DisparityBudget& budget,
                       bool allowNegativeParallax) {
  if (std::isinf(nearest)) return 0.0;
  auto parallax = [&](float depth) { return 2.0 * p.maxSeparation * (1.0 - p.zeroParallaxDistance * inverse(depth)); };
  const double span = budget.uncrossedFraction + (allowNegativeParallax ? budget.crossedFraction : 0.0);
  return (parallax(farthest) - parallax(nearest)) / span;
}

double histogramOverlap(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size()) return 0.0;
  double totalA = 0.0, totalB = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    totalA += a[i];
    totalB += b[i];
  }
  if (totalA == 0.0 || totalB == 0.0) return totalA == totalB ? 1.0 : 0.0;
  double overlap = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) overlap += std::min(a[i] / totalA, b[i] / totalB);
  return overlap;
}

DisparityBudgetController::DisparityBudgetController(const DisparityBudget& budget, bool allowNegativeParallax,
                                                     const DisparityBudgetSettings& settings)
    : budget_(budget), allowNegativeParallax_(allowNegativeParallax), settings_(settings) {
  validate(settings);
  if (!(budget.uncrossedFraction > 0.0) || !(budget.crossedFraction > 0.0))
    throw std::invalid_argument("disparity budget control: the budget must be positive on both sides");
}

BudgetChoice DisparityBudgetController::update(const BudgetFrameInput& frame, float seconds) {
  if (!(seconds > 0.0f) || !std::isfinite(seconds))
    throw std::invalid_argument("disparity budget control: frame time must be positive and finite");
  if (!(frame.nearest > 0.0f) || !(frame.farthest >= frame.nearest))
    throw std::invalid_argument("disparity budget control: the depth range must be positive and ordered");
  // The crosshair counts when it may lie in front of the screen; otherwise the HUD holds it on the plane.
  float nearest = frame.nearest;
  if (allowNegativeParallax_ && frame.crosshairDepth) nearest = std::min(nearest, *frame.crosshairDepth);
  BudgetChoice choice;
  choice.target = fitDepthRange(std::min(nearest, frame.anticipatedNearest.value_or(kInfinity)), frame.farthest,
                                frame.weaponNearestPushed, budget_, allowNegativeParallax_, settings_.targetShare,
                                settings_);

  const float previousLogZ = logZeroParallax_.value, previousLogM = logSeparation_.value;
  const float bound = settings_.maxLogChangePerSecond * seconds;
  const bool histogramCut = frame.histogram && !previousHistogram_.empty() &&
                            histogramOverlap(previousHistogram_, *frame.histogram) < settings_.cutOverlap;
  if (frame.histogram) previousHistogram_ = *frame.histogram;
  choice.cut = !started_ || frame.cut || histogramCut;
  started_ = true;
  if (choice.cut) {
    goal_ = choice.target;
    raiseHeldSeconds_ = 0.0f;
    rising_ = false;
    logSeparation_.hold(std::log(goal_.maxSeparation));
    logZeroParallax_.hold(std::log(goal_.zeroParallaxDistance));
  } else {
    // Rule 5: less depth at once, more depth only once the target has asked for it long enough (at once while
    // the camera recedes), then all the way up.
    const bool asksMore = std::log(choice.target.maxSeparation) > std::log(goal_.maxSeparation) + settings_.hysteresis ||
                          std::log(choice.target.zeroParallaxDistance) >
                              std::log(goal_.zeroParallaxDistance) + settings_.hysteresis;
    raiseHeldSeconds_ = asksMore ? raiseHeldSeconds_ + seconds : 0.0f;
    if (asksMore && (raiseHeldSeconds_ >= settings_.holdSeconds || frame.receding))
      rising_ = true;
    else if (choice.target.maxSeparation <= goal_.maxSeparation &&
             choice.target.zeroParallaxDistance <= goal_.zeroParallaxDistance)
      rising_ = false;  // the target stopped rising
    if (rising_ || choice.target.maxSeparation < goal_.maxSeparation) goal_.maxSeparation = choice.target.maxSeparation;
    if (rising_ || choice.target.zeroParallaxDistance < goal_.zeroParallaxDistance)
      goal_.zeroParallaxDistance = choice.target.zeroParallaxDistance;
    auto response = [&](const CriticallyDamped& filter, float goal) {
      return rising_ && frame.receding && goal > filter.value ? settings_.risingResponseSeconds : settings_.responseSeconds;
    };
    const float logM = std::log(goal_.maxSeparation), logZ = std::log(goal_.zeroParallaxDistance);
    logSeparation_.step(logM, seconds, response(logSeparation_, logM), bound);
    logZeroParallax_.step(logZ, seconds, response(logZeroParallax_, logZ), bound);
  }

  // Rules 1-3 over whatever the filters say.
  float zLimit = frame.weaponNearestPushed.value_or(kInfinity);
  if (!allowNegativeParallax_) zLimit = std::min(zLimit, nearest);
  if (std::exp(logZeroParallax_.value) > zLimit) {
    logZeroParallax_.hold(std::log(zLimit));
    choice.forced = !choice.cut && previousLogZ - logZeroParallax_.value > bound * 1.0001f;
  }
  const double z = std::min(double(std::exp(logZeroParallax_.value)), double(zLimit));
  const double mLimit = largestSeparation(z, nearest, frame.farthest, budget_, kHardShare);
  if (std::exp(double(logSeparation_.value)) > mLimit) {
    logSeparation_.hold(float(std::log(mLimit)));
    choice.forced = choice.forced || (!choice.cut && previousLogM - logSeparation_.value > bound * 1.0001f);
  }
  choice.parameters = {float(std::min(double(std::exp(logSeparation_.value)), mLimit)), float(z)};
  if (choice.cut && !choice.forced && double(goal_.maxSeparation) <= mLimit && goal_.zeroParallaxDistance <= zLimit)
    choice.parameters = goal_;  // exactly the target (exp(log(x)) may differ from x in the last bit)
  choice.usedShare = usedBudgetShare(nearest, frame.farthest, choice.parameters, budget_, allowNegativeParallax_);
  return choice;
}

std::optional<BudgetChoice> DisparityBudgetController::update(const stereo::DepthRange& depth, BudgetFrameInput hints,
                                                             float seconds) {
  if (!depth.hasFinite() && depth.skyPixels == 0) return std::nullopt;
  hints.nearest = depth.hasFinite() ? depth.nearest : kInfinity;
  hints.farthest = depth.farthestShown();
  if (hints.weaponNearestPushed) {  // a range reduced without the weapon, or with it unpushed: the weapon as shown
    hints.nearest = std::min(hints.nearest, *hints.weaponNearestPushed);
    hints.farthest = std::max(hints.farthest, *hints.weaponNearestPushed);
  }
  hints.histogram = depth.bins.empty() ? nullptr : &depth.bins;
  return update(hints, seconds);
}

}  // namespace s3d::comfort
