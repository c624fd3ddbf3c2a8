#pragma once
// The forward (scatter) method: every center pixel is moved to where its parallax puts it in each eye, the
// nearest surface wins, and what no pixel reaches is filled from the background side. The math is in
// forward_shared.h (shared with the stereo_forward_*.comp shaders); this is the plain C++ implementation the GPU
// pass (forward_pass.h) is held to.
#include <cstdint>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/forward_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::stereo {

// Constants for the parameters at the given image size: separation, zero-parallax distance and edge crop as in
// the seed (method, taps and iterations are not used). Throws std::invalid_argument for invalid parameters or a
// displacement beyond what the key's offset bits hold (S3D_FORWARD_OFFSET_BIAS - 2 pixels).
gpu::ForwardConstants makeForwardConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);

// One eye row's z-buffer after the splat: per eye column the winning key, or S3D_FORWARD_EMPTY (exposed for
// tests). direction +1 is the left eye, -1 the right.
std::vector<std::uint32_t> forwardSplatRow(const DepthImage& linearDepth, int y, float direction,
                                           const gpu::ForwardConstants& constants);

// What one eye pixel shows: the center row filtered at `position` (the seed's horizontal linear filter) when
// fillCount is 0, else the mean of fillCount center texels from column fillFirst in steps of fillStep (a hole).
struct ForwardSample {
  float position = 0.0f;
  int fillFirst = 0;
  int fillCount = 0;
  int fillStep = 1;
};

// One eye row's samples (the crop not applied), from forwardSplatRow's keys: the C++ twin of the resolve shader.
std::vector<ForwardSample> forwardRowSamples(const DepthImage& linearDepth, int y, float direction,
                                             const gpu::ForwardConstants& constants);

// Both eyes, same math and order as the shaders (held to it pixel by pixel in the tests).
StereoPair synthesizeForwardReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                      const gpu::ForwardConstants& constants);

}  // namespace s3d::stereo
