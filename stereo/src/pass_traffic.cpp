#include "s3d/stereo/pass_traffic.h"

#include <algorithm>
#include <cstdint>

#include "s3d/stereo/forward.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::stereo {

StereoTraffic stereoPassTraffic(const StereoParameters& methodParameters, std::uint32_t width,
                                std::uint32_t height, bool cpuDevice) {
  const StereoParameters parameters = displacementParameters(methodParameters);  // a hybrid's base
  constexpr std::uint64_t kTexelBytes = 4;  // RGBA8 color, R32F depth, RGBA8 eyes
  int depthLoadsPerEye = 0;
  int margin = 0;
  gpu::StereoConstants crop{};
  if (parameters.method == StereoMethod::Forward) {
    // stereo_forward_*.comp per pixel and eye: splat 4 depth loads and about one atomic; resolve the key, 2 depth
    // and 2 color loads (holes more); atomics write the 4-byte z-buffers, the resolve empties the other pair
    // (for the next frame) and writes the eyes.
    makeForwardConstants(parameters, width, height);  // throws for parameters the pass refuses
    const std::uint64_t pixels = std::uint64_t(width) * height;
    StereoTraffic traffic;
    traffic.bytesRead = 2 * pixels * (4 + 1 + 1 + 2 + 2) * kTexelBytes;
    traffic.bytesWritten = 2 * pixels * 3 * kTexelBytes;
    traffic.compulsoryBytes = pixels * 4 * kTexelBytes;
    return traffic;
  }
  if (parameters.method == StereoMethod::Iterative) {
    const gpu::IterativeConstants c = makeIterativeConstants(parameters, parameters.iterations, width, height);
    depthLoadsPerEye = c.startTapCount + 2 * c.iterations;  // stereo_iterative.comp: taps, then two starts x K
    margin = rowTileMargin(c);
    crop.cropBegin = c.cropBegin;
    crop.cropEnd = c.cropEnd;
  } else {
    crop = makeStereoConstants(parameters, width, height);
    depthLoadsPerEye = crop.tapCount;  // stereo_gather.glsl: minDepthOverTaps
    margin = rowTileMargin(crop);
  }
  const std::uint64_t interior = std::uint64_t(crop.cropEnd - crop.cropBegin) * height;
  const std::uint64_t pixels = std::uint64_t(width) * height;
  const std::uint64_t colorLoadsPerEye = 2;  // sampleRow's two texels
  StereoTraffic traffic;
  traffic.rowTiles = usesRowTiles(parameters.kernel, margin, cpuDevice);
  if (traffic.rowTiles) {
    // stereo_row_tile.glsl: each tile with interior columns [begin, end) loads [begin - margin, end + margin)
    // (clipped to the image, margin at most the shared arrays') once, a depth and a color texel per column.
    std::uint64_t loadedColumns = 0;
    for (int tile = 0; tile < int(width); tile += S3D_STEREO_ROW_TILE) {
      const int begin = std::max(tile, crop.cropBegin);
      const int end = std::min({tile + S3D_STEREO_ROW_TILE, crop.cropEnd, int(width)});
      if (begin < end)
        loadedColumns += std::uint64_t(std::min(end + margin, int(width)) - std::max(begin - margin, 0));
    }
    traffic.bytesRead = loadedColumns * height * 2 * kTexelBytes;
  } else {
    traffic.bytesRead = 2 * interior * (std::uint64_t(depthLoadsPerEye) + colorLoadsPerEye) * kTexelBytes;
  }
  traffic.bytesWritten = 2 * pixels * kTexelBytes;  // both eyes, cropped columns too (black)
  traffic.compulsoryBytes = pixels * 4 * kTexelBytes;
  return traffic;
}

}  // namespace s3d::stereo
