// Numerical hard cases of the stereo pass, each with its tolerance and why: the C++ references
// against double-precision math where the numbers matter, and the GPU passes against the C++ references.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "s3d/gpu/linear_depth.h"
#include "s3d/stereo/hdr_gather.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/iterative_pass.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/sanitize.h"
#include "s3d/stereo/stereo.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

using test::largestChannelDifference;
using test::SyntheticView;

constexpr StereoMethod kMethods[] = {StereoMethod::Seed, StereoMethod::Search, StereoMethod::Iterative};

StereoParameters parametersFor(StereoMethod method, float maxSeparation, float zeroParallaxDistance, float edgeCrop = -1.0f) {
  StereoParameters parameters{maxSeparation, zeroParallaxDistance, edgeCrop};
  parameters.method = method;
  return parameters;
}

StereoPair cpuEyes(const ImageRGBA8& color, const DepthImage& depth, const StereoParameters& p) {
  if (p.method == StereoMethod::Iterative)
    return synthesizeIterativeReference(color, depth, makeIterativeConstants(p, p.iterations, color.width, color.height));
  return synthesizeStereoReference(color, depth, makeStereoConstants(p, color.width, color.height));
}

StereoPair gpuEyes(vk::Context& context, const ImageRGBA8& color, const DepthImage& depth, const StereoParameters& p) {
  if (p.method == StereoMethod::Iterative)
    return synthesizeIterativeOnGpu(context, color, depth, makeIterativeConstants(p, p.iterations, color.width, color.height));
  return synthesizeStereoOnGpu(context, color, depth, makeStereoConstants(p, color.width, color.height));
}

ImageRGBA8 randomColor(std::uint32_t width, std::uint32_t height, unsigned seed) {
  std::mt19937 random(seed);
  ImageRGBA8 color(width, height);
  for (auto& channel : color.pixels) channel = std::uint8_t(random() % 256);
  for (std::size_t i = 3; i < color.pixels.size(); i += 4) color.pixels[i] = 255;
  return color;
}

// The source column in double precision: x + sign * maxSeparation * (1 - zpp / d) * width.
double exactSourceColumn(int x, Eye eye, double maxSeparation, double zpp, double depth, double width) {
  const double parallax = maxSeparation * (1.0 - zpp / depth);
  return eye == Eye::Left ? x + parallax * width : x - parallax * width;
}

// One standard-Z layer over device depth [0, 1] (near 0.1, far 1000, 1.0 is sky), as `s3d convert` reads
// hardware depth: no first-person range.
gpu::LinearDepthParams standardZ() {
  gpu::LinearDepthParams p{};
  p.worldRatio = gpu::projectionRatio(0.1f, 1000.0f, 0.0f, 1.0f);
  p.firstPersonDeviceDepthMax = -1.0f;
  p.skyDeviceDepth = 1.0f;
  p.firstPersonDepthScale = 1.0f;
  return p;
}

// The same world projection with reversed Z (no first-person layer): cleared to 0 for sky.
gpu::LinearDepthParams reversedZ() {
  gpu::LinearDepthParams p = standardZ();
  p.worldRatio = gpu::reversedProjectionRatio(0.1f, 1000.0f, 0.0f, 1.0f);
  p.firstPersonDeviceDepthMax = -1.0f;  // 1 - (-1) = 2: no device depth reads as first-person
  p.skyDeviceDepth = 0.0f;
  p.reversedZ = 1.0f;
  return p;
}

// GPU against C++ for every method: 1 level of 8 bits, because the GPU may fuse the filter's multiply-add and
// round the unorm store differently from std::lround; every tap, texel pick and crop is integer-exact.
class StereoNumericsGpu : public test::VulkanTest {
 protected:
  void expectGpuMatchesCpu(const ImageRGBA8& color, const DepthImage& depth, float maxSeparation, float zpp,
                           float edgeCrop = -1.0f) {
    for (StereoMethod method : kMethods) {
      const StereoParameters p = parametersFor(method, maxSeparation, zpp, edgeCrop);
      const StereoPair expected = cpuEyes(color, depth, p);
      const StereoPair actual = gpuEyes(context(), color, depth, p);
      EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1) << methodName(method);
      EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1) << methodName(method);
    }
  }
};

// --- Depth at the near plane -------------------------------------------------------------------------------

