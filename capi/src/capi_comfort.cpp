// The comfort C structs converted, for inputs capi_validate.h has checked.
#include "capi_comfort.h"

#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "capi_checks.h"
#include "s3d/number_text.h"

namespace s3d::capi {

stereo::StereoParameters toCpp(const s3d_stereo_parameters& p) {
  stereo::StereoParameters result;
  result.maxSeparation = p.max_separation;
  result.zeroParallaxDistance = p.zero_parallax_distance;
  result.edgeCrop = p.edge_crop;
  result.method = p.method == S3D_METHOD_SEED ? stereo::StereoMethod::Seed : stereo::StereoMethod::Search;
  result.searchTaps = p.search_taps;
  result.weaponDepthOffset = p.weapon_depth_offset;
  result.weaponDepthScale = p.weapon_depth_scale;
  stereo::validate(result);  // a backstop: the C checks cover every rule it has
  return result;
}

s3d_stereo_parameters toC(const stereo::StereoParameters& p) {
  return {p.maxSeparation, p.zeroParallaxDistance, p.edgeCrop,
          p.method == stereo::StereoMethod::Seed ? S3D_METHOD_SEED : S3D_METHOD_SEARCH,
          p.searchTaps, p.weaponDepthOffset, p.weaponDepthScale};
}

namespace {

s3d_hud_element_state toC(const comfort::HudElementState& s) {
  return {s.depth, s.parallaxPx, s.fadesBehindWeapon ? 1 : 0};
}

}  // namespace

comfort::FrameComfortInput toCpp(const s3d_frame_comfort_input& input) {
  comfort::FrameComfortInput cpp;
  cpp.camera = {glm::vec3(input.camera_position[0], input.camera_position[1], input.camera_position[2]),
                glm::vec3(input.camera_aim[0], input.camera_aim[1], input.camera_aim[2]), input.camera_near};
  if (input.ray_cast) {
    const s3d_ray_cast cast = input.ray_cast;
    void* user = input.ray_cast_user;
    cpp.rayCast = [cast, user](glm::vec3 origin, glm::vec3 direction, float maxDistance) -> std::optional<float> {
      const float o[3] = {origin.x, origin.y, origin.z}, d[3] = {direction.x, direction.y, direction.z};
      float distance = 0.0f;
      if (!cast(user, o, d, maxDistance, &distance)) return std::nullopt;
      if (!(distance >= 0.0f) || !std::isfinite(distance))
        fail("s3d_frame_comfort_input.ray_cast returned distance " + numberText(distance) +
             "; a hit's distance must be >= 0 and finite");
      return distance;
    };
  }
  cpp.parameters = toCpp(input.parameters);
  cpp.width = input.width;
  cpp.crosshairDistance = input.crosshair_distance;
  cpp.crosshairMargin = input.crosshair_margin;
  cpp.weapon = {input.weapon_pixels, input.weapon_nearest_depth, input.weapon_farthest_depth};
  if (input.has_nearest_world_depth) cpp.nearestWorldDepth = input.nearest_world_depth;
  for (uint32_t i = 0; i < input.hud_count; ++i) cpp.hud.push_back({"hud" + std::to_string(i), input.hud_depths[i]});
  cpp.allowNegativeParallax = input.allow_negative_parallax != 0;
  return cpp;
}

comfort::DisplayProfile toCpp(const s3d_display& display) {
  if (display.field_of_view_degrees != 0.0f)
    return comfort::headMountedDisplay("host", display.viewing_distance_meters, display.field_of_view_degrees,
                                       display.interocular_meters);
  comfort::DisplayProfile profile;
  profile.name = "host";
  profile.screenWidthMeters = display.screen_width_meters;
  profile.viewingDistanceMeters = display.viewing_distance_meters;
  profile.interocularMeters = display.interocular_meters;
  return profile;
}

void toC(const comfort::FrameComfortState& state, std::uint32_t hudCount, s3d_frame_comfort_state* out,
         s3d_hud_element_state* hudStates) {
  out->parameters = toC(state.parameters);
  out->weapon_pushed = state.weaponPushed;
  out->zero_parallax_limited = state.zeroParallaxLimited;
  out->crosshair_hit_world = state.crosshairHitWorld;
  out->crosshair = toC(state.crosshair);
  for (std::uint32_t i = 0; i < hudCount; ++i) hudStates[i] = toC(state.hud[i]);
}

s3d_budget_choice toC(const std::optional<comfort::BudgetChoice>& choice, const comfort::DisparityBudget& budget) {
  if (!choice) return {};
  const comfort::BudgetChoice& c = *choice;
  return {1, c.parameters.maxSeparation, c.parameters.zeroParallaxDistance, c.target.maxSeparation,
          c.target.zeroParallaxDistance, float(c.usedShare), c.cut ? 1 : 0, c.forced ? 1 : 0,
          float(budget.crossedFraction), float(budget.uncrossedFraction)};
}

}  // namespace s3d::capi
