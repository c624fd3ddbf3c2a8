#pragma once
// The stereo core: parameters, the C++ reference of the stereo pass, and the off-axis eye cameras of the
// two-pass reference. Depends on GLM (and, for the GPU pass in stereo_pass.h, on Vulkan) only.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/image.h"
#include "s3d/stereo/stereo_shared.h"

namespace s3d::stereo {

// Min-depth search patterns of the gather pass (one shader, different taps).
enum class StereoMethod {
  Seed,    // Listing 4.5 exactly: taps at 0.5, 0.66 and 1.0 of maxSeparation
  Search,  // searchTaps taps spread evenly over (0, maxSeparation]: no thin occluder falls between taps
  Iterative,  // fixed-point source search, nearest surface wins, holes filled from the background (iterative.h)
  Forward,    // z-buffered scatter of every pixel with sub-pixel placement, holes filled from the background (forward.h)
  // hybridBase's displacement, then the pixels it gets wrong (ranked, up to hybridBudget of each eye) rendered
  // from the real eye cameras and composited (hybrid.h); needs a renderer, so not for external frames.
  Hybrid,
};

const char* methodName(StereoMethod method);

// Where the depth comes from, for --method auto.
enum class DepthSource {
  Renderer,  // s3d's own frames: the default method (the built-in scenes' measurements)
  External,  // files: photographs' disparity, other programs' depth
};
// --method auto, from measurements (docs/RESULTS.md): forward for external depth or disparity (on the real
// scenes at least the plain forward warp on visible pixels, where every gather method is below it: their
// searches look behind the screen only, and disparity input is all in front of it; on the built-in scenes'
// depth at 1920x1080 the highest SSIM of all methods); the default otherwise.
StereoMethod automaticMethod(DepthSource source);
StereoMethod parseStereoMethod(const std::string& name);  // throws std::invalid_argument listing the choices
// The names parseStereoMethod accepts, in declaration order, for option checks and menus; without hybrid, the
// displacements a hybrid can start from.
std::vector<std::string> stereoMethodNames(bool withHybrid = true);

// How a method's shader walks the image (same results either way, docs/DESIGN.md "Row tiles"). The forward
// method reads them as its two kernels (forward_pass.h): RowTiles is a workgroup per whole row in shared
// memory, PerPixel its dispatches over key images, and Auto is RowTiles where the row fits.
enum class StereoKernel {
  Auto,      // gather methods: PerPixel: row tiles measured slower on lavapipe and on a GPU
             // (docs/RESULTS.md, "Stereo methods"), so they stay opt-in
  PerPixel,  // 8x8 workgroups, every tap and filter texel an image load
  RowTiles,  // a workgroup per run of one row, read once into shared memory; PerPixel where the margin does not
             // fit the shared arrays (above S3D_STEREO_ROW_TILE_MARGIN columns, e.g. 25 % of 2100)
};

const char* kernelName(StereoKernel kernel);
StereoKernel parseStereoKernel(const std::string& name);  // throws std::invalid_argument listing the choices

// How depth becomes parallax (disparity_map.h): the seed's linear m (1 - zpp / d), or through a per-frame
// monotonic curve over the frame's depth distribution that keeps the frame's parallax range.
enum class DisparityMapping {
  Linear,
  Nonlinear,
};

const char* disparityMappingName(DisparityMapping mapping);         // "linear", "nonlinear"
DisparityMapping parseDisparityMapping(const std::string& name);  // throws std::invalid_argument listing them

struct StereoParameters {
  float maxSeparation = 0.02f;        // per-eye displacement at infinity, fraction of the screen width
  float zeroParallaxDistance = 1.0f;  // world units: depth that stays on the screen plane
  float edgeCrop = -1.0f;             // fraction of the width blacked out per side; < 0 means = maxSeparation
  // Default: a 4-tap search, the seed's cost with a higher halo PSNR in every measured case (docs/RESULTS.md,
  // "Stereo methods"); `seed` stays selectable as the baseline.
  StereoMethod method = StereoMethod::Search;
  int searchTaps = 4;  // StereoMethod::Search only, 1..S3D_STEREO_MAX_TAPS
  int iterations = 6;  // StereoMethod::Iterative only, 1..16
  StereoKernel kernel = StereoKernel::Auto;
  // Seed 4.6.2: the first-person weapon's depth as the stereo pass sees it is offset + scale * depth, so it
  // sits behind the screen plane instead of popping out (applied where linear depth is produced).
  float weaponDepthOffset = 1.0f;  // world units
  float weaponDepthScale = 1.0f;
  // StereoMethod::Hybrid only: the displacement it starts from (any other method, with its own taps or
  // iterations above), and the largest share of each eye's pixels rendered from the eye camera: 0 is the base
  // bit for bit, 1 renders every pixel (the two-pass reference). The default 0.6 is the smallest measured budget
  // that gives every built-in scene >= 35 dB whole-image and >= 32 dB halo PSNR in both eyes at 2 % separation
  // on a GPU and on lavapipe (the fence's thin slats need the most); scenes with less to fix mask less
  // (docs/RESULTS.md, "Hybrid stereo").
  StereoMethod hybridBase = StereoMethod::Search;
  float hybridBudget = 0.6f;
  // Hybrid only: the classification's cell in pixels per side, 1 or 2, or 0 to choose by the image's width
  // (hybridCellFor). At 2 each 2x2 block is classified once, from its nearest depth, and masked whole: a quarter of
  // the classification's work, for a few more masked pixels at the same quality from 1280 columns up; at 640x360
  // the fence's 1-2 pixel slats fall below the quality target on 2x2 cells (docs/RESULTS.md, "The classification
  // on 2x2 cells").
  int hybridCell = 0;  // 0 .. kHybridCellLimit
  // Hybrid only: below budget 1, cells whose expected error (the classification's score, pixels of parallax on its
  // grid) lies below this are never rendered, however much of the budget is left. 0.15 keeps the nearness tier's
  // pixels closest to a boundary (its scores fall from 0.2) and every edge band, hole and wrong source: the largest
  // floor at which every built-in scene kept >= 35 dB whole and >= 32 dB halo at the default budget
  // (docs/RESULTS.md, "The score floor").
  float hybridScoreFloor = 0.15f;  // 0 .. kHybridScoreFloorLimit
  // Forward only, over frames: disocclusions take the previous frame's eyes, reprojected with their depth and the
  // camera's motion, where that frame saw them (previous_fill_pass.h); a single frame has no previous one.
  bool previousFrameFill = false;
  // Nonlinear needs the frame's depth distribution (the disparity budget's reduction); the tools apply it.
  DisparityMapping disparityMapping = DisparityMapping::Linear;
};

// The parameters of a hybrid's displacement (parameters.method = hybridBase); any other method as it is.
StereoParameters displacementParameters(StereoParameters parameters);

// Largest accepted maxSeparation / edgeCrop: beyond a quarter of the screen the eyes cannot fuse anything.
inline constexpr float kMaxSeparationLimit = 0.25f;
// Largest accepted hybridCell (2x2 cells) and hybridScoreFloor (pixels of parallax, far above any useful floor).
inline constexpr int kHybridCellLimit = 2;
inline constexpr float kHybridScoreFloorLimit = 32.0f;

// Throws std::invalid_argument naming the parameter when a value is NaN, negative or absurd.
void validate(const StereoParameters& parameters);

// Listing 4.5's depth-search taps, as fractions of maxSeparation.
inline constexpr float kSeedTaps[3] = {0.5f, 0.66f, 1.0f};

// Push constants for the parameters' method at the given image size (taps rounded to whole pixels).
gpu::StereoConstants makeStereoConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);
// Listing 4.5's constants whatever parameters.method says.
gpu::StereoConstants makeSeedConstants(const StereoParameters& parameters, std::uint32_t width, std::uint32_t height);

