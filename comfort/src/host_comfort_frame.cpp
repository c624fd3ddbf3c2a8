#include "s3d/comfort/host_comfort_frame.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "s3d/number_text.h"

namespace s3d::comfort {
namespace {

[[noreturn]] void refuse(const std::string& field, const std::string& problem) {
  throw std::invalid_argument("HostComfortInput." + field + " " + problem);
}

void requirePositive(float value, const std::string& field) {
  if (!(value > 0.0f) || !std::isfinite(value)) refuse(field, numberText(value) + " must be positive and finite");
}

void validate(const HostComfortInput& input, std::uint32_t framesInFlight) {
  if (input.frameSlot >= framesInFlight)
    refuse("frameSlot", std::to_string(input.frameSlot) + " is outside [0, " + std::to_string(framesInFlight) + ")");
  const float m = input.parameters.maxSeparation;
  if (!(m >= 0.0f && m <= 0.25f)) refuse("parameters.maxSeparation", numberText(m) + " is outside [0, 0.25]");
  requirePositive(input.parameters.zeroParallaxDistance, "parameters.zeroParallaxDistance");
  requirePositive(input.seconds, "seconds");
  requirePositive(input.crosshairDistance, "crosshairDistance");
  if (!(input.crosshairMargin >= 0.0f) || !std::isfinite(input.crosshairMargin))
    refuse("crosshairMargin", numberText(input.crosshairMargin) + " must be >= 0 and finite");
  if (input.nearestWorldDepth) requirePositive(*input.nearestWorldDepth, "nearestWorldDepth");
  if (input.anticipatedNearest) requirePositive(*input.anticipatedNearest, "anticipatedNearest");
  for (std::size_t i = 0; i < input.hud.size(); ++i)
    requirePositive(input.hud[i].depth, "hud[" + std::to_string(i) + "].depth");
  if (input.weapon.pixels > 0) {
    requirePositive(input.weapon.nearestDepth, "weapon.nearestDepth");
    if (!(input.weapon.farthestDepth >= input.weapon.nearestDepth) || !std::isfinite(input.weapon.farthestDepth))
      refuse("weapon.farthestDepth", numberText(input.weapon.farthestDepth) + " is below weapon.nearestDepth");
  }
}

std::uint32_t checkedFramesInFlight(const HostComfortFrameDesc& desc) {
  if (desc.framesInFlight == 0)
    throw std::invalid_argument("HostComfortFrameDesc.framesInFlight is 0; it must be at least 1");
  return desc.framesInFlight;
}

}  // namespace

HostComfortFrame::HostComfortFrame(vk::Context& context, const HostComfortFrameDesc& desc)
    : desc_(desc), stereo_(context, desc.stereo), reduced_(checkedFramesInFlight(desc), false) {
  if (desc.budget) {
    try {
      controller_.emplace(*desc.budget, desc.allowNegativeParallax, desc.budgetSettings);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(std::string("HostComfortFrameDesc.budget: ") + error.what());
    }
  }
  reductions_.reserve(desc.framesInFlight);
  for (std::uint32_t i = 0; i < desc.framesInFlight; ++i) reductions_.emplace_back(context);
}

const FrameComfortState& HostComfortFrame::update(const HostComfortInput& input) {
  validate(input, desc_.framesInFlight);
  slot_ = input.frameSlot;
  // The slot's reduction was recorded framesInFlight frames ago; the host waited for that submission.
  hasRange_ = reduced_[slot_];
  if (hasRange_) range_ = reductions_[slot_].result();

  FrameComfortInput frame;
  frame.camera = input.camera;
  frame.rayCast = input.rayCast;
  frame.parameters = input.parameters;
  if (lastChoice_) {  // the controller's latest choice holds until it chooses again
    frame.parameters.maxSeparation = lastChoice_->maxSeparation;
    frame.parameters.zeroParallaxDistance = lastChoice_->zeroParallaxDistance;
  }
  frame.width = desc_.stereo.width;
  frame.crosshairDistance = input.crosshairDistance;
  frame.crosshairMargin = input.crosshairMargin;
  frame.weapon = input.weapon;
  frame.nearestWorldDepth = input.nearestWorldDepth;
  if (!frame.nearestWorldDepth && hasRange_ && range_.hasFinite()) frame.nearestWorldDepth = range_.nearest;
  frame.hud = input.hud;
  frame.allowNegativeParallax = desc_.allowNegativeParallax;
  if (controller_ && hasRange_)
    frame.budget = FrameBudget{&*controller_, &range_, input.seconds, input.cut, input.anticipatedNearest, input.receding};
  state_ = frameComfortState(frame);
  if (state_.budget) lastChoice_ = state_.budget->parameters;
  updated_ = true;
  masksRecorded_ = false;
  return state_;
}

stereo::StereoFrameDispatch HostComfortFrame::comforted(const stereo::StereoFrameDispatch& dispatch,
                                                        const char* call) const {
  if (!updated_)
    throw std::invalid_argument(std::string("HostComfortFrame: ") + call +
                                " needs this frame's update(HostComfortInput) first (once per recorded frame)");
  if (dispatch.eyeViews)
    throw std::invalid_argument("HostComfortFrame: StereoFrameDispatch.eyeViews is not taken: the comfort rules choose "
                                "maxSeparation and zeroParallaxDistance (give the views' as HostComfortInput.parameters)");
  stereo::StereoFrameDispatch d = dispatch;
  d.maxSeparation = state_.parameters.maxSeparation;
  d.zeroParallaxDistance = state_.parameters.zeroParallaxDistance;
  d.weaponDepthOffset = state_.parameters.weaponDepthOffset;
  d.weaponDepthScale = state_.parameters.weaponDepthScale;
  return d;
}

// The reduction reads the depth as the stereo frame will: the dispatch's projection, the state's weapon push.
void HostComfortFrame::recordReduction(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& d) {
  reductions_[slot_].recordHost(cmd, d.depth, desc_.stereo.width, desc_.stereo.height, d.projection,
                                d.weaponDepthOffset, d.weaponDepthScale);
}

void HostComfortFrame::record(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& dispatch) {
  const stereo::StereoFrameDispatch d = comforted(dispatch, "record");
  if (desc_.stereo.method == stereo::StereoMethod::Hybrid)  // before the reduction: nothing recorded on refusal
    throw std::invalid_argument("HostComfortFrame: a StereoFrameDesc.method Hybrid frame records with "
                                "recordHybridMasks and recordHybridComposite");
  recordReduction(cmd, d);
  stereo_.record(cmd, d);
  reduced_[slot_] = true;  // only once the frame is recorded whole: a refused dispatch leaves the slot as it was
  updated_ = false;
}

stereo::HybridEyeCameras HostComfortFrame::recordHybridMasks(VkCommandBuffer cmd,
                                                             const stereo::StereoFrameDispatch& dispatch) {
  const stereo::StereoFrameDispatch d = comforted(dispatch, "recordHybridMasks");
  if (desc_.stereo.method != stereo::StereoMethod::Hybrid)
    throw std::invalid_argument("HostComfortFrame: recordHybridMasks needs StereoFrameDesc.method Hybrid");
  recordReduction(cmd, d);
  const stereo::HybridEyeCameras cameras = stereo_.recordHybridMasks(cmd, d);
  reduced_[slot_] = true;
  masksRecorded_ = true;
  return cameras;
}

void HostComfortFrame::recordHybridComposite(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& dispatch) {
  if (!masksRecorded_)
    throw std::invalid_argument("HostComfortFrame: recordHybridComposite needs this frame's recordHybridMasks first");
  stereo_.recordHybridComposite(cmd, comforted(dispatch, "recordHybridComposite"));
  updated_ = false;
  masksRecorded_ = false;
}

}  // namespace s3d::comfort
