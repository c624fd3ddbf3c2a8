// The C API's host comfort frame over comfort::HostComfortFrame: the C structs checked field by field (named as C
// spells them), converted, the state written back.
#include <string>

#include "capi_comfort.h"
#include "capi_common.h"
#include "capi_stereo_frame.h"
#include "capi_validate.h"
#include "s3d/comfort/host_comfort_frame.h"

struct s3d_host_comfort_frame_t {
  s3d::comfort::HostComfortFrame frame;
  // Where the frame's calls are, so a call out of order is refused in the C API's terms.
  enum class Step { Recorded, Updated, MasksRecorded } step = Step::Recorded;
};

namespace {

using s3d::capi::fail;
using s3d::capi::guarded;
using s3d::capi::present;
using s3d::capi::requireNotNull;

// The frame's fields that must agree with the description, and the budget's timing.
void validate(const s3d_host_comfort_input& input, const s3d::comfort::HostComfortFrameDesc& desc) {
  if (input.frame_slot >= desc.framesInFlight)
    fail("s3d_host_comfort_input.frame_slot " + std::to_string(input.frame_slot) + " is outside [0, " +
         std::to_string(desc.framesInFlight) + ")");
  s3d::capi::validate(input.frame);
  if (input.frame.width != desc.stereo.width)
    fail("s3d_host_comfort_input.frame.width is " + std::to_string(input.frame.width) + ", the frame's width " +
         std::to_string(desc.stereo.width));
  if ((input.frame.allow_negative_parallax != 0) != desc.allowNegativeParallax)
    fail("s3d_host_comfort_input.frame.allow_negative_parallax is " + std::to_string(input.frame.allow_negative_parallax) +
         ", the frame was created with allow_negative_parallax " + std::to_string(int(desc.allowNegativeParallax)));
  s3d::capi::requirePositive(input.frame_seconds, {"s3d_host_comfort_input", "frame_seconds"});
  if (input.has_anticipated_nearest)
    s3d::capi::requirePositive(input.anticipated_nearest, {"s3d_host_comfort_input", "anticipated_nearest"});
}

s3d::comfort::HostComfortInput toCpp(const s3d_host_comfort_input& input) {
  const s3d::comfort::FrameComfortInput frame = s3d::capi::toCpp(input.frame);
  s3d::comfort::HostComfortInput cpp;
  cpp.frameSlot = input.frame_slot;
  cpp.camera = frame.camera;
  cpp.rayCast = frame.rayCast;
  cpp.parameters = frame.parameters;
  cpp.crosshairDistance = frame.crosshairDistance;
  cpp.crosshairMargin = frame.crosshairMargin;
  cpp.weapon = frame.weapon;
  cpp.nearestWorldDepth = frame.nearestWorldDepth;
  cpp.hud = frame.hud;
  cpp.seconds = input.frame_seconds;
  cpp.cut = input.camera_cut != 0;
  cpp.receding = input.receding != 0;
  if (input.has_anticipated_nearest) cpp.anticipatedNearest = input.anticipated_nearest;
  return cpp;
}

void requireStep(const s3d_host_comfort_frame_t& frame, s3d_host_comfort_frame_t::Step step, const char* call,
                 const char* before) {
  if (frame.step != step) fail(std::string(call) + " needs this frame's " + before + " first");
}

// The dispatch as the stereo frame checks it, with eye views refused: the comfort rules choose the parameters.
s3d::stereo::StereoFrameDispatch checkedDispatch(const s3d::comfort::HostComfortFrame& frame,
                                                 const s3d_stereo_frame_dispatch& dispatch) {
  if (dispatch.eye_views)
    fail("s3d_stereo_frame_dispatch.eye_views must be NULL for a host comfort frame: its comfort rules choose "
         "max_separation and zero_parallax_distance (give the views' as s3d_host_comfort_input.frame.parameters)");
  return s3d::capi::checkedDispatch(frame.stereoFrame(), dispatch);
}

}  // namespace