TEST(StereoNumerics, DepthAtTheNearPlaneGivesTheDoublePrecisionSourceColumn) {
  // d = near = 0.1 with zpp 1: parallax = 0.02 (1 - 10) = -0.18 of the width, the largest negative parallax a
  // scene can produce. Tolerance 1e-3 px: a float holds x + p W (|.| < 2000) to 1.2e-4 px, and zpp / d to
  // one ulp. The source lies outside the image for many pixels: sampleRow clamps it to the edge column.
  const DepthImage depth(400, 1, 0.1f);
  const gpu::StereoConstants c = makeStereoConstants(parametersFor(StereoMethod::Seed, 0.02f, 1.0f), 400, 1);
  for (int x = c.cropBegin; x < c.cropEnd; ++x)
    for (Eye eye : {Eye::Left, Eye::Right})
      EXPECT_NEAR(gatherSourceColumn(depth, x, 0, eye, c), exactSourceColumn(x, eye, 0.02, 1.0, double(0.1f), 400.0), 1e-3);
}

TEST_F(StereoNumericsGpu, DepthAtTheNearPlaneMatchesOnGpu) {
  DepthImage depth(96, 6, 0.1f);
  for (std::uint32_t y = 0; y < 6; ++y)
    for (std::uint32_t x = 40; x < 60; ++x) *depth.at(x, y) = 5.0f;  // a far patch among near-plane depth
  expectGpuMatchesCpu(randomColor(96, 6, 1), depth, 0.05f, 1.0f);
}

// --- Sky at infinite depth ------------------------------------------------------------------------------

TEST(StereoNumerics, SkyParallaxIsExactlyMaxSeparationAndNeverNan) {
  // zpp / inf = 0 exactly, so the parallax is maxSeparation to the bit, for maxSeparation 0 too (no 0 * inf).
  for (float separation : {0.0f, 1e-6f, 0.02f, kMaxSeparationLimit})
    for (float zpp : {1e-3f, 1.0f, 500.0f}) {
      const float parallax = gpu::parallaxFromDepth(separation, zpp, INFINITY);
      EXPECT_EQ(parallax, separation) << separation << " " << zpp;
    }
  // Every method moves the sky by maxSeparation * W = 6 px (of 300) exactly, iterative included.
  const DepthImage sky(300, 1, INFINITY);
  for (StereoMethod method : kMethods) {
    const SourceColumns columns = referenceSourceColumns(sky, parametersFor(method, 0.02f, 1.0f));
    for (int x = 6; x < 294; ++x) {
      EXPECT_EQ(columns.left[std::size_t(x)], float(x + 6)) << methodName(method) << " " << x;
      EXPECT_EQ(columns.right[std::size_t(x)], float(x - 6)) << methodName(method) << " " << x;
    }
  }
}

// --- Zero-parallax distance at / beyond the far plane and near zero ----------------------------------------

TEST(StereoNumerics, ZeroParallaxDistanceAtOrBeyondTheFarPlaneIsClampedWithAWarning) {
  for (float zpp : {1000.0f, 5000.0f, 3.0e38f}) {
    const ClampedZeroParallax clamped = clampZeroParallaxDistance(zpp, 0.1f, 1000.0f);
    EXPECT_EQ(clamped.zeroParallaxDistance, kMaxZppFractionOfFar * 1000.0f) << zpp;
    ASSERT_TRUE(clamped.warning) << zpp;
    EXPECT_NE(clamped.warning->find("far plane"), std::string::npos) << *clamped.warning;
    EXPECT_NE(clamped.warning->find("clamped"), std::string::npos) << *clamped.warning;
  }
}

TEST(StereoNumerics, ZeroParallaxDistanceNearZeroIsClampedToTheNearPlaneWithAWarning) {
  for (float zpp : {1e-30f, 1e-6f, 0.05f}) {
    const ClampedZeroParallax clamped = clampZeroParallaxDistance(zpp, 0.1f, 1000.0f);
    EXPECT_EQ(clamped.zeroParallaxDistance, 0.1f) << zpp;
    ASSERT_TRUE(clamped.warning) << zpp;
    EXPECT_NE(clamped.warning->find("near plane"), std::string::npos) << *clamped.warning;
  }
  // Inside the range: untouched, no warning. Zero, negative and NaN stay errors (validate's rule).
  const ClampedZeroParallax inside = clampZeroParallaxDistance(1.0f, 0.1f, 1000.0f);
  EXPECT_EQ(inside.zeroParallaxDistance, 1.0f);
  EXPECT_FALSE(inside.warning);
  for (float bad : {0.0f, -1.0f, NAN, INFINITY})
    EXPECT_THROW(clampZeroParallaxDistance(bad, 0.1f, 1000.0f), std::invalid_argument) << bad;
}

