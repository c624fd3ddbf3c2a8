#pragma once
// The stereo pass inside a host's frame: the host's own colour and depth images in, its eye images or one
// packed target out, recorded into the host's command buffer (docs/INTEGRATION.md).
#include <cstdint>
#include <optional>
#include <span>

#include <vulkan/vulkan.h>

#include "s3d/gpu/linear_depth.h"
#include "s3d/stereo/detail/eye_pair_pipeline.h"
#include "s3d/stereo/host_pass_shared.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// One of the host's images as it is when record() runs.
struct HostImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;  // 2D, mip 0, layer `layer`; for depth/stencil formats the depth aspect only
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // current layout; record() leaves the image in it
  // The host's last access. With a stage, record() adds the barriers (into the layout s3d needs and back);
  // with VK_PIPELINE_STAGE_2_NONE the host has synchronized the image itself and `layout` must be one s3d can
  // use as it is (inputs: GENERAL or a read-only layout; outputs: GENERAL).
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  std::uint32_t layer = 0;  // the array layer `view` shows: 0 and 1 for two eyes in one 2-layer array image
};

// The host's depth buffer convention, for linear depth (Listings 4.2 and 4.3).
struct HostProjection {
  float nearPlane = 0.1f;  // world units
  float farPlane = 1000.0f;  // ignored with infiniteFarPlane
  bool reversedZ = false;  // near at device depth 1, far (and the cleared sky) at 0
  bool infiniteFarPlane = false;
  // The first-person layer (weapon, arms) drawn with its own projection into a slice of the depth range: device
  // depth [0, firstPersonDepthRange] (reversed-Z: [1 - firstPersonDepthRange, 1]); 0 when the host has none.
  float firstPersonDepthRange = 0.0f;
  float firstPersonNear = 0.01f;
  float firstPersonFar = 10.0f;
};

enum class HostColorFormat { Rgba8, Rgba8Srgb, Bgra8, Bgra8Srgb, Rgba16F, B10G11R11 };
enum class HostDepthKind { Linear, Hardware };
enum class HostOutput { TwoEyes, SideBySideHalf, SideBySideFull, TopBottomHalf, TopBottomFull, Anaglyph };

// How the seed and short searches (up to four taps) read the host's colour and depth: Direct samples them inside
// the gather (one dispatch; per texel the sRGB encode and the depth linearization), Convert runs the input
// conversion into RGBA8 + R32F first. Auto: Direct on GPUs; on CPU devices (lavapipe) Convert to two eyes and
// Direct where the gather packs the anaglyph or a half packing (sparing the packing pass), each the faster there
// (docs/RESULTS.md "Host pass against the bare stereo pass").
enum class HostInputRead { Auto, Direct, Convert };

// What the pass is set up for; everything it creates (pipelines, sampler, intermediate images) is made from this
// at construction, so record() allocates nothing.
struct HostStereoPassDesc {
  std::uint32_t width = 0;  // the host's colour and depth images (the eyes have this size)
  std::uint32_t height = 0;
  VkFormat colorFormat = VK_FORMAT_R8G8B8A8_UNORM;  // RGBA8/BGRA8 UNORM or SRGB, RGBA16F, B10G11R11
  VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;      // D32, D24S8, D16 (hardware) or R32F (linear depth)
  HostOutput output = HostOutput::TwoEyes;
  // Skip the input conversion when the host's colour is RGBA8 UNORM and its depth R32F linear depth, both made
  // with VK_IMAGE_USAGE_STORAGE_BIT: the stereo kernel reads them as they are.
  bool inputsAreStorage = false;
  HostInputRead inputRead = HostInputRead::Auto;
};

// Per frame: the stereo parameters as push constants (makeStereoConstants; Seed or Search methods) and, for
// hardware depth, the projection and the first-person push.
struct HostFrame {
  gpu::StereoConstants stereo{};
  HostProjection projection;
  float weaponDepthOffset = 1.0f;  // seed 4.6.2 (StereoParameters::weaponDepthOffset/Scale)
  float weaponDepthScale = 1.0f;
};

// LinearDepthParams for a host's projection (infinite far planes and reversed-Z included).
gpu::LinearDepthParams linearDepthParams(const HostProjection& projection, float weaponDepthOffset,
                                         float weaponDepthScale);

