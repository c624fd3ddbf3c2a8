#pragma once
// The disparity budget in the jobs (render, sequence, tune, convert): the GPU depth reduction of the frame,
// the controller's choice applied to the stereo parameters, and its report.json section.
#include <array>
#include <cstdint>
#include <optional>

#include <nlohmann/json.hpp>

#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/disparity_map.h"
#include "s3d/stereo/disparity_map_pass.h"
#include "s3d/stereo/stereo.h"

namespace s3d::app {

// One frame's budget: what the reduction saw, the controller chose, and the GPU time of the reduction.
struct BudgetFrame {
  comfort::DisparityBudgetRule rule = comfort::DisparityBudgetRule::Off;
  comfort::DisparityBudget budget;
  stereo::DepthRange depth;      // the reduction's result (empty when the rule is off)
  comfort::BudgetChoice choice;  // parameters, target, used share, cut, forced
  std::optional<double> reductionGpuMs;
  // For the budget in pixels: the reduced image's width; a job with a guard band sets the output eyes' width
  // (the parallax statistics' pixels), since the reduction ran over the wider rendered frame.
  std::uint32_t imageWidth = 0;
  double spanFraction = 0.0;     // the budget's usable span (uncrossed, plus crossed with pop-out allowed)
};

// The frame's depth-to-parallax mapping as applied (stereo/disparity_map.h) and what its reference took.
struct DisparityMapReport {
  stereo::DisparityMapping mapping = stereo::DisparityMapping::Linear;
  gpu::DisparityMapConstants map = stereo::identityDisparityMap();
  std::optional<double> gpuMs;                     // the mapping dispatch (nonlinear only)
  std::uint32_t referenceLayers = 1;               // renders per reference eye (layered_reference.h)
  std::array<std::uint64_t, 2> unresolvedPixels{};  // left, right: no layer qualified
};

// The passes the mapping needs, made once per job.
class FrameDisparityMapper {
 public:
  explicit FrameDisparityMapper(const vk::Context& context) : reduction_(context), pass_(context) {}
  // Nonlinear: the frame's curve from a GPU reduction of `linearDepth` (vk::kComputeWrite state, left so) and
  // the zero-parallax distance, applied to it in place on the GPU; linear: nothing recorded, the identity.
  DisparityMapReport apply(vk::Context& context, const vk::Image& linearDepth,
                           const stereo::StereoParameters& parameters) const;

 private:
  stereo::DepthRangePass reduction_;
  stereo::DisparityMapPass pass_;
};

// report.json "disparityMapping": {"mapping", "knots": [{"depth", "mappedDepth"}] (depths as linear depth,
// +inf as null), "gpuMs", "referenceLayers", "unresolvedPixels": {"left", "right"}}.
nlohmann::json disparityMapJson(const DisparityMapReport& report);

// What the controller needs besides the depth image.
struct BudgetFrameHints {
  std::optional<float> crosshairDepth;
  std::optional<float> weaponNearestPushed;
  std::optional<float> anticipatedNearest;
  bool cut = false;
  bool receding = false;  // comfort::BudgetFrameInput::receding
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
// rule, from the comfort report), "bulkShare" (the span of the 5th to 95th percentile of the parallax of the
// pixels with finite depth over the budget's usable span, from the comfort report: the depth impression the
// bulk of the scene keeps),
// "cut", "forced", "depth": {"nearest", "farthest", "p01", "p50", "p99"},
// "reductionGpuMs"}; just {"rule": "off", "shareOutside"} when off.
nlohmann::json budgetJson(const BudgetFrame& frame, const comfort::FrameComfort& comfort);

}  // namespace s3d::app