TEST(StereoNumerics, ClampedZeroParallaxDistanceKeepsTheNearPlaneParallaxBounded) {
  // Unclamped, zpp = 1e6 would put the near plane at m (1 - 1e7): 2e5 screen widths. Clamped to 500 it is
  // m (1 - 5000) = -100 widths: large but finite, and the source columns of every method stay finite.
  const float zpp = clampZeroParallaxDistance(1e6f, 0.1f, 1000.0f).zeroParallaxDistance;
  DepthImage depth(64, 1, 0.1f);
  *depth.at(20, 0) = INFINITY;
  for (StereoMethod method : kMethods) {
    const SourceColumns columns = referenceSourceColumns(depth, parametersFor(method, 0.02f, zpp));
    for (std::size_t x = 2; x < 62; ++x) EXPECT_TRUE(std::isfinite(columns.left[x]) && std::isfinite(columns.right[x]));
  }
}

// --- maxSeparation 0 and absurdly large ------------------------------------------------------------------

TEST_F(StereoNumericsGpu, ZeroSeparationIsTheExactIdentityForEveryMethodOnGpuAndCpu) {
  // Exact: every parallax is 0 * (finite or 1) = 0 (NaN and invalid depth are sanitized first), so every
  // source is the pixel itself with filter fraction 0; the HDR gather reproduces the float image bit for bit.
  SyntheticView view = test::makeBlockView(45, 7, 4, 0.1f, 5, 3, true);
  *view.depth.at(3, 2) = NAN;
  *view.depth.at(4, 2) = -INFINITY;
  for (StereoMethod method : kMethods) {
    const StereoParameters p = parametersFor(method, 0.0f, 1.0f);
    EXPECT_EQ(cpuEyes(view.color, view.depth, p).left.pixels, view.color.pixels) << methodName(method);
    const StereoPair gpu = gpuEyes(context(), view.color, view.depth, p);
    EXPECT_EQ(gpu.left.pixels, view.color.pixels) << methodName(method);
    EXPECT_EQ(gpu.right.pixels, view.color.pixels) << methodName(method);
    ImageRGBA32F hdr(45, 7);
    for (std::size_t i = 0; i < hdr.pixels.size(); ++i) hdr.pixels[i] = float(i % 97) * 0.37f;
    EXPECT_EQ(synthesizeHdrReference(hdr, view.depth, p).right.pixels, hdr.pixels) << methodName(method);
  }
}

TEST(StereoNumerics, AbsurdlyLargeSeparationIsRejectedNamingIt) {
  for (float separation : {kMaxSeparationLimit * 1.01f, 1.0f, 1e30f, INFINITY, NAN, -0.01f}) {
    StereoParameters p;
    p.maxSeparation = separation;
    try {
      (void)makeStereoConstants(p, 64, 64);
      ADD_FAILURE() << separation << " accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("maxSeparation"), std::string::npos) << error.what();
    }
  }
  StereoParameters largest;
  largest.maxSeparation = kMaxSeparationLimit;  // the limit itself is allowed
  EXPECT_NO_THROW((void)makeStereoConstants(largest, 64, 64));
}

// --- Reversed-Z and standard-Z -----------------------------------------------------------------------------

