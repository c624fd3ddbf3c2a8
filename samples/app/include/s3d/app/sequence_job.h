#pragma once
// `s3d render --sequence`: a scene's camera path (an animated scene without one: one loop of its animation, frame
// N posed at N / framesPerSecond) with the comfort controls running frame by frame: the
// zero-parallax control pulls the screen plane in when the player nears a wall (seed 4.6.2), the weapon
// push shrinks with it, the crosshair follows the aim ray; every frame is checked for depth conflicts.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "s3d/comfort/budget_frame.h"
#include "s3d/comfort/comfort_profile.h"
#include "s3d/comfort/comfort_report.h"
#include "s3d/comfort/zero_parallax_control.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/stereo.h"
#include "s3d/stereo/temporal.h"
#include "s3d/vk/context.h"

namespace s3d::app {

struct SequenceJobOptions {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::string scene = "cover";
  std::filesystem::path outputFolder = "out";
  bool writeFrames = true;          // anaglyph_NNNN.png per frame
  bool writeReport = true;          // report.json
  std::uint32_t supersample = 1;  // renderer anti-aliasing, 1..4
  float framesPerSecond = 12.0f;  // the built-in paths walk at about 2 m/s at this rate; frame N's animation time is N / it
  // zeroParallaxDistance is the control's rest value; edgeCrop < 0 (the default): a guard band, full-frame eyes
  // (as in `s3d render`); >= 0: the output-size center view and that crop.
  stereo::StereoParameters stereo;
  comfort::ZeroParallaxControlSettings zeroParallax;  // its restDistance is taken from stereo
  comfort::CrosshairSettings crosshair;               // distance (nullopt: the scene's), margin, smoothing
  comfort::DisplayProfile display = comfort::builtInDisplayProfile("tv55");  // of the per-frame comfort report
  bool allowNegativeParallax = false;  // off: the zero-parallax distance never exceeds the frame's nearest depth
  bool reversedZ = false;  // renderer::RendererOptions::reversedZ
  // OneDegree: the disparity budget controller (s3d/comfort/budget_frame.h) chooses maxSeparation and the zero-parallax
  // distance per frame from the GPU depth reduction; off: the zero-parallax control alone, as before.
  comfort::DisparityBudgetRule disparityBudget = comfort::DisparityBudgetRule::Off;
  // The budget's anticipation: the zero-parallax control's ray casts from where the camera will be this many
  // seconds ahead at its current velocity (0: none; 0.35 s: no forced frame on the cover path, docs/RESULTS.md,
  // "Disparity budget: every camera path x display, off and 1deg"); a surface they find eases the target down early.
  float anticipateSeconds = 0.35f;
  std::optional<std::uint64_t> memoryLimitBytes;  // --memory-limit; the machine's available memory in any case
  // Every frame's camera is this frame of the path (a static camera: the controls and the metrics at rest).
  std::optional<std::size_t> holdFrame;
};

struct SequenceFrame {
  std::size_t index = 0;
  float zeroParallaxDistance = 0.0f;
  std::optional<float> nearestSurface;  // what the control's ray casts saw
  float crosshairDepth = 0.0f;          // smoothed over frames (comfort::CrosshairSmoother)
  std::optional<float> aimSurface;      // depth of the surface the aim ray hits within the crosshair distance
  bool zeroParallaxLimited = false;     // the no-negative-parallax rule cut the controller's value this frame
  float nearestDepth = 0.0f;            // nearest finite depth of the stereo pass's input (weapon pushed)
  comfort::FrameComfort comfort;        // parallax range, share beyond the 1-degree rule, window violations
  float weaponDepthOffset = 0.0f;       // the push, shrunk with the zero-parallax distance
  float weaponDepthScale = 0.0f;
  std::uint64_t weaponPixels = 0;
  std::uint64_t weaponConflictPixels = 0;  // weapon pixels whose pushed depth lies behind the world surface there
  double psnrLeftDb = 0.0, psnrRightDb = 0.0;  // synthesized vs two-pass reference
  comfort::BudgetFrame budget;                  // the disparity budget's reduction and choice (off: empty)
  comfort::DisparityMapReport disparityMap;     // the depth-to-parallax curve (identity: linear)
  float maxSeparation = 0.0f;                   // as the stereo pass used it
  std::uint32_t cropColumns = 0;                // per side, blacked out and not compared (0 with a guard band)
  std::uint32_t guardBandColumns = 0;           // per side, rendered beyond the output (0 with an edge crop)
  std::optional<double> stereoPassGpuMs;        // the stereo pass (and the previous-frame fill), GPU timestamps
  // Left, right: the change of the eye's error since the previous frame along the camera's motion
  // (stereo/temporal.h), over the pixels both frames saw, the halo and this frame's disocclusion; empty on the
  // first frame.
  std::optional<std::array<stereo::FlickerStats, 2>> flicker;
};

struct SequenceReport {
  std::string deviceName;
  std::string scene;
  std::vector<SequenceFrame> frames;
  std::vector<std::string> filesWritten;
};

// Mean over the frames that have one of each eye's flicker per region (all, halo, disocclusion).
std::array<stereo::FlickerStats, 2> meanFlicker(const SequenceReport& report);

// The widest guard band a frame of the sequence can need (none with an edge crop): what the memory estimate counts.
stereo::GuardBand widestSequenceGuardBand(const SequenceJobOptions& options);

// One frame's images at a time with the widest guard band the sequence can reach, the previous frame (the
// flicker metric's) and the previous-frame fill's history: checked before the Vulkan start-up and again by
// runSequenceJob once the device is known.
frame::MemoryEstimate sequenceMemoryEstimate(const SequenceJobOptions& options);

// Throws std::invalid_argument for bad options (checked before rendering) and anything the renderer throws.
SequenceReport runSequenceJob(vk::Context& context, const SequenceJobOptions& options);

nlohmann::json toJson(const SequenceReport& report);

}  // namespace s3d::app
