#pragma once
// The transparent pass (shaders/transparent.comp): after lighting, the transparent objects are composited over
// the lit HDR image back to front, each one dispatch over the render tiles its bounds cover, and their coverage
// (1 - prod(1 - opacity), the error metrics' transparent region) is written beside it. Compute, not a blended
// raster pass: on a GPU whose raster side is a small part of the chip (the H100) the raster pass cost the bytes
// its fragments read and wrote (0.47 ms for the glass scene at 1920x1080), while compute runs on all of it.
//
// Reads: the opaque device depth (sampled by compute; depth-tested, never written), the frame and object
// constants, the index, vertex and surface buffers, each object's textures. Writes: the HDR image (storage,
// GENERAL; left readable by compute for the resolve) and the coverage image (storage, GENERAL).
// Synchronization: expects the HDR image as the lighting pass leaves it (vk::kComputeWrite); leaves it in
// vk::kComputeRead and the coverage in vk::kComputeWrite.
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "s3d/renderer/shadows.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer::detail {

class TransparentPass {
 public:
  // width, height: the render size (the HDR and depth images' size).
  TransparentPass(vk::Context& context, std::uint32_t width, std::uint32_t height);

  struct Inputs {
    const vk::Image& depth;  // sampled by compute
    const vk::Image& hdr;    // lit, as the lighting pass leaves it
    VkBuffer frameConstants, objectConstants, indices, vertices, surfaces;
    VkSampler textureSampler;
    glm::mat4 worldViewProjection;  // the world layer's, for each object's screen rectangle
    glm::vec2 depthRange;           // the world layer's viewport depth range
    bool reversedZ;
  };
  struct Object {
    std::uint32_t index;          // into the object constants
    std::uint32_t triangleCount;  // of its mesh
    BoundingSphere bounds;        // in the world
    VkImageView baseColor, normalMap;  // its textures or the 1x1 defaults
  };
  // `backToFront`: the transparent objects, farthest first (the order they are composited in), at least one;
  // the first one's dispatch runs over the whole image and writes every pixel's coverage.
  void record(VkCommandBuffer cmd, const Inputs& inputs, std::span<const Object> backToFront);

  // Red: the coverage of the last recorded frame (RGBA8).
  const vk::Image& coverage() const { return coverage_; }
  static constexpr vk::ImageState kCoverageState = vk::kComputeWrite;

  // The render tiles [min, max) whose pixel centres the sphere's projection can reach (all of them when the
  // sphere reaches the eye plane), clamped to the screen; empty (min == max) when off screen.
  static glm::uvec4 tileRect(const glm::mat4& viewProjection, const BoundingSphere& bounds, std::uint32_t width,
                             std::uint32_t height);

 private:
  vk::Context& context_;
  std::uint32_t width_, height_;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;
  vk::Unique<VkSampler> nearest_;
  vk::Image coverage_;
};

}  // namespace s3d::renderer::detail