TEST(StereoNumerics, ReversedAndStandardZGiveTheSameLinearDepth) {
  // Device depth computed in double, stored as float, read back by Listing 4.2's formula. Standard Z loses
  // precision far away (one float ulp near 1 is d / near * 6e-8 relative: 6e-4 at 1000 m), reversed Z keeps
  // it (float is dense near 0): tolerance 2e-3 relative between the two, 1e-5 for reversed against exact.
  const double n = 0.1, f = 1000.0;
  const gpu::LinearDepthParams standard = standardZ();
  const gpu::LinearDepthParams reversed = reversedZ();
  for (double d : {0.1, 0.1001, 0.5, 1.0, 7.0, 50.0, 300.0, 999.0}) {
    const float standardDevice = float(f / (f - n) - f * n / ((f - n) * d));
    const float reversedDevice = float(n / (f - n) * (f / d - 1.0));
    const float fromStandard = gpu::linearDepthFromDevice(standard, standardDevice);
    const float fromReversed = gpu::linearDepthFromReversedDevice(reversed, reversedDevice);
    EXPECT_NEAR(fromReversed, d, d * 1e-5) << d;
    EXPECT_NEAR(fromStandard, fromReversed, d * 2e-3) << d;
  }
  EXPECT_TRUE(std::isinf(gpu::linearDepthFromReversedDevice(reversed, 0.0f)));  // cleared: sky
  EXPECT_TRUE(std::isinf(gpu::linearDepthFromDevice(standard, 1.0f)));
}

TEST(StereoNumerics, ReversedAndStandardZGiveTheSameEyes) {
  // The same scene depth through both encodings: the linear depths differ by at most 2e-3 relative (above),
  // which moves a source column by m zpp W 2e-3 / d <= 0.03 px here: the eyes agree within 1 level.
  const double n = 0.1, f = 1000.0;
  const gpu::LinearDepthParams standard = standardZ();
  const gpu::LinearDepthParams reversed = reversedZ();
  SyntheticView view = test::makeBlockView(120, 6, 9, 0.5f, 9, 2, true);
  DepthImage fromStandard = view.depth, fromReversed = view.depth;
  for (std::size_t i = 0; i < view.depth.pixels.size(); ++i) {
    const double d = view.depth.pixels[i];
    const float standardDevice = std::isinf(d) ? 1.0f : float(f / (f - n) - f * n / ((f - n) * d));
    const float reversedDevice = std::isinf(d) ? 0.0f : float(n / (f - n) * (f / d - 1.0));
    fromStandard.pixels[i] = gpu::linearDepthFromDevice(standard, standardDevice);
    fromReversed.pixels[i] = gpu::linearDepthFromReversedDevice(reversed, reversedDevice);
  }
  for (StereoMethod method : kMethods) {
    const StereoParameters p = parametersFor(method, 0.05f, 2.0f);
    const StereoPair a = cpuEyes(view.color, fromStandard, p), b = cpuEyes(view.color, fromReversed, p);
    EXPECT_LE(largestChannelDifference(a.left, b.left), 1) << methodName(method);
    EXPECT_LE(largestChannelDifference(a.right, b.right), 1) << methodName(method);
  }
}

// --- 16-, 24- and 32-bit depth -------------------------------------------------------------------------------

TEST(StereoNumerics, DepthQuantizationMovesSourcesByNoMoreThanItsParallaxStep) {
  // Parallax is affine in device depth z: 1 / d = (z - x) / y, so p = m (1 - zpp (z - x) / y) and
  // |dp/dz| = m zpp (f - n) / (n f). Rounding z to k bits (step 1 / (2^k - 1)) moves a source by at most
  // W m zpp (f - n) / (n f) / 2 / (2^k - 1) px: 1e-3 px for 16 bits, 4e-6 px for 24 at 640 px; 32-bit float
  // depth keeps z to half an ulp (<= 3e-8). Each bound gets 2e-3 px for float rounding of the formula itself.
  // Held for the min-depth methods, which are monotone in every depth (rounding is monotone, so the minimum
  // over the taps commutes with it); the iterative method's solution set can change where a residual
  // crosses its tolerance, so it is held to the colors in the next test.
  const double n = 0.1, f = 1000.0, m = 0.02, zpp = 1.0, width = 640.0;
  const gpu::LinearDepthParams params = standardZ();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> logDepth(std::log(0.2), std::log(900.0));
  DepthImage exact(640, 2);
  for (float& d : exact.pixels) d = float(std::exp(logDepth(random)));
  const double slopePx = width * m * zpp * (f - n) / (n * f);
  for (int bits : {16, 24, 32}) {
    DepthImage quantized = exact;
    for (float& d : quantized.pixels) {
      const double z = f / (f - n) - f * n / ((f - n) * double(d));
      const double stored = bits == 32 ? double(float(z)) : std::round(z * (std::exp2(bits) - 1.0)) / (std::exp2(bits) - 1.0);
      d = gpu::linearDepthFromDevice(params, float(stored));
    }
    const double step = bits == 32 ? 6e-8 : 1.0 / (std::exp2(bits) - 1.0);
    const double bound = slopePx * step / 2.0 + 2e-3;
    for (StereoMethod method : {StereoMethod::Seed, StereoMethod::Search}) {
      const StereoParameters p = parametersFor(method, float(m), float(zpp));
      const SourceColumns a = referenceSourceColumns(exact, p), b = referenceSourceColumns(quantized, p);
      double largest = 0.0;
      for (std::size_t i = 0; i < a.left.size(); ++i)
        if (!std::isnan(a.left[i])) largest = std::max({largest, std::abs(double(a.left[i]) - b.left[i]), std::abs(double(a.right[i]) - b.right[i])});
      EXPECT_LE(largest, bound) << bits << " bits, " << methodName(method);
    }
  }
}

