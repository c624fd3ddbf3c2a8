#pragma once
// Temporal stability of a synthesized eye: how much its error changes from one frame to the next.
#include <cstdint>
#include <vector>

#include "s3d/image.h"

namespace s3d::stereo {

// Mean over a region of |(S_t - S_t-1) - (R_t - R_t-1)| = |e_t - e_t-1| (e = S - R), 8-bit levels averaged over
// R, G and B: the synthesized eye's frame-to-frame change minus the reference's. A static error (a halo that
// stays put) scores 0, as does an exact method under any motion; an error that comes and goes scores its size.
struct FlickerRegion {
  double meanLevels = 0.0;
  std::uint64_t pixelCount = 0;
};

struct FlickerStats {
  FlickerRegion all;           // every compared pixel
  FlickerRegion halo;          // the current frame's halo mask
  FlickerRegion disocclusion;  // the current frame's disocclusion mask
};

// Columns [cropColumns, width - cropColumns) are compared; empty masks select no pixel. All four images share
// one size, each mask is empty or has one entry per pixel. Throws std::invalid_argument otherwise.
FlickerStats temporalFlicker(const ImageRGBA8& synthesized, const ImageRGBA8& previousSynthesized,
                             const ImageRGBA8& reference, const ImageRGBA8& previousReference,
                             std::uint32_t cropColumns, const std::vector<std::uint8_t>& halo,
                             const std::vector<std::uint8_t>& disocclusion);

}  // namespace s3d::stereo
