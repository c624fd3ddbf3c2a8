#pragma once
// The per-frame rules on the stereo parameters of a frame from s3d's tools or a host: the disparity budget (the
// GPU depth reduction, the controller's choice applied), the depth-to-parallax mapping, and the no-negative-parallax
// rules (the weapon pushed to the screen plane, the zero-parallax distance held at the nearest surface).
#include <array>
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/image.h"
#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/disparity_map.h"
#include "s3d/stereo/disparity_map_pass.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

// One frame's budget: what the reduction saw, the controller chose, and the GPU time of the reduction.
struct BudgetFrame {
  DisparityBudgetRule rule = DisparityBudgetRule::Off;
  DisparityBudget budget;
  stereo::DepthRange depth;      // the reduction's result (empty when the rule is off)
  BudgetChoice choice;  // parameters, target, used share, cut, forced
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
  explicit FrameDisparityMapper(vk::Context& context) : reduction_(context), pass_(context) {}
  // Nonlinear: the frame's curve from a GPU reduction of `linearDepth` (vk::kComputeWrite state, left so) and
  // the zero-parallax distance, applied to it in place on the GPU; linear: nothing recorded, the identity.
  DisparityMapReport apply(vk::Context& context, const vk::Image& linearDepth,
                           const stereo::StereoParameters& parameters) const;

 private:
  stereo::DepthRangePass reduction_;
  stereo::DisparityMapPass pass_;
};

// What the controller needs besides the depth image.
struct BudgetFrameHints {
  std::optional<float> crosshairDepth;
  std::optional<float> weaponNearestPushed;
  std::optional<float> anticipatedNearest;
  bool cut = false;
  bool receding = false;  // BudgetFrameInput::receding
};

// With the rule on: reduces `linearDepth` (GPU, vk::kComputeWrite state, left so), lets `controller` choose
// and writes maxSeparation and zeroParallaxDistance into `parameters`. Off: returns the rule only.
BudgetFrame applyDisparityBudget(vk::Context& context, const stereo::DepthRangePass& pass,
                                 DisparityBudgetController* controller, const vk::Image& linearDepth,
                                 const BudgetFrameHints& hints, float seconds, stereo::StereoParameters& parameters);

// The weapon's nearest point as the stereo pass sees it (pushed), if there is a weapon.
std::optional<float> weaponNearestPushed(const stereo::StereoParameters& parameters,
                                         const std::optional<glm::vec2>& weaponDepths);

// The renderer's weapon depth range (renderer::firstPersonDepthRange; none: no weapon in view) as the weapon mask
// statistics the comfort rules take.
WeaponMaskStats weaponMaskStats(const std::optional<glm::vec2>& weaponDepths);

// Before the center view: without negative parallax allowed, the weapon push reaches at least the screen
// plane (weaponPushForFrame).
stereo::StereoParameters pushWeaponUnlessNegativeParallaxAllowed(stereo::StereoParameters parameters,
                                                                 const std::optional<glm::vec2>& weaponDepths,
                                                                 bool allowNegativeParallax);

// Once the frame's depth is known: without negative parallax allowed, the zero-parallax distance is held at
// the nearest surface (nearestDepth), so every pixel gets zero or positive parallax. Returns whether it was lowered.
bool holdZeroParallaxAtNearestDepth(stereo::StereoParameters& parameters, const DepthImage& stereoDepth,
                                    bool allowNegativeParallax);

}  // namespace s3d::comfort
