#pragma once
// A host's stereo frame, in the style of a FidelityFX effect: created from a description, recorded into the
// host's command buffer once per frame with a dispatch description, destroyed. Every displacement method (seed,
// search, iterative, forward, forward with the previous-frame fill) from every host colour and depth format, to
// two eye images, the two layers of one array image (what OpenXR swapchains and multiview hosts hand over), or one
// packed target. Synchronization: as HostStereoPass (host_stereo_pass.h): with a stage in a HostImage s3d adds the
// barriers into the layout it needs and back; recording allocates nothing (everything is made at creation).
//
// The hybrid (StereoMethod::Hybrid, two eye images) records in two steps around the host's own draw:
//   1. recordHybridMasks: the base search into the eyes, the classification, threshold and masks, and each eye's
//      mask written into a depth image the host names (leftMask, rightMask: D32_SFLOAT, TRANSFER_DST usage): far
//      (1, or 0 with projection.reversedZ) where the mask is set, near (0, or 1) elsewhere. Returns the eye cameras.
//      Images: the inputs and eyes as record()'s; the masks barriered from their HostImage layout, stage and access
//      into TRANSFER_DST_OPTIMAL and back (copy stage, transfer write), so after step 1 each image is in the layout
//      it named, its writes ordered before the stage and access it named (the eyes: e.g. COLOR_ATTACHMENT_OPTIMAL,
//      COLOR_ATTACHMENT_OUTPUT, COLOR_ATTACHMENT_READ|WRITE; the masks: DEPTH_ATTACHMENT_OPTIMAL, EARLY|LATE
//      FRAGMENT_TESTS, DEPTH_STENCIL_ATTACHMENT_READ|WRITE). With stage NONE the host orders its use itself.
//   2. The host draws its scene into each eye (load, no clear) from that eye's camera with that eye's mask as depth
//      attachment (load, no clear), depth test LESS (GREATER with reversed-Z) and depth writes as usual: only the
//      masked pixels change. A masked pixel the host draws nothing into keeps the displaced colour.
//   3. recordHybridComposite: the overlay, when given (the eyes barriered from their HostImage state into GENERAL
//      and back); without an overlay it records nothing: the eyes are finished when the host's draw is.
#include <array>
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "s3d/stereo/eye_views.h"
#include "s3d/stereo/forward_pass.h"
#include "s3d/stereo/host_hybrid_pass.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/stereo/iterative_pass.h"
#include "s3d/stereo/previous_fill_pass.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

struct StereoFrameDesc {
  std::uint32_t width = 0;  // the host's colour and depth images in pixels (the eyes have this size), >= 1
  std::uint32_t height = 0;
  VkFormat colorFormat = VK_FORMAT_R8G8B8A8_UNORM;  // RGBA8/BGRA8 UNORM or SRGB, RGBA16F, B10G11R11
  VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;      // D32, D24S8, D16 (hardware depth) or R32F linear depth
  HostOutput output = HostOutput::TwoEyes;
  // Seed, Search, Iterative, Forward or Hybrid (search, then the host's raster re-draws the pixels it gets wrong;
  // two eyes, 8-bit colour; the steps above). The HDR colour formats (RGBA16F, B10G11R11) take Seed and Search,
  // whose kernels gather HDR values.
  StereoMethod method = StereoMethod::Search;
  int searchTaps = 4;   // Search: taps spread over the separation, 1..S3D_STEREO_MAX_TAPS
  int iterations = 6;   // Iterative: fixed-point steps, 1..16
  StereoKernel kernel = StereoKernel::Auto;
  bool previousFrameFill = false;  // Forward only: holes take the previous frame's eyes, reprojected
  float hybridBudget = 0.6f;       // Hybrid only: the largest share of each eye's pixels the host re-draws, [0, 1]
  int hybridCell = 0;              // Hybrid only: the classification's cell in pixels per side, 1 or 2; 0 by the
                                   // width (StereoParameters::hybridCell)
  float hybridScoreFloor = 0.15f;  // Hybrid only: pixels of parallax error below which no pixel is re-drawn below
                                   // budget 1, [0, 32] (StereoParameters::hybridScoreFloor)
};

