#pragma once
// Hybrid stereo, the stereo side: classify the eye pixels a displacement gets wrong (score bins, hybrid_shared.h),
// pick the bins a budget can afford from a histogram, mask those pixels for the renderer, and composite what it
// rendered into the displaced eyes. Plain C++ of the same math as the GPU passes (hybrid_pass.h), which the tests
// hold to it.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/hybrid_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// Histogram of one eye's score bins over the classified (uncropped) pixels.
using HybridHistogram = std::array<std::uint64_t, S3D_HYBRID_BINS>;

struct HybridClassification {
  std::vector<std::uint32_t> leftBins, rightBins;  // per cell of the grid (hybridGridConstants), row-major; 0 outside its crop
  HybridHistogram leftHistogram{}, rightHistogram{};
};

// The budget as a whole number of pixels: budget * classifiedPixels rounded down, and every pixel at budget 1
// whatever the rounding. Throws std::invalid_argument unless budget is in [0, 1].
std::uint32_t hybridPixelCap(float budget, std::uint64_t classifiedPixels);

// The classification's cell for an image `width` pixels wide: parameters.hybridCell, or where that is 0, 2 from
// kHybridCellWidth columns up and 1 below.
inline constexpr std::uint32_t kHybridCellWidth = 1280;
int hybridCellFor(const StereoParameters& parameters, std::uint32_t width);

// Constants for the parameters at the given size: the crop as the stereo pass's, the window = the largest
// parallax the zero-parallax distance allows + 1 px, the cap of parameters.hybridBudget over the crop, a gather
// base's taps, the classification's cell (hybridCellFor) and the score floor's bin.
gpu::HybridConstants makeHybridConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);

// The classification grid's constants for an image's (hybridGridSize): one pixel per cell, the grid's size and
// crop, its window, the taps in whole cells (rounded half up) and the same share of its classified cells as the
// image's cap is of its classified pixels (all of them when the cap takes every pixel). A cell of 1 gives the
// image's own constants.
gpu::HybridConstants hybridGridConstants(const gpu::HybridConstants& image);
// The grid's depth: each cell's nearest sanitized linear depth over its pixels (the nearest surface's parallax
// opens the widest holes, so a cell with an edge is classified as the edge's near side).
DepthImage hybridGridDepthReference(const DepthImage& linearDepth, const gpu::HybridConstants& image);

// The gather base's own stereo constants (its taps, separation, zero-parallax distance, size), for its choice of
// source (gatherSourceColumn); baseTapCount 0 (a base that is no gather) gives no taps.
gpu::StereoConstants hybridBaseGatherConstants(const gpu::HybridConstants& constants);

// What the center view shows at every eye pixel of row y (hybrid_shared.h), at the constants' own resolution (a
// cell of one pixel: hybridGridConstants gives a grid's): each pair of neighbouring center
// texels of the edge-extended row scatters its terms into the pixels it reaches, and the change pairs' landing
// intervals are swept along the row once each way for the nearest boundary.
std::vector<gpu::HybridCoverage> hybridRowCoverageReference(const DepthImage& linearDepth, int y, Eye eye,
                                                             const gpu::HybridConstants& constants);

// The expected error of one eye pixel in pixels of parallax (hybrid_shared.h; a cell of one pixel), and every
// cell's bin: the image's depth classified on its grid (hybridGridDepthReference, hybridGridConstants).
float hybridPixelScoreReference(const DepthImage& linearDepth, int x, int y, Eye eye, const gpu::HybridConstants& constants);
HybridClassification classifyHybridReference(const DepthImage& linearDepth, const gpu::HybridConstants& constants);

// Counted in the classification grid's cells (pixels for a cell of one pixel).
struct HybridThreshold {
  int bin = S3D_HYBRID_NO_PIXEL;  // pixels with bin >= this are rendered
  std::uint64_t maskedPixels = 0;  // all of them, the split bin's share included
  // The bin just below, where the cap falls inside it: its first splitPixels pixels in raster order (inside the
  // crop) are rendered too, so the masked count meets the cap. S3D_HYBRID_NO_PIXEL and 0: no split.
  int splitBin = S3D_HYBRID_NO_PIXEL;
  std::uint64_t splitPixels = 0;
};

// The masked pixels for a cap: whole bins from the highest score down to minimumBin while they stay within
// maskedPixelCap, then as many pixels of the next bin as the cap leaves (its ties split in raster order), so
// min(cap, pixels scored at or above the floor) are masked. Bin 0 (nothing expected wrong) and the bins below
// minimumBin are never masked, unless the cap takes every classified pixel (budget 1): a cap of 0 masks nothing,
// the classified count everything.
HybridThreshold hybridThreshold(const HybridHistogram& histogram, std::uint32_t maskedPixelCap, int minimumBin = 0);

// Per pixel of the image: 1 for the pixels inside the crop whose cell's bin is >= threshold.bin, or whose cell is
// one of the first threshold.splitPixels cells of threshold.splitBin in the grid's crop in raster order; else 0
// (what the renderer shades). bins and the threshold are the grid's (cells), `constants` the image's.
std::vector<std::uint8_t> hybridMaskReference(const std::vector<std::uint32_t>& bins, const HybridThreshold& threshold,
                                              const gpu::HybridConstants& constants);

// Eye pixels whose mask is set take `rendered`'s color (in place); the others keep the displaced color. Display
// (RGBA8) or linear HDR (RGBA32F) eyes alike.
template <typename Channel>
void compositeHybridReference(Image<Channel, 4>& eye, const Image<Channel, 4>& rendered,
                              const std::vector<std::uint8_t>& mask) {
  requireSameSize(eye, rendered, "hybrid composite (eye vs rendered eye)");
  if (mask.size() != eye.pixelCount()) throw std::invalid_argument("hybrid composite: mask size does not match the eye");
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i] != 0)
      for (std::size_t channel = 0; channel < 4; ++channel) eye.pixels[4 * i + channel] = rendered.pixels[4 * i + channel];
}

}  // namespace s3d::stereo