extern "C" {

s3d_result s3d_host_comfort_frame_create(s3d_context context, const s3d_host_comfort_frame_desc* desc,
                                         s3d_host_comfort_frame* out) {
  return guarded([&] {
    requireNotNull(context, {"context"});
    requireNotNull(desc, {"desc"});
    requireNotNull(out, {"out"});
    s3d::comfort::HostComfortFrameDesc cpp;
    cpp.stereo = s3d::capi::checkedDesc(desc->stereo, context->maxImageDimension2D);
    if (desc->display) {
      s3d::capi::validate(*desc->display);
      cpp.budget = s3d::comfort::disparityBudget(s3d::capi::toCpp(*desc->display));
    }
    cpp.allowNegativeParallax = desc->allow_negative_parallax != 0;
    if (desc->frames_in_flight == 0) fail("s3d_host_comfort_frame_desc.frames_in_flight is 0; it must be at least 1");
    cpp.framesInFlight = desc->frames_in_flight;
    *out = new s3d_host_comfort_frame_t{s3d::comfort::HostComfortFrame(context->context, cpp)};
  });
}

void s3d_host_comfort_frame_destroy(s3d_host_comfort_frame frame) { delete frame; }

VkFormat s3d_host_comfort_frame_eye_format(s3d_host_comfort_frame frame) {
  return present(frame, "frame") ? frame->frame.stereoFrame().eyeFormat() : VK_FORMAT_UNDEFINED;
}

s3d_result s3d_host_comfort_frame_update(s3d_host_comfort_frame frame, const s3d_host_comfort_input* input,
                                         s3d_frame_comfort_state* out, s3d_hud_element_state* hud_states,
                                         s3d_budget_choice* choice) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    requireNotNull(input, {"input"});
    requireNotNull(out, {"out"});
    validate(*input, frame->frame.desc());
    if (input->frame.hud_count > 0) requireNotNull(hud_states, {"hud_states"});
    const s3d::comfort::FrameComfortState& state = frame->frame.update(toCpp(*input));
    frame->step = s3d_host_comfort_frame_t::Step::Updated;
    s3d::capi::toC(state, input->frame.hud_count, out, hud_states);
    if (choice)
      *choice = frame->frame.desc().budget ? s3d::capi::toC(state.budget, *frame->frame.desc().budget) : s3d_budget_choice{};
  });
}

s3d_result s3d_host_comfort_frame_record(s3d_host_comfort_frame frame, VkCommandBuffer cmd,
                                         const s3d_stereo_frame_dispatch* dispatch) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    requireNotNull(dispatch, {"dispatch"});
    if (frame->frame.desc().stereo.method == s3d::stereo::StereoMethod::Hybrid)
      fail("s3d_host_comfort_frame_record: a S3D_METHOD_HYBRID frame records with "
           "s3d_host_comfort_frame_record_hybrid_masks and s3d_host_comfort_frame_record_hybrid_composite");
    requireStep(*frame, s3d_host_comfort_frame_t::Step::Updated, "s3d_host_comfort_frame_record",
                "s3d_host_comfort_frame_update");
    frame->frame.record(cmd, checkedDispatch(frame->frame, *dispatch));
    frame->step = s3d_host_comfort_frame_t::Step::Recorded;
  });
}

s3d_result s3d_host_comfort_frame_record_hybrid_masks(s3d_host_comfort_frame frame, VkCommandBuffer cmd,
                                                      const s3d_stereo_frame_dispatch* dispatch,
                                                      s3d_eye_cameras* cameras) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    requireNotNull(dispatch, {"dispatch"});
    requireNotNull(cameras, {"cameras"});
    s3d::capi::requireHybrid(frame->frame.stereoFrame(), "s3d_host_comfort_frame_record_hybrid_masks");
    s3d::capi::validateHybridMasks(*dispatch);
    requireStep(*frame, s3d_host_comfort_frame_t::Step::Updated, "s3d_host_comfort_frame_record_hybrid_masks",
                "s3d_host_comfort_frame_update");
    s3d::capi::toC(frame->frame.recordHybridMasks(cmd, checkedDispatch(frame->frame, *dispatch)), cameras);
    frame->step = s3d_host_comfort_frame_t::Step::MasksRecorded;
  });
}

s3d_result s3d_host_comfort_frame_record_hybrid_composite(s3d_host_comfort_frame frame, VkCommandBuffer cmd,
                                                          const s3d_stereo_frame_dispatch* dispatch) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    requireNotNull(dispatch, {"dispatch"});
    s3d::capi::requireHybrid(frame->frame.stereoFrame(), "s3d_host_comfort_frame_record_hybrid_composite");
    requireStep(*frame, s3d_host_comfort_frame_t::Step::MasksRecorded, "s3d_host_comfort_frame_record_hybrid_composite",
                "s3d_host_comfort_frame_record_hybrid_masks");
    frame->frame.recordHybridComposite(cmd, checkedDispatch(frame->frame, *dispatch));
    frame->step = s3d_host_comfort_frame_t::Step::Recorded;
  });
}

}  // extern "C"
