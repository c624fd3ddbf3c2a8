#pragma once
// The forward method (forward.h) on the GPU: a drop-in for StereoPass with the same four bindings. Two kernels
// with the same eyes bit for bit (docs/DESIGN.md, the forward method):
// - rows (StereoKernel::RowTiles, and Auto where it fits): one dispatch, a workgroup per image row holding the
//   row's depth and both eyes' z-buffers in shared memory (12 B per column, the width rounded up to 256);
// - key images (StereoKernel::PerPixel, and wherever the row does not fit the device's shared memory): two
//   dispatches over R32UI z-buffer images (splat with image atomics; resolve, which also empties the other pair
//   of z-buffers for the next record), plus a clear dispatch before the first record at a size.
// Images the pass owns (two pairs of z-buffers, the row pipeline sized for the width) are created at the first record for
// the size and reused; a record at another size replaces them: finish command buffers using the old size first.
#include <array>
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

#include "s3d/stereo/forward.h"
#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// Whether the pass leaves both eyes' z-buffers in images for a pass recorded after it (keys()). The key-image
// kernel has them anyway; the row kernel then also stores its shared z-buffers (8 B a pixel more written).
enum class ForwardKeys { Discarded, Kept };

// Shared memory the row kernel needs for a row of `width` pixels.
std::uint32_t forwardRowSharedBytes(int width);

// Reads: center color (RGBA8, display-encoded) and linear depth (R32F), both in VK_IMAGE_LAYOUT_GENERAL.
// Writes: left and right eye (RGBA8, GENERAL); compute barriers between its own dispatches.
// StereoPass::recordInputBarriers / recordInputRelease apply unchanged.
class ForwardStereoPass {
 public:
  explicit ForwardStereoPass(const vk::Context& context, StereoKernel kernel = StereoKernel::Auto,
                             ForwardKeys keys = ForwardKeys::Discarded);
  void record(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
              const vk::Image& leftEye, const vk::Image& rightEye, const gpu::ForwardConstants& constants) const;
  // Whether a record at this width runs the row kernel: asked for (StereoKernel::RowTiles; Auto runs the key-image
  // dispatches, measured faster on a GPU), and the row fits the device's maxComputeSharedMemorySize.
  bool usesRowKernel(int width) const;
  // The z-buffer of one eye after the last record (R32UI, GENERAL, last accessed by compute shader reads and
  // writes; keys as in forward_shared.h, S3D_FORWARD_EMPTY for a hole): a pass recorded after this one reads
  // it to know the holes. Throws std::logic_error before a record, or after a row-kernel record of a pass
  // constructed with ForwardKeys::Discarded.
  const vk::Image& keys(Eye eye) const;

 private:
  const vk::Context* context_;
  StereoKernel kernel_;
  ForwardKeys keysWanted_;
  std::uint32_t maxSharedBytes_ = 0;
  vk::PipelineLayout layout_;
  mutable vk::Unique<VkPipeline> clear_, splat_, resolve_;  // the key-image kernel, created at its first record
  struct RowPipeline {
    int capacity = 0;  // columns its shared arrays hold
    vk::Unique<VkPipeline> pipeline;
  };
  mutable std::optional<RowPipeline> row_;
  // The pipelines a record needs, made at their first use (lavapipe compiles at creation): the row kernel for a
  // row capacity, the key-image kernel's three dispatches.
  const RowPipeline& rowPipeline(int capacity) const;
  void makeKeyImagePipelines() const;
  struct KeyPair {
    vk::Image left, right;
    bool empty = false;  // every key is S3D_FORWARD_EMPTY (a resolve emptied it for the next record)
  };
  // Two pairs of z-buffers used in turn: each record splats into one while its resolve empties the other for
  // the next record, which so needs no clear dispatch (and no barrier after one).
  mutable std::optional<std::array<KeyPair, 2>> zBuffers_;
  mutable int current_ = 0;  // the pair the last record splatted into (keys())
  mutable bool keysWritten_ = false;  // the last record left its z-buffers in zBuffers_
};

// Uploads CPU images, runs the pass once and reads both eyes back (tests, tools).
StereoPair synthesizeForwardOnGpu(vk::Context& context, const ImageRGBA8& center, const DepthImage& linearDepth,
                                  const gpu::ForwardConstants& constants, StereoKernel kernel = StereoKernel::Auto);

}  // namespace s3d::stereo
