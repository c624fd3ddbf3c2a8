#pragma once
// The hybrid's base depth: for each eye pixel, the center view's device depth at the texel the gather base (seed,
// search) filters that pixel from. An eye render that casts rays for its masked pixels only gives this depth to
// the other pixels its ambient occlusion reads (renderer::ShadeMask::uncastDepth). Plain C++ of the GPU pass's
// math (HybridBaseDepthPass), which the tests hold it to.
#include <array>

#include "s3d/image.h"
#include "s3d/stereo/hybrid_shared.h"

namespace s3d::stereo {

// Left and right eye: pixel (x, y) holds deviceDepth at (t, y), t the gather's source column
// (gatherSourceColumn with the constants' base taps) rounded to the nearest texel (ties up) and clamped to the
// row; cropped columns too. linearDepth: the center's (the taps read it); deviceDepth: the center's device depth,
// passed through as it is. Throws std::invalid_argument for images of another size than the constants' or
// constants without a gather base (baseTapCount 0: iterative and forward bases have no source column).
std::array<DepthImage, 2> hybridBaseDepthReference(const DepthImage& linearDepth, const DepthImage& deviceDepth,
                                                   const gpu::HybridConstants& constants);

}  // namespace s3d::stereo
