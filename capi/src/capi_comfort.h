#pragma once
// The comfort C structs as the comfort library takes them and back (shared by the frame comfort call and the host
// comfort frame). Inputs must have passed capi_validate.h's checks.
#include <cstdint>
#include <optional>

#include "s3d/comfort/disparity_budget.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/s3d.h"
#include "s3d/stereo/stereo.h"

namespace s3d::capi {

stereo::StereoParameters toCpp(const s3d_stereo_parameters& parameters);
s3d_stereo_parameters toC(const stereo::StereoParameters& parameters);
// Everything but the budget; the ray cast calls the host's callback, a bad distance refused naming ray_cast.
comfort::FrameComfortInput toCpp(const s3d_frame_comfort_input& input);
comfort::DisplayProfile toCpp(const s3d_display& display);
// The state into `out` and `hudCount` HUD element states (the input's order).
void toC(const comfort::FrameComfortState& state, std::uint32_t hudCount, s3d_frame_comfort_state* out,
         s3d_hud_element_state* hudStates);
// What the controller chose (chosen 0 without a choice), with the budget's fractions.
s3d_budget_choice toC(const std::optional<comfort::BudgetChoice>& choice, const comfort::DisparityBudget& budget);

}  // namespace s3d::capi