// Per frame. The images must have the description's formats and sizes.
struct StereoFrameDispatch {
  HostImage color;
  HostImage depth;
  // TwoEyes: the eyes, in eyeFormat(), storage images; for one array image, both name it with layer 0 and 1 and a
  // 2D view of that layer each. Packed outputs: `target` (eyeFormat(), packedWidth() x packedHeight()).
  HostImage left, right, target;
  HostProjection projection;          // the depth buffer's convention (ignored for R32F linear depth)
  float maxSeparation = 0.02f;        // per-eye displacement at infinity, fraction of the width, [0, 0.25]
  float zeroParallaxDistance = 1.0f;  // world units, > 0: the depth that stays on the screen plane
  // Instead of the two above: the eyes' views (OpenXR's XrView per eye, each eye the description's size), from
  // which both are derived (eye_views.h: eyeViewsParallax; the rules eyeViewsProblem checks). The center image is
  // then rendered from the eyes' midpoint with sharedCenterView's frustum.
  std::optional<ViewConfiguration> eyeViews;
  float edgeCrop = -1.0f;             // fraction of the width blacked out per side, [0, 0.25]; < 0: = maxSeparation
  float weaponDepthOffset = 1.0f;     // the first-person layer's depth becomes offset + scale * depth (seed 4.6.2)
  float weaponDepthScale = 1.0f;
  // Previous-frame fill and hybrid: the center camera this frame (world to view, and the view's projection; column-major,
  // Vulkan clip space), from which s3d derives the eye cameras and their motion since the previous frame.
  glm::mat4 centerView{1.0f};
  glm::mat4 centerProjection{1.0f};
  bool cameraCut = false;  // the previous frame does not continue into this one (also implied by the first frame)
  // Drawn on the finished eyes before they are packed (the HUD: hud::HudPass::overlay); null: nothing.
  const EyeOverlay* overlay = nullptr;
  // Hybrid: each eye's mask as the depth image the host draws that eye with (D32_SFLOAT, TRANSFER_DST usage, the
  // description's size; `view` unused), written by recordHybridMasks.
  HostImage leftMask, rightMask;
};

// The cameras the host draws each eye's masked pixels from (world to view, and the projection; column-major,
// Vulkan clip space): the off-axis eyes of the center camera whose parallax the displacement reproduces.
struct HybridEyeCameras {
  EyeCamera left, right;
};

class StereoFrame {
 public:
  // Throws std::invalid_argument naming the field of the description that is out of range or unsupported.
  StereoFrame(vk::Context& context, const StereoFrameDesc& desc);

  // Records the input conversion, the method's kernel (and the fill) and the packing into `cmd`. Throws
  // std::invalid_argument naming the dispatch field that does not match the description. With the fill, frames
  // must be submitted in the order they are recorded.
  void record(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch);

  // The hybrid's two steps (above), in place of record(). Throw std::invalid_argument for another method and
  // naming the dispatch field that is missing or does not match (leftMask, rightMask, the center camera).
  HybridEyeCameras recordHybridMasks(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch);
  void recordHybridComposite(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch) const;

  VkFormat eyeFormat() const;  // RGBA8 UNORM for 8-bit colour, RGBA16F for HDR colour
  std::uint32_t packedWidth() const;
  std::uint32_t packedHeight() const;
  const StereoFrameDesc& desc() const { return desc_; }

 private:
  StereoParameters parameters(const StereoFrameDispatch& dispatch) const;
  void requireImages(const StereoFrameDispatch& dispatch) const;
  // The checks every record makes (eye views, parameters, images), and the host pass's frame for the dispatch.
  HostFrame checkedFrame(const StereoFrameDispatch& dispatch) const;
  void requireCenterCamera(const StereoFrameDispatch& dispatch, const char* forWhat) const;
  void requireHybrid(const char* step) const;
  // Iterative or forward (with the fill) from the converted center into the eyes.
  void recordKernel(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch, const vk::Image& centerColor,
                    const vk::Image& linearDepth, const vk::Image& leftEye, const vk::Image& rightEye);

  StereoFrameDesc desc_;
  // Seed and search run inside the host pass, which also converts and packs for every method.
  HostStereoPass host_;
  std::optional<IterativeStereoPass> iterative_;
  std::optional<ForwardStereoPass> forward_;
  std::optional<PreviousFillPass> fill_;
  std::optional<HostHybridPass> hybrid_;
  std::array<glm::mat4, 2> previousEyeView_{}, previousEyeProjection_{};
  bool hasPrevious_ = false;
};

}  // namespace s3d::stereo
