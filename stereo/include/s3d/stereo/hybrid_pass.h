#pragma once
// Hybrid stereo on the GPU: classification (score bins of both eyes and their histograms), the budget's
// threshold per eye, both eyes' render masks, and the per-eye composite of rendered pixels (math in
// hybrid_shared.h, C++ reference in hybrid.h). Nothing is read back between the passes: a frame records
// classify, renders each eye's masked pixels with its own renderer, then composites.
#include <vulkan/vulkan.h>

#include <functional>
#include <optional>

#include "s3d/stereo/detail/base_tap_pipelines.h"
#include "s3d/stereo/hybrid.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

// The classification's workgroups (its invocations per row and chunk of eye pixels) and the mask pass's cells per
// invocation along a row (hybrid_shared.h). Any shape the device can run gives the same bins and masks; only the
// time differs.
struct HybridRowShape {
  int rowGroup = S3D_HYBRID_ROW_GROUP;  // invocations per row; sharing slots, half of them per eye (an even count)
  int chunk = S3D_HYBRID_CHUNK;         // eye pixels per step along the row, per eye
  bool independentRuns = false;  // each invocation classifies its own run alone (the chunk a multiple of the group)
  int maskRun = 1;               // cells per mask-pass invocation: a CPU device loads the thresholds once per run
  bool operator==(const HybridRowShape&) const = default;
};
inline constexpr HybridRowShape kHybridCpuRowShape{S3D_HYBRID_CPU_ROW_GROUP, S3D_HYBRID_CPU_CHUNK, true,
                                                   S3D_HYBRID_CPU_MASK_RUN};
inline constexpr HybridRowShape kHybridFallbackRowShape{S3D_HYBRID_ROW_GROUP, S3D_HYBRID_CHUNK};
inline constexpr HybridRowShape kHybridGpuRowShape{S3D_HYBRID_GPU_ROW_GROUP, S3D_HYBRID_GPU_CHUNK};
// The fast shape for the device: independent runs on a CPU device, many invocations on a GPU (the fallback where
// the device's workgroup or shared-memory limits refuse its own).
HybridRowShape hybridRowShapeFor(const vk::Context& context);
// Whether the device can run `shape` (invocations, shared memory; the chunk and groups positive, a group sharing
// slots even).
bool hybridRowShapeFits(const vk::Context& context, HybridRowShape shape);

class HybridPass {
 public:
  // shape: the device's (hybridRowShapeFor) unless given; throws std::invalid_argument for one the device cannot run.
  explicit HybridPass(const vk::Context& context, std::optional<HybridRowShape> shape = std::nullopt);
  HybridRowShape rowShape() const { return shape_; }

  // One size's intermediate images, created once and reused every frame. R32_UINT but the grid's depth; the bins,
  // row histograms and split offsets are the classification grid's (hybridGridConstants), the masks the image's.
  struct Images {
    int cell = 1;                   // the classification's cell they were made for
    vk::Image gridDepth;            // R32F, each cell's nearest depth (a cell of more than one pixel only)
    vk::Image leftBins, rightBins;  // score bin per cell
    vk::Image histogram;            // S3D_HYBRID_BINS x 2, row 0 the left eye
    vk::Image rowHistograms;        // 2 S3D_HYBRID_BINS x the grid's height: each row's left-eye bins, then right
    // S3D_HYBRID_THRESHOLD_FIELDS x 2: (0, eye) the threshold bin, (1, eye) the masked cell count, (2, eye) the
    // split bin, (3, eye) its masked cells (HybridThreshold), (4, eye) and (5, eye) the row and column of the
    // split's last masked cell
    vk::Image thresholds;
    vk::Image leftMask, rightMask;  // per pixel: 1 where the eye camera renders it
    bool written = false;           // set by recordMasks: later frames wait for the earlier frame's reads
  };
  // cell: the classification's (StereoParameters::hybridCell); recordMasks refuses constants of another.
  Images createImages(std::uint32_t width, std::uint32_t height, int cell) const;

  // Classification, threshold and masks in three dispatches (one workgroup per row of cells, one per eye, one
  // invocation per cell), after the grid's depth for a cell of more than one pixel. linearDepth: the center view's
  // (R32F, GENERAL, written by an earlier compute pass and made visible by the caller). Leaves every image of `images`
  // in vk::kComputeWrite state: a consumer of the masks (the renderer) transitions them to what it reads with.
  // afterEachDispatch (optional) is called right after each of the three dispatches is recorded (a caller's
  // timestamps: classify with the grid's depth before it, threshold, mask).
  void recordMasks(VkCommandBuffer cmd, const vk::Image& linearDepth, Images& images,
                   const gpu::HybridConstants& constants, const std::function<void()>& afterEachDispatch = {}) const;
  // eye (RGBA8) takes renderedEye's (RGBA8) colour where mask is set; all three in VK_IMAGE_LAYOUT_GENERAL with
  // earlier writes made visible by the caller; eye is left in vk::kComputeWrite state.
  void recordComposite(VkCommandBuffer cmd, const vk::Image& eye, const vk::Image& renderedEye, const vk::Image& mask,
                       const gpu::HybridConstants& constants) const;
  // Budget 1's eye rendered whole into `eye` (RGBA8): its cropped columns black, as the displacement leaves them;
  // nothing recorded without a crop. In VK_IMAGE_LAYOUT_GENERAL with earlier writes made visible by the caller;
  // left in vk::kComputeWrite state.
  void recordCropEdges(VkCommandBuffer cmd, const vk::Image& eye, const gpu::HybridConstants& constants) const;

  static HybridHistogram readHistogram(vk::Context& context, const vk::Image& histogram, int row);
  static HybridThreshold readThreshold(vk::Context& context, const vk::Image& thresholds, int row);
  static std::vector<std::uint32_t> readBins(vk::Context& context, const vk::Image& bins);
  static std::vector<std::uint8_t> readMask(vk::Context& context, const vk::Image& mask);

  static constexpr VkFormat kMaskFormat = VK_FORMAT_R32_UINT;

 private:
  const vk::Context* context_;
  HybridRowShape shape_;
  vk::PipelineLayout gridDepthLayout_, classifyLayout_, thresholdLayout_, maskLayout_, compositeLayout_, cropEdgesLayout_;
  detail::BaseTapPipelines classify_;
  vk::Unique<VkPipeline> gridDepth_, threshold_, mask_, composite_, cropEdges_;
};

// What the GPU passes produce for one depth image (tests): bins, histograms, thresholds and masks.
struct HybridGpuResult {
  HybridClassification classification;
  HybridThreshold leftThreshold, rightThreshold;
  std::vector<std::uint8_t> leftMask, rightMask;
};
HybridGpuResult classifyHybridOnGpu(vk::Context& context, const DepthImage& linearDepth,
                                    const gpu::HybridConstants& constants,
                                    std::optional<HybridRowShape> shape = std::nullopt);
// Uploads the images, composites on the GPU and reads the eye back (tests).
ImageRGBA8 compositeHybridOnGpu(vk::Context& context, const ImageRGBA8& eye, const ImageRGBA8& rendered,
                                const std::vector<std::uint8_t>& mask, const gpu::HybridConstants& constants);

}  // namespace s3d::stereo
