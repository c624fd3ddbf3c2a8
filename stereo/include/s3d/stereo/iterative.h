#pragma once
// The iterative gather method: per target pixel, solve for the source position whose content the
// parallax moves onto it, by fixed-point iteration with a fixed iteration count, preferring the nearest
// surface when several do and the background when none does. The math is in iterative_shared.h (shared with
// stereo_iterative.comp); this is the plain C++ implementation the GPU pass (iterative_pass.h) is held to.
#include <cstdint>

#include "s3d/image.h"
#include "s3d/stereo/iterative_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

inline constexpr int kDefaultIterations = 6;

// Constants for the parameters at the given image size: separation, zero-parallax distance and edge crop as
// in the seed (parameters.method and searchTaps are not used), the near start's taps spread evenly over
// [0, maxSeparation] in whole pixels, and markFilled 0 (the eyes carry the center's alpha). Throws std::invalid_argument for
// invalid parameters or an iteration count outside [1, S3D_ITERATIVE_MAX_ITERATIONS].
gpu::IterativeConstants makeIterativeConstants(const StereoParameters& parameters, int iterations, std::uint32_t width,
                                               std::uint32_t height);

// Columns each side of a pixel the iterative pass reads (row_tile_shared.h): every fetch is within it.
int rowTileMargin(const gpu::IterativeConstants& constants);

// Solution for one target pixel of one eye.
struct IterativeSample {
  float sourcePosition;  // fractional column of the center view the color is filtered at
  float depth;           // linear depth of the chosen surface (the background's when filled)
  bool filled;           // no iterate mapped onto the target: a disocclusion, filled from the background
};

// The per-pixel solver as the shader runs it (exposed for tests). x must be inside the image.
IterativeSample solveIterativePixel(const DepthImage& linearDepth, int x, int y, Eye eye,
                                    const gpu::IterativeConstants& constants);

// Both eyes, same math and order as the shader. Color is filtered horizontally at the fractional source
// position exactly as the seed does, so maxSeparation = 0 reproduces the center view bit for bit, alpha (the
// weapon mask) included. With constants.markFilled set, alpha is the fill flag instead (0 filled, 255 not).
StereoPair synthesizeIterativeReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                        const gpu::IterativeConstants& constants);

}  // namespace s3d::stereo
