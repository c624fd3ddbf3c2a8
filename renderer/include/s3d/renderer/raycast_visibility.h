#pragma once
// The ray-cast visibility pass (shaders/raycast_visibility.comp): finds the surface of each masked pixel by
// casting its pixel-centre ray through a SceneBvh in compute, and writes what the raster G-buffer pass writes
// there (visibility id and device depth), so the G-buffer resolve and lighting can shade those pixels without a
// raster pass: compute runs on all of a GPU where the raster side is a small part of it, and an eye needs no
// depth clear. Agreement with the raster pass: docs/DESIGN.md "Ray-cast visibility".
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "s3d/renderer/scene_bvh.h"
#include "s3d/renderer/shade_mask.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::renderer {

// Tiles of S3D_TILE_SIZE pixels to cast, as a buffer of a TileHeader and then one flag word per tile (row by
// row, tilesX per row; nonzero: cast): pixels of other tiles get the cleared depth and id 0. A null buffer: every
// pixel the mask admits. The buffer's writes must be visible to compute shader reads when the pass runs.
struct RaycastRegion {
  VkBuffer tiles = VK_NULL_HANDLE;
  std::uint32_t tilesX = 0;
};

// What cut-outs' alpha test (CutoutCoverage) reads on the GPU, the renderer's scene buffers: its object constants
// (gpu::ObjectConstants), index buffer, surface vertices (gpu::SurfaceVertex) and the texture table and texels of
// the G-buffer resolve (surface_texels.glsl). Null objects: a cut-out's hit is not tested and writes
// S3D_RASTER_SHADED.
struct RaycastCutouts {
  VkBuffer objects = VK_NULL_HANDLE;
  VkBuffer indices = VK_NULL_HANDLE, surfaceVertices = VK_NULL_HANDLE;
  VkBuffer textureTable = VK_NULL_HANDLE, texels = VK_NULL_HANDLE;
};

// How the pass finds each pixel's closest triangle. Bins: the view's screen bins list the set-up triangles that may
// cover their pixels (raycast_shared.h), and a pixel of a complete list tests that list alone; a list past its
// capacity traverses the tree. Binning costs a pass over every triangle per view, so Automatic bins only trees of
// at most S3D_RAYCAST_BIN_AUTO_REFERENCES references per bin of the view (docs/RESULTS.md "Screen bins").
enum class RaycastSearch { Automatic, Bins, Tree };

class RaycastVisibility {
 public:
  explicit RaycastVisibility(vk::Context& context);
  RaycastVisibility(const RaycastVisibility&) = delete;
  RaycastVisibility& operator=(const RaycastVisibility&) = delete;

  // Uploads the tree (device-local buffers); call again when the scene changes. Throws std::invalid_argument for
  // a scene whose visibility ids are wide (R32G32_UINT): the pass writes narrow ids only.
  void setBvh(const SceneBvh& bvh);
  void setSearch(RaycastSearch search) { search_ = search; }
  // Whether a recording at this image size decides pixels by screen bins.
  bool usesBins(std::uint32_t width, std::uint32_t height) const;

  // Records the pass for the pixels of `mask` (ShadeMask's image and threshold; a null image: every pixel):
  // `visibilityIds` (R32_UINT) and `deviceDepth` (R32_SFLOAT), both the mask's size when there is one, created
  // with VK_IMAGE_USAGE_STORAGE_BIT and in VK_IMAGE_LAYOUT_GENERAL, get the masked pixels' ids and depths
  // (SceneBvh::castPixel, with a CutoutCoverage where `cutouts` are given); other pixels are not written, but
  // for a region's (RaycastRegion), and with the mask's uncastDepth they get its depth and id 0 (within the
  // region, when there is one). The caller orders it against earlier and later uses of the images with barriers
  // (it records compute and indirect-argument barriers for its own buffers only: the per-view triangle setup and
  // screen bins). Uses one uniform buffer and one set of bins: one recording in flight at a time. The bins are
  // made at the first recording of a size that uses them (per bin: two layers of a count and
  // S3D_RAYCAST_BIN_CAPACITY entries, 4 bytes each).
  // Throws std::invalid_argument for images of other formats or sizes, or before setBvh.
  void record(VkCommandBuffer cmd, const RaycastCamera& camera, const ShadeMask& mask, const vk::Image& visibilityIds,
              const vk::Image& deviceDepth, const RaycastRegion& region = {}, const RaycastCutouts& cutouts = {});