TEST(StereoNumerics, DepthQuantizationKeepsTheEyesWithinOneLevelFrom24Bits) {
  // Smooth color (a ramp of 1 level per pixel), so a sub-pixel move of d px changes a level by at most d:
  // 24- and 32-bit depth stay within 1 level for every method, iterative included (its tolerance test sees
  // residuals move by < 1e-3 px). 16 bits may shift the iterative choice on slanted depth: stated, not held.
  const double n = 0.1, f = 1000.0;
  const gpu::LinearDepthParams params = standardZ();
  ImageRGBA8 color(200, 3);
  for (std::uint32_t y = 0; y < 3; ++y)
    for (std::uint32_t x = 0; x < 200; ++x) {
      std::uint8_t* p = color.at(x, y);
      p[0] = p[1] = p[2] = std::uint8_t(x), p[3] = 255;
    }
  DepthImage exact(200, 3);
  for (std::uint32_t y = 0; y < 3; ++y)
    for (std::uint32_t x = 0; x < 200; ++x) *exact.at(x, y) = x < 80 ? 0.7f + 0.01f * float(x) : (x < 120 ? 30.0f : INFINITY);
  for (int bits : {24, 32}) {
    DepthImage quantized = exact;
    for (float& d : quantized.pixels) {
      if (std::isinf(d)) continue;
      const double z = f / (f - n) - f * n / ((f - n) * double(d));
      d = gpu::linearDepthFromDevice(params, bits == 32 ? float(z) : float(std::round(z * (std::exp2(bits) - 1.0)) / (std::exp2(bits) - 1.0)));
    }
    for (StereoMethod method : kMethods) {
      const StereoParameters p = parametersFor(method, 0.02f, 1.0f);
      const StereoPair a = cpuEyes(color, exact, p), b = cpuEyes(color, quantized, p);
      EXPECT_LE(largestChannelDifference(a.left, b.left), 1) << bits << " bits, " << methodName(method);
      EXPECT_LE(largestChannelDifference(a.right, b.right), 1) << bits << " bits, " << methodName(method);
    }
  }
}

// --- The jump between the weapon's depth range and the world's ----------------------------------------------

TEST_F(StereoNumericsGpu, TheWeaponToWorldDepthJumpIsFiniteAndMatchesOnGpu) {
  // Listing 4.3's two device-depth ranges in one row: the weapon (device depth <= 0.1, pushed by 1 + d per
  // seed 4.6.2) next to distant world depth and sky, with the jump at the split itself. Inside the weapon,
  // farther than maxSeparation from its edge, the seed shifts by exactly the pushed depth's parallax.
  gpu::LinearDepthParams params = gpu::makeLinearDepthParams(0.1f, 1000.0f, 0.02f, 4.0f, 0.1f);
  params.firstPersonDepthOffset = 1.0f;
  const float width = 160.0f;
  DepthImage depth(160, 4);
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x = 0; x < 160; ++x) {
      const float device = x < 70 ? 0.05f : (x == 70 ? 0.1f : (x < 140 ? std::nextafter(0.1f, 1.0f) + 0.8f : 1.0f));
      *depth.at(x, y) = gpu::stereoDepthFromDevice(params, device);
    }
  for (float d : depth.pixels) EXPECT_FALSE(std::isnan(d));
  const float weaponDepth = *depth.at(10, 0);
  EXPECT_GT(weaponDepth, 1.0f);  // pushed behind the zero-parallax plane
  const ImageRGBA8 color = randomColor(160, 4, 8);
  expectGpuMatchesCpu(color, depth, 0.05f, 1.0f);
  const gpu::StereoConstants c = makeStereoConstants(parametersFor(StereoMethod::Seed, 0.05f, 1.0f), 160, 4);
  for (int x = 10; x < 60; ++x)
    EXPECT_NEAR(gatherSourceColumn(depth, x, 1, Eye::Left, c), exactSourceColumn(x, Eye::Left, 0.05, 1.0, weaponDepth, width), 1e-3);
}

