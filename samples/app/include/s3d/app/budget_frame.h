#pragma once
// The disparity budget in the jobs (render, sequence, tune, convert): the GPU depth reduction of the frame,
// the controller's choice applied to the stereo parameters, and its report.json section.
#include <cstdint>
#include <optional>

#include <nlohmann/json.hpp>

#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/stereo.h"

namespace s3d::app {

// One frame's budget: what the reduction saw, the controller chose, and the GPU time of the reduction.
struct BudgetFrame {
  comfort::DisparityBudgetRule rule = comfort::DisparityBudgetRule::Off;
  comfort::DisparityBudget budget;
  stereo::DepthRange depth;      // the reduction's result (empty when the rule is off)
  comfort::BudgetChoice choice;  // parameters, target, used share, cut, forced
  std::optional<double> reductionGpuMs;
  std::uint32_t imageWidth = 0;  // for the budget in pixels
};

// What the controller needs besides the depth image.
struct BudgetFrameHints {
  std::optional<float> crosshairDepth;
  std::optional<float> weaponNearestPushed;
  std::optional<float> anticipatedNearest;
  bool cut = false;
};

// With the rule on: reduces `linearDepth` (GPU, vk::kComputeWrite state, left so), lets `controller` choose
// and writes maxSeparation and zeroParallaxDistance into `parameters`. Off: returns the rule only.
BudgetFrame applyDisparityBudget(vk::Context& context, const stereo::DepthRangePass& pass,
                                 comfort::DisparityBudgetController* controller, const vk::Image& linearDepth,
                                 const BudgetFrameHints& hints, float seconds, stereo::StereoParameters& parameters);

// The weapon's nearest point as the stereo pass sees it (pushed), if there is a weapon.
std::optional<float> weaponNearestPushed(const stereo::StereoParameters& parameters,
                                         const std::optional<glm::vec2>& weaponDepths);

// report.json "disparityBudget": {"rule", "limitArcmin", "budgetPx": {"crossed", "uncrossed"}, "chosen":
// {"maxSeparation", "zeroParallaxDistance"}, "target": {...}, "usedShare", "shareOutside" (pixels beyond the
// rule, from the comfort report), "cut", "forced", "depth": {"nearest", "farthest", "p01", "p50", "p99"},
// "reductionGpuMs"}; just {"rule": "off", "shareOutside"} when off.
nlohmann::json budgetJson(const BudgetFrame& frame, const comfort::FrameComfort& comfort);

}  // namespace s3d::app