  // The view's work that no mask decides, recorded ahead of record() in three steps a caller may place beside its
  // own dispatches (the hybrid runs them beside its classification): Setup (every triangle set up for the camera
  // at this image size), Bins (the screen bins), LargeBins (the large triangles' indirect pass, with its own
  // barrier for the indirect arguments). Setup and Bins record no barrier: the caller orders Setup after the
  // previous recording's casts, and Bins after Setup, with compute-to-compute barriers of its own. The next
  // record() for the same camera and size then casts without setting up or binning again (it still orders its
  // casts after LargeBins); for another camera it prepares its own. Throws std::logic_error for a step out of
  // order, std::invalid_argument before setBvh.
  enum class PreparationStep { Setup, Bins, LargeBins };
  void recordPreparation(VkCommandBuffer cmd, PreparationStep step, const RaycastCamera& camera, std::uint32_t width,
                         std::uint32_t height);
  // Whether the next record() for this camera and size casts without setting up (all three steps recorded since
  // the last record() or setBvh).
  bool isPrepared(const RaycastCamera& camera, std::uint32_t width, std::uint32_t height) const {
    return prepared_ == PreparedView{camera, {width, height}};
  }

 private:
  struct PreparedView {
    RaycastCamera camera;
    glm::uvec2 size;
    bool operator==(const PreparedView&) const = default;
  };
  void sizeView(std::uint32_t width, std::uint32_t height);
  void writeCameraConstants(gpu::RaycastConstants& constants, const RaycastCamera& camera, std::uint32_t width,
                            std::uint32_t height) const;
  void requirePreparing(const PreparedView& view, const char* what) const;
  void dispatchSetup(VkCommandBuffer cmd) const;
  void dispatchBins(VkCommandBuffer cmd) const;
  void recordLargeBins(VkCommandBuffer cmd) const;
  void bindBinPass(VkCommandBuffer cmd, VkPipeline pipeline) const;
  VkPipeline alphaTestPipeline();
  void bindSetupLayoutPass(VkCommandBuffer cmd, VkPipeline pipeline, const VkDescriptorBufferInfo& constants,
                           const std::array<VkDescriptorBufferInfo, 4>& buffers, std::span<const std::uint32_t> push) const;
  void sizeBins(std::uint32_t width, std::uint32_t height);

  vk::Context& context_;
  vk::PipelineLayout layout_, setupLayout_;
  vk::Unique<VkPipeline> pipeline_, setupPipeline_;
  vk::Buffer constants_, nodes_, triangles_;
  vk::Buffer snapped_;  // every triangle set up for the recorded view (raycast_setup.comp)
  // The recorded view's screen bins (raycast_bin.comp): counts, lists, and the large triangles' indirect pass.
  vk::Unique<VkPipeline> binPipeline_, largeBinPipeline_;  // in setupLayout_
  vk::Buffer binCounts_, binEntries_, binLarge_;
  glm::uvec2 binsSize_{0, 0};  // the image size the bins were made for
  std::uint32_t binsX_ = 0, binsPerLayer_ = 0;
  bool binning_ = false;  // the recording being made uses bins
  RaycastSearch search_ = RaycastSearch::Automatic;
  std::uint32_t triangleCount_ = 0, firstPersonFirst_ = 0;
  std::uint32_t worldRoot_ = S3D_BVH_NO_ROOT, firstPersonRoot_ = S3D_BVH_NO_ROOT;
  bool hasCutouts_ = false;  // the tree holds cut-out triangles (S3D_BVH_CUTOUT)
  vk::Unique<VkPipeline> alphaTestPipeline_;
  glm::uvec2 packing_{0, 0};
  bool hasBvh_ = false;
  // The view being prepared ahead (Setup recorded), and the one prepared (LargeBins recorded) for record().
  std::optional<PreparedView> preparing_, prepared_;
};

}  // namespace s3d::renderer