// Work recorded on the finished eyes inside HostStereoPass::record, before they are packed (the HUD pass:
// hud::HudPass::overlay). The eyes come in GENERAL layout, eyeFormat(), already ordered after the stereo kernel's
// compute writes (stage NONE: s3d synchronizes them), and record() orders the packing after the overlay's compute
// writes. An overlay synchronizes any other image it uses itself.
class EyeOverlay {
 public:
  virtual void recordOnEyes(VkCommandBuffer cmd, const HostImage& left, const HostImage& right) const = 0;

 protected:
  ~EyeOverlay() = default;
};

// The displacement recorded inside HostStereoPass::record in place of its own seed/search kernel (the other
// methods: stereo_frame.h). The center comes as RGBA8 display colour and R32F linear depth, the eyes as
// eyeFormat() images, all GENERAL and ordered after the conversion's writes; record() orders the overlay or the
// packing after the kernel's compute writes.
class EyeKernel {
 public:
  virtual void recordKernel(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                            const vk::Image& leftEye, const vk::Image& rightEye) const = 0;

 protected:
  ~EyeKernel() = default;
};

class HostStereoPass {
 public:
  // Throws std::invalid_argument naming an unsupported format or size.
  HostStereoPass(vk::Context& context, const HostStereoPassDesc& desc);

  // Records the input conversion (unless skipped), the stereo kernel, the overlay (when given) and the output
  // packing into `cmd`. Eyes: `left`/`right` (storage images in the pass's eye format, see eyeFormat()); packed
  // outputs: `target` (storage image in eyeFormat(), packedWidth() x packedHeight()). No submit, no wait, no
  // allocation.
  // `kernel` replaces the seed/search kernel (frame.stereo then only has to be valid).
  void record(VkCommandBuffer cmd, const HostImage& color, const HostImage& depth, const HostFrame& frame,
              const HostImage* left, const HostImage* right, const HostImage* target,
              const EyeOverlay* overlay = nullptr, const EyeKernel* kernel = nullptr) const;

  // RGBA8 UNORM (display colour) for 8-bit inputs, RGBA16F for RGBA16F and B10G11R11 (HDR) inputs.
  VkFormat eyeFormat() const { return hdr_ ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R8G8B8A8_UNORM; }
  std::uint32_t packedWidth() const;
  std::uint32_t packedHeight() const;
  bool convertsInputs() const { return !desc_.inputsAreStorage; }
  const HostStereoPassDesc& desc() const { return desc_; }

 private:
  struct Recording;  // one record's images, the layouts s3d reads its inputs in and the views it writes
  Recording begin(VkCommandBuffer cmd, const HostImage& color, const HostImage& depth, const HostFrame& frame,
                  const HostImage* left, const HostImage* right, const HostImage* target, bool overlay,
                  bool kernel) const;  // checks the images, then the barriers from the host's state
  void end(const Recording& r) const;   // the barriers back to the host's state
  void dispatch(VkCommandBuffer cmd, const detail::EyePairPipeline& pass, std::span<const VkWriteDescriptorSet> writes,
                const void* push, std::uint32_t width, std::uint32_t height) const;
  void recordGatherFromHost(const Recording& r) const;   // seed and short searches on the host's images
  void recordConversion(Recording& r) const;             // the host's images into the storage intermediates
  void recordStorageKernel(const Recording& r) const;    // seed or search on storage images
  void recordOverlay(const Recording& r, const EyeOverlay& overlay) const;
  void recordPacking(const Recording& r) const;

  vk::Context* context_;
  HostStereoPassDesc desc_;
  bool hdr_ = false;
  int colorTransfer_ = S3D_HOST_COLOR_AS_STORED;
  vk::Unique<VkSampler> sampler_;
  // hostGather_: seed and searches of up to four taps straight from the host's sampled images (no conversion), in
  // the half packings' own module for those outputs; hostGatherFirstPerson_ the same for a depth buffer with a
  // first-person range, picked per frame by the projection.
  std::optional<detail::EyePairPipeline> input_, hostGather_, hostGatherFirstPerson_, shortTaps_, allTaps_, pack_;
  vk::Image centerColor_, linearDepth_, leftEye_, rightEye_;  // intermediates (unused ones stay empty)
};

}  // namespace s3d::stereo