// Columns each side of a pixel the pass may read (row_tile_shared.h), and whether `kernel` runs on row tiles
// for that margin on a CPU (lavapipe) or GPU device.
int rowTileMargin(const gpu::StereoConstants& constants);
bool usesRowTiles(StereoKernel kernel, int rowTileMarginPx, bool cpuDevice);

enum class Eye { Left, Right };

// The fractional center-view column the seed / search pass filters pixel (x, y) of an eye from: x plus (left
// eye) or minus (right eye) the parallax of the nearest depth over the taps. x must be inside the crop.
float gatherSourceColumn(const DepthImage& linearDepth, int x, int y, Eye eye, const gpu::StereoConstants& constants);

struct StereoPair {
  ImageRGBA8 left;
  ImageRGBA8 right;
};

// Plain C++ implementation of the stereo compute pass (same math, same rounding); the tests hold the GPU to it.
StereoPair synthesizeStereoReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                     const gpu::StereoConstants& constants);


template <typename T>
struct EyeCameraT {
  glm::mat<4, 4, T> view;
  glm::mat<4, 4, T> projection;
};
using EyeCamera = EyeCameraT<float>;

// An off-axis eye: the camera moves by `eyeOffset` (view units) along its x axis and the frustum shifts by
// `frustumShift` in NDC; the left eye moves to -eyeOffset and shifts by +frustumShift, the right mirrors it.
template <typename T>
struct OffAxisTerms {
  T eyeOffset;
  T frustumShift;
};

