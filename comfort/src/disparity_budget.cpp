#include "s3d/comfort/disparity_budget.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "s3d/number_text.h"

namespace s3d::comfort {
namespace {

constexpr double kArcminutesPerRadian = 180.0 * 60.0 / 3.14159265358979323846;

}  // namespace

const char* disparityBudgetRuleName(DisparityBudgetRule rule) {
  return rule == DisparityBudgetRule::Off ? "off" : "1deg";
}

DisparityBudgetRule parseDisparityBudgetRule(const std::string& name) {
  if (name == "off") return DisparityBudgetRule::Off;
  if (name == "1deg") return DisparityBudgetRule::OneDegree;
  throw std::invalid_argument("unknown disparity budget '" + name + "' (choices: off, 1deg)");
}

double parallaxMetersForDisparity(const DisplayProfile& display, double arcmin) {
  const double e = display.interocularMeters, v = display.viewingDistanceMeters;
  const double screenVergence = 2.0 * std::atan(e / (2.0 * v));
  // disparity = screen vergence - point vergence, point vergence = 2 atan((e - P) / (2 v)).
  const double pointVergence = screenVergence - arcmin / kArcminutesPerRadian;
  if (pointVergence <= 0.0) return e;  // at or beyond parallel: the eyes would diverge
  return e - 2.0 * v * std::tan(0.5 * pointVergence);
}

DisparityBudget disparityBudget(const DisplayProfile& display, double limitArcmin) {
  validate(display);
  if (!(limitArcmin > 0.0) || !(limitArcmin <= 600.0))
    throw std::invalid_argument("disparity budget: the limit must be in (0, 600] arcminutes (got " +
                                numberText(limitArcmin) + ")");
  DisparityBudget budget;
  budget.limitArcmin = limitArcmin;
  budget.uncrossedMeters = parallaxMetersForDisparity(display, limitArcmin);
  budget.crossedMeters = -parallaxMetersForDisparity(display, -limitArcmin);
  budget.uncrossedFraction = budget.uncrossedMeters / double(display.screenWidthMeters);
  budget.crossedFraction = budget.crossedMeters / double(display.screenWidthMeters);
  return budget;
}

}  // namespace s3d::comfort
