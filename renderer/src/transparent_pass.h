#pragma once
// The transparent pass: after lighting, the transparent objects are composited over the lit HDR image back to
// front, and their coverage (1 - prod(1 - opacity), the error metrics' transparent region) is written beside it.
// Two implementations of the same blending (RendererOptions::TransparentCompositing; by default picked by the
// device, as the G-buffer's shading is):
//  - GPUs: compute (shaders/transparent.comp), each object one dispatch over the render tiles its bounds cover.
//    On a GPU whose raster side is a small part of the chip a blended raster pass costs the bytes its
//    fragments read and write; compute runs on the whole chip (docs/RESULTS.md, "Transparent pass").
//  - CPU devices: a blended raster pass (shaders/transparent.frag) that shades only covered fragments; there
//    the compute pass is far slower (docs/RESULTS.md, "Transparent pass").
//
// Reads: the opaque device depth (sampled by compute; depth-tested, never written), the frame and object
// constants, the index, vertex and surface buffers, each object's textures. Writes: the HDR image (storage,
// GENERAL; left readable by compute for the resolve) and the coverage image. Synchronization: expects the HDR
// image as the lighting pass leaves it (vk::kComputeWrite) and the depth sampled by compute; leaves the HDR image
// in vk::kComputeRead, the depth as it was and the coverage in coverageState().
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/renderer/renderer_options.h"
#include "s3d/renderer/scene.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer::detail {

class TransparentPass {
 public:
  // width, height: the render size (the HDR and depth images' size). compositing: which implementation
  // (Automatic: compute on GPUs, raster on CPU devices). `geometry`, `geometryLayout`: what the
  // renderer's pipelines drawing scene objects share (geometry.vert, the depth test's comparison), for the raster
  // implementation.
  TransparentPass(vk::Context& context, std::uint32_t width, std::uint32_t height,
                  RendererOptions::TransparentCompositing compositing,
                  const vk::GraphicsPipelineDesc& geometry, VkPipelineLayout geometryLayout);
  bool usesCompute() const { return pipeline_ != VK_NULL_HANDLE; }

  // The scene's transparent objects (world layer) with their meshes' triangle counts (per mesh) and textures;
  // `white` and `flatNormal`: what objects without a texture sample. Kept until the next setScene.
  void setScene(const Scene& scene, std::span<const std::uint32_t> meshTriangleCounts, std::span<const vk::Image> textures,
                const vk::Image& white, const vk::Image& flatNormal);
  bool hasObjects() const { return !objects_.empty(); }

  struct Inputs {
    const vk::Image& depth;  // sampled by compute
    const vk::Image& hdr;    // lit, as the lighting pass leaves it
    VkBuffer frameConstants, objectConstants, indices, vertices, surfaces;
    VkSampler textureSampler;
    glm::mat4 worldView;            // sorts the objects by their origins' view depth, farthest first
    glm::mat4 worldViewProjection;  // the world layer's, for each object's screen rectangle
    glm::vec2 depthRange;           // the world layer's viewport depth range
    bool reversedZ;
    // A masked render's shade mask (R32_UINT, output size, GENERAL; a placeholder otherwise) and whether to
    // composite only the pixels it shades: compute only (a raster pass relies on the depth fill before it).
    VkImageView shadeMask;
    bool masked;
    // The raster implementation: draws these objects in this order with the bound pipeline.
    std::function<void(VkCommandBuffer, const std::vector<std::uint32_t>& objects)> drawObjects;
  };
  // Composites the scene's transparent objects (hasObjects() must hold); the farthest object's dispatch runs over
  // the whole image and writes every pixel's coverage.
  void record(VkCommandBuffer cmd, const Inputs& inputs);

  // Red: the coverage of the last recorded frame (RGBA8), in coverageState().
  const vk::Image& coverage() const { return coverage_; }
  vk::ImageState coverageState() const { return usesCompute() ? vk::kComputeWrite : vk::kColorAttachment; }

  // The render tiles [min, max) whose pixel centres the box's projection can reach (all of them when the box
  // reaches the eye plane), clamped to the screen; empty (min == max) when the box is outside the view volume.
  static glm::uvec4 tileRect(const glm::mat4& viewProjection, const glm::mat4& boxToWorld, std::uint32_t width,
                             std::uint32_t height);

 private:
  struct Object {
    std::uint32_t index;          // into the object constants
    std::uint32_t triangleCount;  // of its mesh
    glm::mat4 boxToWorld;         // its mesh's bounding box as the image of the cube [-1, 1]^3
    glm::vec4 origin;             // of its transform, in the world: its sort key
    VkImageView baseColor, normalMap;  // its textures or the 1x1 defaults
  };
  void recordCompute(VkCommandBuffer cmd, const Inputs& inputs);
  void recordRaster(VkCommandBuffer cmd, const Inputs& inputs);

  vk::Context& context_;
  std::uint32_t width_, height_;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;        // compute (GPUs)
  vk::Unique<VkPipeline> rasterPipeline_;  // blended raster (CPU devices)
  vk::Unique<VkSampler> nearest_;
  vk::Image coverage_;
  std::vector<Object> objects_;                        // the scene's transparent objects, in scene order
  std::vector<std::pair<float, std::size_t>> sorted_;  // per frame: view depth, index into objects_
  std::vector<std::uint32_t> drawOrder_;               // per frame: object indices, farthest first (raster)
};

}  // namespace s3d::renderer::detail