// --- 1x1, odd-sized and 7680x4320 images -------------------------------------------------------------------

TEST_F(StereoNumericsGpu, OneByOneImageIsItsOwnEyesForEveryMethod) {
  // Every tap and sample clamps to the only pixel; the crop rounds to 0 columns of 1 (min(ceil(m), W/2)).
  const ImageRGBA8 color = randomColor(1, 1, 2);
  for (float depth : {0.1f, 3.0f, INFINITY}) {
    const DepthImage depthImage(1, 1, depth);
    for (StereoMethod method : kMethods) {
      const StereoParameters p = parametersFor(method, 0.02f, 1.0f);
      StereoPair cpu = cpuEyes(color, depthImage, p);
      StereoPair gpu = gpuEyes(context(), color, depthImage, p);
      cpu.left.pixels[3] = gpu.left.pixels[3] = 255;  // the iterative method may mark the pixel as filled
      EXPECT_EQ(cpu.left.pixels, color.pixels) << methodName(method) << " " << depth;
      EXPECT_EQ(gpu.left.pixels, color.pixels) << methodName(method) << " " << depth;
    }
  }
  EXPECT_EQ(compareDisplayImages(color, color, 0).ssim, 1.0);
}

TEST_F(StereoNumericsGpu, OddSizesMatchOnGpu) {
  // Sizes that are not multiples of the 8x8 work group, in both directions.
  for (auto [width, height] : {std::pair{63u, 17u}, std::pair{9u, 33u}, std::pair{131u, 1u}}) {
    const SyntheticView view = test::makeBlockView(width, height, width + height, 0.3f, 5, 3, true);
    expectGpuMatchesCpu(view.color, view.depth, 0.04f, 1.5f);
  }
}

TEST_F(StereoNumericsGpu, EightKWidthAndHeightMatchOnGpuAndInDoublePrecision) {
  // 7680x4320 in two strips: every row of the pass is independent and only the width enters the math (taps,
  // parallax in pixels, crop), so 7680x32 covers 8K's horizontal numerics and 32x4320 its vertical dispatch
  // (540 work groups); the full frame would take minutes through the C++ reference on lavapipe's 2 cores.
  // Columns near 7680 hold a float to 4.9e-4 px: tolerance 2e-3 px against double.
  const SyntheticView wide = test::makeBlockView(7680, 32, 8, 0.3f, 40, 8, true);
  expectGpuMatchesCpu(wide.color, wide.depth, 0.02f, 1.0f);
  const gpu::StereoConstants c = makeStereoConstants(parametersFor(StereoMethod::Search, 0.02f, 1.0f), 7680, 32);
  const DepthImage flat(7680, 1, 4.0f);
  for (int x = c.cropBegin; x < c.cropEnd; x += 97)
    EXPECT_NEAR(gatherSourceColumn(flat, x, 0, Eye::Right, c), exactSourceColumn(x, Eye::Right, 0.02, 1.0, 4.0, 7680.0), 2e-3);
  const SyntheticView tall = test::makeBlockView(32, 4320, 9, 0.3f, 4, 16, true);
  expectGpuMatchesCpu(tall.color, tall.depth, 0.02f, 1.0f, 0.0f);
}

// --- NaN and Inf in color or depth -------------------------------------------------------------------------

TEST(StereoNumerics, NanAndInfInColorAreSanitizedAndCountedAndNeverReachTheEyes) {
  ImageRGBA32F hdr(40, 3, 0.25f);
  hdr.at(10, 1)[0] = NAN;
  hdr.at(11, 1)[1] = INFINITY;
  hdr.at(12, 1)[2] = -INFINITY;
  hdr.at(13, 1)[3] = NAN;
  DepthImage depth(40, 3, 2.0f);
  ImageRGBA32F sanitized = hdr;
  EXPECT_EQ(sanitizeColor(sanitized), 4u);
  EXPECT_EQ(sanitized.at(10, 1)[0], 0.0f);
  EXPECT_EQ(sanitizeColor(sanitized), 0u);  // idempotent
  for (StereoMethod method : kMethods) {
    const HdrStereoPair eyes = synthesizeHdrReference(sanitized, depth, parametersFor(method, 0.05f, 1.0f));
    for (float value : eyes.left.pixels) ASSERT_TRUE(std::isfinite(value)) << methodName(method);
    for (float value : eyes.right.pixels) ASSERT_TRUE(std::isfinite(value)) << methodName(method);
  }
}

