#pragma once
// Hybrid stereo, the stereo side: classify the eye pixels a displacement gets wrong (score bins, hybrid_shared.h),
// pick the bins a budget can afford from a histogram, and composite rendered pixels into the displaced eyes.
// Plain C++ of the same math as the GPU pass (hybrid_pass.h), which the tests hold to it.
#include <array>
#include <cstdint>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/hybrid_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// Histogram of one eye's score bins over the classified (uncropped) pixels.
using HybridHistogram = std::array<std::uint64_t, S3D_HYBRID_BINS>;

struct HybridClassification {
  std::vector<std::uint32_t> leftBins, rightBins;  // per pixel, row-major; 0 in the cropped columns
  HybridHistogram leftHistogram{}, rightHistogram{};
};

// Constants for the parameters at the given size (crop as the stereo pass; window = the largest parallax the
// zero-parallax distance allows, + 1 px); thresholdBin starts at S3D_HYBRID_NO_PIXEL.
gpu::HybridConstants makeHybridConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);

HybridClassification classifyHybridReference(const DepthImage& linearDepth, const gpu::HybridConstants& constants);

struct HybridThreshold {
  int bin = S3D_HYBRID_NO_PIXEL;  // pixels with bin >= this are rendered
  std::uint64_t maskedPixels = 0;
};

// The lowest threshold whose masked pixels stay within budget * classifiedPixels: the highest scores first, and
// a bin is taken whole or not at all. budget 0 masks nothing, budget 1 everything. budget must be in [0, 1].
HybridThreshold hybridThreshold(const HybridHistogram& histogram, float budget);

// Eye pixels inside the crop whose bin is >= thresholdBin take `rendered`'s color (in place).
void compositeHybridReference(ImageRGBA8& eye, const ImageRGBA8& rendered, const std::vector<std::uint32_t>& bins,
                              const gpu::HybridConstants& constants);

}  // namespace s3d::stereo
