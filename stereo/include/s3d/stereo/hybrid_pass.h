#pragma once
// Hybrid stereo on the GPU: the classification pass (score bins of both eyes and their histograms) and the
// per-eye composite of rendered pixels (math in hybrid_shared.h, C++ reference in hybrid.h).
#include <vulkan/vulkan.h>

#include "s3d/stereo/hybrid.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::stereo {

class HybridPass {
 public:
  explicit HybridPass(const vk::Context& context);

  // The images a classification writes: a bin per eye pixel (R32UI) and the histogram (R32UI,
  // S3D_HYBRID_BINS x 2, row 0 the left eye), all in vk::kComputeWrite state after record.
  struct Classification {
    vk::Image leftBins, rightBins, histogram;
  };
  Classification createClassification(std::uint32_t width, std::uint32_t height) const;

  // linearDepth in VK_IMAGE_LAYOUT_GENERAL, readable by compute; the classification's images in any state
  // written by an earlier record (or fresh: `fresh` true).
  void recordClassify(VkCommandBuffer cmd, const vk::Image& linearDepth, const Classification& target, bool fresh,
                      const gpu::HybridConstants& constants) const;
  // eye (RGBA8) is updated in place where bins >= constants.thresholdBin from renderedEye (RGBA8); all in
  // VK_IMAGE_LAYOUT_GENERAL with earlier writes made visible by the caller.
  void recordComposite(VkCommandBuffer cmd, const vk::Image& eye, const vk::Image& renderedEye, const vk::Image& bins,
                       const gpu::HybridConstants& constants) const;

  static HybridHistogram readHistogram(vk::Context& context, const vk::Image& histogram, int row);
  static std::vector<std::uint32_t> readBins(vk::Context& context, const vk::Image& bins);

 private:
  const vk::Context* context_;
  vk::PipelineLayout classifyLayout_, compositeLayout_;
  vk::Unique<VkPipeline> classify_, composite_;
};

// Uploads the depth, classifies it on the GPU and reads bins and histograms back (tests).
HybridClassification classifyHybridOnGpu(vk::Context& context, const DepthImage& linearDepth,
                                         const gpu::HybridConstants& constants);
// Uploads both images, composites on the GPU and reads the eye back (tests).
ImageRGBA8 compositeHybridOnGpu(vk::Context& context, const ImageRGBA8& eye, const ImageRGBA8& rendered,
                                const std::vector<std::uint32_t>& bins, const gpu::HybridConstants& constants);

}  // namespace s3d::stereo