TEST_F(StereoNumericsGpu, NanAndInfInDepthAreSanitizedAndCountedOnGpuAndCpu) {
  // NaN, -inf, zero and negative depth read as the zero-parallax plane in every method (gpu::sanitizedDepth);
  // +inf is the sky. So the eyes of the raw depth equal those of the sanitized depth exactly on the CPU, and
  // within 1 level on the GPU; the count is what s3d reports.
  SyntheticView view = test::makeBlockView(70, 5, 12, 0.3f, 6, 2, true);
  const float invalid[] = {NAN, -INFINITY, 0.0f, -2.0f};
  for (std::uint32_t x = 0; x < 70; x += 3) *view.depth.at(x, 2) = invalid[(x / 3) % 4];
  *view.depth.at(1, 0) = NAN;
  DepthImage sanitized = view.depth;
  EXPECT_EQ(countInvalidDepth(view.depth), 25u);
  EXPECT_EQ(sanitizeDepth(sanitized, 1.5f), 25u);
  EXPECT_EQ(countInvalidDepth(sanitized), 0u);
  for (StereoMethod method : kMethods) {
    const StereoParameters p = parametersFor(method, 0.06f, 1.5f);
    const StereoPair raw = cpuEyes(view.color, view.depth, p), clean = cpuEyes(view.color, sanitized, p);
    EXPECT_EQ(raw.left.pixels, clean.left.pixels) << methodName(method);
    EXPECT_EQ(raw.right.pixels, clean.right.pixels) << methodName(method);
    const SourceColumns columns = referenceSourceColumns(view.depth, p);
    for (std::size_t i = 0; i < columns.left.size(); ++i)
      if (!std::isnan(columns.left[i])) {
        EXPECT_TRUE(std::isfinite(columns.left[i]) && std::isfinite(columns.right[i]));
      }
  }
  expectGpuMatchesCpu(view.color, view.depth, 0.06f, 1.5f);
}

// --- A depth edge exactly at the screen border ---------------------------------------------------------------

TEST_F(StereoNumericsGpu, ADepthEdgeAtTheScreenBorderStaysInsideTheImage) {
  // A near object filling the first and last 3 columns against sky, no crop: taps and samples past the
  // border clamp to the edge column, never outside: the seed's right eye at column 0 reads its taps at
  // column 0 (the near object, parallax 0.1 (1 - 1 / 0.5) = -0.1) and so samples column 0 + 0.1 * 50 = 5.
  // GPU within 1 level.
  ImageRGBA8 color = randomColor(50, 4, 6);
  DepthImage depth(50, 4, INFINITY);
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x : {0u, 1u, 2u, 47u, 48u, 49u}) *depth.at(x, y) = 0.5f;
  expectGpuMatchesCpu(color, depth, 0.1f, 1.0f, 0.0f);
  for (StereoMethod method : kMethods) {
    const SourceColumns columns = referenceSourceColumns(depth, parametersFor(method, 0.1f, 1.0f, 0.0f));
    for (float column : columns.left) EXPECT_TRUE(std::isfinite(column)) << methodName(method);
  }
  const StereoPair eyes = cpuEyes(color, depth, parametersFor(StereoMethod::Seed, 0.1f, 1.0f, 0.0f));
  for (int channel = 0; channel < 3; ++channel) EXPECT_EQ(eyes.right.at(0, 1)[channel], color.at(5, 1)[channel]);
  // The halo region reaches the border without writing past it.
  const std::vector<std::uint8_t> halo = haloMask(depth, 5);
  EXPECT_EQ(halo.size(), depth.pixelCount());
  EXPECT_EQ(halo[0], 1);
  EXPECT_EQ(halo[49], 1);
  EXPECT_EQ(halo[25], 0);
}

}  // namespace
}  // namespace s3d::stereo
