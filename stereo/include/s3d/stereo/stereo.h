#pragma once
// The stereo core: parameters, the C++ reference of the stereo pass, and the off-axis eye cameras of the
// two-pass reference. Depends on GLM (and, for the GPU pass in stereo_pass.h, on Vulkan) only.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "s3d/image.h"
#include "s3d/stereo/stereo_shared.h"

namespace s3d::stereo {

// Min-depth search patterns of the gather pass (one shader, different taps).
enum class StereoMethod {
  Seed,    // Listing 4.5 exactly: taps at 0.5, 0.66 and 1.0 of maxSeparation
  Search,  // searchTaps taps spread evenly over (0, maxSeparation]: no thin occluder falls between taps
};

const char* methodName(StereoMethod method);
StereoMethod parseStereoMethod(const std::string& name);  // throws std::invalid_argument listing the choices

struct StereoParameters {
  float maxSeparation = 0.02f;        // per-eye displacement at infinity, fraction of the screen width
  float zeroParallaxDistance = 1.0f;  // world units: depth that stays on the screen plane
  float edgeCrop = -1.0f;             // fraction of the width blacked out per side; < 0 means = maxSeparation
  StereoMethod method = StereoMethod::Seed;
  int searchTaps = 8;  // StereoMethod::Search only, 1..S3D_STEREO_MAX_TAPS
};

// Largest accepted maxSeparation / edgeCrop: beyond a quarter of the screen the eyes cannot fuse anything.
inline constexpr float kMaxSeparationLimit = 0.25f;

// Throws std::invalid_argument naming the parameter when a value is NaN, negative or absurd.
void validate(const StereoParameters& parameters);

// Listing 4.5's depth-search taps, as fractions of maxSeparation.
inline constexpr float kSeedTaps[3] = {0.5f, 0.66f, 1.0f};

// Push constants for the parameters' method at the given image size (taps rounded to whole pixels).
gpu::StereoConstants makeStereoConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);
// Listing 4.5's constants whatever parameters.method says.
gpu::StereoConstants makeSeedConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);

struct StereoPair {
  ImageRGBA8 left;
  ImageRGBA8 right;
};

// Plain C++ implementation of the stereo compute pass (same math, same rounding); the tests hold the GPU to it.
StereoPair synthesizeStereoReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                     const gpu::StereoConstants& constants);

enum class Eye { Left, Right };

template <typename T>
struct EyeCameraT {
  glm::mat<4, 4, T> view;
  glm::mat<4, 4, T> projection;
};
using EyeCamera = EyeCameraT<float>;

// Two-pass reference: an eye camera with a parallel axis and an off-axis frustum such that a point at linear
// depth d lands exactly parallaxFromDepth(maxSeparation, zpp, d) * width away from its center-view position
// (left eye: to the left). See docs/DESIGN.md for the derivation:
//   eye offset e = 2 * maxSeparation * zpp / P[0][0], frustum shift s = 2 * maxSeparation (NDC units).
// Templated so the hard-case tests can check it in double precision.
template <typename T>
EyeCameraT<T> offAxisEyeCamera(const glm::mat<4, 4, T>& centerView, const glm::mat<4, 4, T>& centerProjection,
                               Eye eye, T maxSeparation, T zeroParallaxDistance) {
  // x_ndc(eye) = P00 (X + sign e) / d - P20 must equal x_ndc(center) - sign 2 m (1 - zpp / d) for every depth d:
  // the 1/d terms give e = 2 m zpp / P00, the constant terms P20 = sign 2 m (sign = +1 for the left eye).
  const T sign = eye == Eye::Left ? T(1) : T(-1);
  const T eyeOffset = T(2) * maxSeparation * zeroParallaxDistance / centerProjection[0][0];
  glm::mat<4, 4, T> toEye(T(1));
  toEye[3][0] = sign * eyeOffset;  // the left camera sits at -e, so view-space points move by +e
  EyeCameraT<T> camera{toEye * centerView, centerProjection};
  camera.projection[2][0] += sign * T(2) * maxSeparation;
  return camera;
}

}  // namespace s3d::stereo
