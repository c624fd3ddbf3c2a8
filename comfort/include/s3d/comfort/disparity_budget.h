#pragma once
// The disparity a display allows: the on-screen parallax (right-eye minus left-eye image position) whose
// angular disparity (display_profile.h's disparityArcminutes) stays within a limit, by default the 1-degree
// rule. Flat screens and head-mounted displays alike: an HMD's virtual screen lies at its focal distance and
// spans its field of view (headMountedDisplay), so the same vergence geometry applies.
//
// The 1-degree rule is the only limit: Shibata et al. 2011's zone of comfort is not in s3d because its
// constants could not be verified against the paper (docs/DESIGN.md "Comfort report").
#include <cstdint>
#include <string>

#include "s3d/comfort/display_profile.h"

namespace s3d::comfort {

enum class DisparityBudgetRule {
  Off,        // parameters as given, nothing fitted
  OneDegree,  // every pixel's |disparity| within 60 arcminutes
};

const char* disparityBudgetRuleName(DisparityBudgetRule rule);        // "off", "1deg"
DisparityBudgetRule parseDisparityBudgetRule(const std::string& name);  // throws std::invalid_argument listing them

inline constexpr double kOneDegreeArcmin = 60.0;

// On-screen parallax in metres whose disparity is `arcmin` (positive: uncrossed, behind the screen; negative:
// crossed): the inverse of disparityArcminutes. Behind the screen it is capped at the interocular distance
// (the eyes never diverge), so a limit larger than the screen's own vergence angle gives parallel lines of sight.
double parallaxMetersForDisparity(const DisplayProfile& display, double arcmin);

struct DisparityBudget {
  double limitArcmin = kOneDegreeArcmin;
  double uncrossedMeters = 0.0;  // largest parallax behind the screen (> 0)
  double crossedMeters = 0.0;    // largest parallax in front of it, as a magnitude (> 0)
  // As fractions of the image width (the stereo pass's unit: total parallax 2 m (1 - zpp / depth)).
  double uncrossedFraction = 0.0;
  double crossedFraction = 0.0;
  // In pixels of an image `imageWidthPx` wide.
  double uncrossedPx(std::uint32_t imageWidthPx) const { return uncrossedFraction * imageWidthPx; }
  double crossedPx(std::uint32_t imageWidthPx) const { return crossedFraction * imageWidthPx; }
};

// The budget of `display` for |disparity| <= limitArcmin (validates the display; limit in (0, 600]).
DisparityBudget disparityBudget(const DisplayProfile& display, double limitArcmin = kOneDegreeArcmin);

}  // namespace s3d::comfort