template <typename T>
EyeCameraT<T> offAxisEyeCamera(const glm::mat<4, 4, T>& centerView, const glm::mat<4, 4, T>& centerProjection, Eye eye,
                               OffAxisTerms<T> terms) {
  const T sign = eye == Eye::Left ? T(1) : T(-1);
  glm::mat<4, 4, T> toEye(T(1));
  toEye[3][0] = sign * terms.eyeOffset;  // the left camera sits at -e, so view-space points move by +e
  EyeCameraT<T> camera{toEye * centerView, centerProjection};
  camera.projection[2][0] += sign * terms.frustumShift;
  return camera;
}

// Two-pass reference: the terms that make a point at linear depth d land exactly
// parallaxFromDepth(maxSeparation, zpp, d) * width away from its center-view position (left eye: to the
// left), for every d. See docs/DESIGN.md: x_ndc(eye) = P00 (X + sign e) / d - P20 must equal
// x_ndc(center) - sign 2 m (1 - zpp / d), so e = 2 m zpp / P00 and s = 2 m.
template <typename T>
OffAxisTerms<T> exactParallaxTerms(T projectionScaleX, T maxSeparation, T zeroParallaxDistance) {
  return {T(2) * maxSeparation * zeroParallaxDistance / projectionScaleX, T(2) * maxSeparation};
}

// The terms for parallax m (1 - zpp w) where w = intercept + slope u is affine in the inverse depth u = 1/d
// (a camera gives exactly A - B u): exactParallaxTerms is slope 1, intercept 0; the pushed weapon's chord and
// the nonlinear mapping's segments (disparity_map.h) are others.
template <typename T>
OffAxisTerms<T> affineInverseDepthTerms(T projectionScaleX, T maxSeparation, T zeroParallaxDistance, T slope,
                                        T intercept) {
  return {T(2) * maxSeparation * zeroParallaxDistance * slope / projectionScaleX,
          T(2) * maxSeparation * (T(1) - zeroParallaxDistance * intercept)};
}

// The first-person layer with its depth pushed (d' = offset + scale d, seed 4.6.2): 1/d' is affine in 1/d only
// when offset = 0, so the reference uses the chord of 1/d' as a function of 1/d over the weapon's depth range
// [nearest, farthest]: exact at both ends (and everywhere when offset = 0), within a fraction of a pixel
// between them (docs/DESIGN.md). Returns {slope, intercept}.
template <typename T>
glm::vec<2, T> pushedInverseDepthChord(T offset, T scale, T nearest, T farthest) {
  auto pushedInverse = [&](T inverseDepth) { return inverseDepth / (offset * inverseDepth + scale); };
  const T uNear = T(1) / nearest, uFar = T(1) / farthest;
  const T slope = uNear > uFar ? (pushedInverse(uNear) - pushedInverse(uFar)) / (uNear - uFar) : T(1) / (offset * uFar + scale) / (offset * uFar + scale) * scale;
  return {slope, pushedInverse(uFar) - slope * uFar};
}

template <typename T>
OffAxisTerms<T> pushedLayerTerms(T projectionScaleX, T maxSeparation, T zeroParallaxDistance, T offset, T scale,
                                 T nearest, T farthest) {
  const glm::vec<2, T> chord = pushedInverseDepthChord(offset, scale, nearest, farthest);
  return affineInverseDepthTerms(projectionScaleX, maxSeparation, zeroParallaxDistance, chord.x, chord.y);
}

// Shorthand for the exact terms.
template <typename T>
EyeCameraT<T> offAxisEyeCamera(const glm::mat<4, 4, T>& centerView, const glm::mat<4, 4, T>& centerProjection, Eye eye,
                               T maxSeparation, T zeroParallaxDistance) {
  return offAxisEyeCamera(centerView, centerProjection, eye,
                          exactParallaxTerms(centerProjection[0][0], maxSeparation, zeroParallaxDistance));
}

}  // namespace s3d::stereo
