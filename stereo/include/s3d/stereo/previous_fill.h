#pragma once
// The previous-frame fill (previous_fill_shared.h): the forward method's disocclusions filled from the previous
// frame's eyes, reprojected with their depth and the camera's motion. The plain C++ implementation the GPU pass
// (previous_fill_pass.h) is held to.
#include <array>
#include <cstdint>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/previous_fill_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// What one eye showed in a frame and the linear depth of it (0 in the cropped columns): the next frame's history.
struct EyeHistory {
  ImageRGBA8 color;
  DepthImage depth;
};

// One eye's constants from the forward method's (size, crop, edge search) and the eye's motion.
gpu::PreviousFillConstants makePreviousFillConstants(const gpu::ForwardConstants& forward, const gpu::EyeMotion& motion,
                                                     bool hasHistory);

struct PreviousFillCounts {
  std::uint64_t holePixels = 0;          // disoccluded eye pixels inside the crop
  std::uint64_t filledFromPrevious = 0;  // ... of them filled from the previous frame
};

// One eye: `eye` is what the forward method wrote, `keys` its z-buffer (forwardSplatRow, row after row); the holes
// are filled in place from `previous` (ignored unless constants.hasHistory), and this frame's history is returned.
EyeHistory fillFromPreviousFrameReference(ImageRGBA8& eye, const std::vector<std::uint32_t>& keys,
                                          const EyeHistory* previous, const gpu::PreviousFillConstants& constants,
                                          PreviousFillCounts* counts = nullptr);

struct ForwardWithHistory {
  StereoPair eyes;
  std::array<EyeHistory, 2> history;  // left, right
  std::array<PreviousFillCounts, 2> counts{};
};

// Both eyes of the forward method with the previous frame's eyes filling its disocclusions: the C++ twin of
// ForwardStereoPass followed by PreviousFillPass. `previous` null: the first frame (the forward method's eyes).
ForwardWithHistory synthesizeForwardWithPreviousFrameReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                                               const gpu::ForwardConstants& forward,
                                                               const std::array<gpu::EyeMotion, 2>& motion,
                                                               const std::array<EyeHistory, 2>* previous);

}  // namespace s3d::stereo
