#pragma once
// A host's stereo frame with its per-frame comfort rules, in one object in the style of a FidelityFX effect: the
// stereo frame (stereo/stereo_frame.h), a ring of GPU depth reductions (one per frame in flight), the disparity
// budget controller and the comfort state (frame_comfort_state.h). Created from a description; per frame update()
// (CPU: the comfort state, which the HUD needs before its overlay is made) then record() (GPU: the reduction and the
// stereo frame, into the host's command buffer); destroyed. It needs no s3d renderer.
//
// Frames in flight: record() writes the frame's reduction into its slot's buffer, read back by the next update() of
// the same slot, framesInFlight frames later, after the host's fence wait for that slot. So the budget follows the
// depth of framesInFlight frames ago; until a slot's first reduction has completed it waits (the host's parameters,
// or the controller's last choice).
//
// Synchronization: both the reduction and the stereo frame read the host's depth image in the host's command buffer,
// the reduction first. Each barriers it from the state the HostImage states (layout, stage, access) into a layout a
// compute shader samples and back (detail::sampledReadLayout), so the stereo frame finds it in the stated layout, its
// barrier chained after the reduction's on the stated stage; with stage NONE both read it as it is (it must then be
// in a sampled-readable layout). The eyes and colour as StereoFrame::record's. record() creates no Vulkan object and
// allocates nothing (everything is made at creation); update() is CPU work whose only allocations are the comfort
// state's own (its HUD element list) and the read range's histogram.
#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/disparity_budget.h"
#include "s3d/comfort/disparity_budget_controller.h"
#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/stereo/depth_range.h"
#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/stereo_frame.h"
#include "s3d/vk/context.h"

namespace s3d::comfort {

struct HostComfortFrameDesc {
  stereo::StereoFrameDesc stereo;  // the stereo frame's images, method and output (stereo_frame.h)
  // The display's disparity budget (disparityBudget(DisplayProfile)); none: maxSeparation and the zero-parallax
  // distance are the host's (HostComfortInput::parameters), with the no-negative-parallax rules applied.
  std::optional<DisparityBudget> budget;
  DisparityBudgetSettings budgetSettings;  // the controller's smoothing and bounds (validated at creation)
  bool allowNegativeParallax = false;  // off: nothing in front of the screen plane (weapon pushed, plane held)
  std::uint32_t framesInFlight = 2;    // the host's frames in flight, >= 1: that many depth reductions
};

// What the host knows of one frame (frame_comfort_state.h's FrameComfortInput, less what the object supplies: the
// eyes' width, negative parallax, the budget and its depth range).
struct HostComfortInput {
  // The host's frame-in-flight index, [0, framesInFlight). The host guarantees that this slot's previous submission
  // has completed (its fence wait before reusing the slot's command buffer).
  std::uint32_t frameSlot = 0;
  FrameCamera camera;  // position, aim (unit vector) and near plane, world units
  RayCast rayCast;     // the host's ray cast along the aim; empty: no world, the crosshair at crosshairDistance
  // The host's settings: maxSeparation (fraction of the width, [0, 0.25]) and zeroParallaxDistance (world units,
  // > 0) used as given without a budget, and before the controller's first choice; the weapon push
  // (weaponDepthOffset >= 0, weaponDepthScale > 0) as the rules start from it. The method fields are the
  // description's.
  stereo::StereoParameters parameters;
  float crosshairDistance = 10.0f;  // world units, > 0: where the crosshair sits without a hit
  float crosshairMargin = 0.25f;    // world units, >= 0: in front of the hit
  WeaponMaskStats weapon;           // the first-person layer's linear depth range in view (pixels 0: none)
  // The frame's nearest world depth (world units, > 0); none: the reduction's nearest (framesInFlight frames ago),
  // when it has one. The zero-parallax distance is held at it unless negative parallax is allowed.
  std::optional<float> nearestWorldDepth;
  std::vector<HudElementDepth> hud;  // the HUD elements' linear depths (world units, > 0), in the state's order
  float seconds = 1.0f / 60.0f;      // this frame's duration, > 0 (the controller's rate bounds)
  bool cut = false;                  // the camera cut: the budget jumps to its target without a ramp
  bool receding = false;             // the camera moves away from what it sees: more depth followed at once
  std::optional<float> anticipatedNearest;  // a nearer surface expected soon (world units, > 0), e.g. ray casts ahead
};

class HostComfortFrame {
 public:
  // Throws std::invalid_argument naming the description's field (framesInFlight, budgetSettings, the stereo
  // frame's fields as StereoFrame names them).
  HostComfortFrame(vk::Context& context, const HostComfortFrameDesc& desc);

  // CPU only: reads the slot's reduction (framesInFlight frames ago), lets the controller choose, and runs
  // frameComfortState. The state stays valid until the next update(). Throws std::invalid_argument naming the
  // HostComfortInput field out of range (e.g. "HostComfortInput.frameSlot 3 is outside [0, 2)").
  const FrameComfortState& update(const HostComfortInput& input);

  // Records this frame's depth reduction of dispatch.depth (with the dispatch's projection and the state's weapon
  // push) into the slot, then the stereo frame. The dispatch's maxSeparation, zeroParallaxDistance,
  // weaponDepthOffset and weaponDepthScale are replaced by the state's; eyeViews are refused (the rules choose the
  // parameters). Throws std::invalid_argument without this frame's update(), or as StereoFrame::record.
  void record(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& dispatch);
  // The hybrid's two steps (stereo_frame.h) in place of record(): the reduction and the masks, then the composite
  // after the host's draw. The composite needs this frame's masks first.
  stereo::HybridEyeCameras recordHybridMasks(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& dispatch);
  void recordHybridComposite(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& dispatch);

  // The depth range the last update() read (its slot's reduction), or null when that slot had none yet.
  const stereo::DepthRange* depthRange() const { return hasRange_ ? &range_ : nullptr; }
  const FrameComfortState& state() const { return state_; }
  const HostComfortFrameDesc& desc() const { return desc_; }
  const stereo::StereoFrame& stereoFrame() const { return stereo_; }

 private:
  // The dispatch with the state's parameters, after checking this frame's update() came first.
  stereo::StereoFrameDispatch comforted(const stereo::StereoFrameDispatch& dispatch, const char* call) const;
  void recordReduction(VkCommandBuffer cmd, const stereo::StereoFrameDispatch& dispatch);

  HostComfortFrameDesc desc_;
  stereo::StereoFrame stereo_;
  std::vector<stereo::DepthRangePass> reductions_;  // one per slot
  std::vector<bool> reduced_;                       // the slot's reduction has been recorded
  std::optional<DisparityBudgetController> controller_;
  std::optional<BudgetParameters> lastChoice_;  // the controller's latest parameters
  stereo::DepthRange range_;
  bool hasRange_ = false;
  FrameComfortState state_;
  std::uint32_t slot_ = 0;      // the last update()'s
  bool updated_ = false;        // update() ran and its frame is not recorded yet
  bool masksRecorded_ = false;  // the hybrid's first step ran for this update()
};

}  // namespace s3d::comfort
