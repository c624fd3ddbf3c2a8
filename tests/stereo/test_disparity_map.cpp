// Nonlinear depth-to-parallax mapping (disparity_map.h): the per-frame curve is monotonic, exact at its control
// points, keeps the frame's parallax range and the screen plane, gives the populated depths more disparity than
// the linear mapping, and the GPU pass maps every pixel as the C++ reference does.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "s3d/stereo/disparity_map.h"
#include "s3d/stereo/disparity_map_pass.h"
#include "s3d/stereo/guard_band.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

constexpr float kSky = std::numeric_limits<float>::infinity();

// A corridor-like frame: a quarter of the pixels on walls from 1 to 3 m, half on a far wall near 40 m, a
// quarter sky (the empty depths between 3 and 40 m and beyond are the gaps the map should compress).
DepthImage corridor() {
  DepthImage depth(64, 16);
  for (std::uint32_t y = 0; y < 16; ++y)
    for (std::uint32_t x = 0; x < 64; ++x)
      *depth.at(x, y) = y < 4 ? kSky : y < 12 ? 38.0f + 0.25f * float(x % 16) : 1.0f + 2.0f * float(x) / 63.0f;
  return depth;
}

gpu::DisparityMapConstants corridorMap(float zeroParallax = 1.0f) {
  return nonlinearDisparityMap(reduceDepthRangeReference(corridor()), zeroParallax);
}

TEST(DisparityMap, MappingNamesParseAndUnknownOnesAreRefused) {
  EXPECT_EQ(parseDisparityMapping("linear"), DisparityMapping::Linear);
  EXPECT_EQ(parseDisparityMapping(disparityMappingName(DisparityMapping::Nonlinear)), DisparityMapping::Nonlinear);
  try {
    (void)parseDisparityMapping("log");
    FAIL();
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("linear, nonlinear"), std::string::npos);
  }
}

TEST(DisparityMap, TheLinearMappingLeavesEveryDepthBitForBit) {
  const gpu::DisparityMapConstants identity = disparityMapFor(DisparityMapping::Linear, reduceDepthRangeReference(corridor()), 1.0f);
  for (float depth : {0.3f, 1.0f, 3.0f, 1e6f, kSky, 0.0f, -2.0f})
    EXPECT_EQ(std::bit_cast<std::uint32_t>(gpu::mappedDepth(identity, depth)), std::bit_cast<std::uint32_t>(depth));
  EXPECT_TRUE(std::isnan(gpu::mappedDepth(identity, std::numeric_limits<float>::quiet_NaN())));
}

TEST(DisparityMap, TheNonlinearMapIsExactAtItsControlPoints) {
  const gpu::DisparityMapConstants map = corridorMap();
  ASSERT_GE(map.knotCount, 5);
  for (int i = 0; i < map.knotCount; ++i)
    EXPECT_EQ(gpu::mapInverseDepth(map, map.inverseDepth[i]), map.mapped[i]) << "knot " << i;
}

TEST(DisparityMap, TheNonlinearMapIsStrictlyMonotonic) {
  const gpu::DisparityMapConstants map = corridorMap();
  for (int i = 1; i < map.knotCount; ++i) {
    EXPECT_GT(map.inverseDepth[i], map.inverseDepth[i - 1]) << i;
    EXPECT_GT(map.mapped[i], map.mapped[i - 1]) << i;
    EXPECT_GT(map.slope[i - 1], 0.0f) << i;
  }
  // w(u) over 200000 inverse depths from beyond the sky's side to beyond the nearest: never falls, and the
  // depth it gives never comes nearer as the input recedes (0.05 % apart: well above float rounding).
  float previous = -1.0f;
  for (int k = 0; k <= 200000; ++k) {
    const float u = 1.2f * float(k) / 200000.0f;
    const float w = gpu::mapInverseDepth(map, u);
    EXPECT_GE(w, previous) << u;
    previous = w;
  }
  float previousDepth = 0.0f;
  for (float depth = 0.5f; depth < 1e4f; depth *= 1.0005f) {
    const float mapped = gpu::mappedDepth(map, depth);
    EXPECT_GT(mapped, previousDepth) << depth;
    previousDepth = mapped;
  }
}

TEST(DisparityMap, TheNearestDepthAndTheSkyStayWhereTheyAre) {
  // The frame's parallax range is the linear mapping's: the disparity budget's fit holds as it is.
  const gpu::DisparityMapConstants map = corridorMap();
  EXPECT_EQ(gpu::mappedDepth(map, 1.0f), 1.0f);
  EXPECT_EQ(gpu::mappedDepth(map, kSky), kSky);
  EXPECT_EQ(gpu::mappedDepth(map, 0.7f), 0.7f);  // nearer than the frame (an eye-only surface): unchanged
}

TEST(DisparityMap, WithoutSkyTheFarthestDepthStaysWhereItIs) {
  DepthImage depth = corridor();
  for (float& value : depth.pixels) value = std::isinf(value) ? 60.0f : value;
  const gpu::DisparityMapConstants map = nonlinearDisparityMap(reduceDepthRangeReference(depth), 1.0f);
  EXPECT_EQ(gpu::mappedDepth(map, 60.0f), 60.0f);
  EXPECT_EQ(gpu::mappedDepth(map, 1.0f), 1.0f);
  EXPECT_NE(gpu::mappedDepth(map, 2.0f), 2.0f);  // in between it does map
}

TEST(DisparityMap, AZeroParallaxPlaneInsideTheRangeIsAFixedPointSoNoPixelCrossesIt) {
  // Negative parallax allowed: the plane at 2 m, inside the 1..40 m range.
  const gpu::DisparityMapConstants map = corridorMap(2.0f);
  EXPECT_EQ(gpu::mappedDepth(map, 2.0f), 2.0f);
  for (float depth = 1.0f; depth < 60.0f; depth *= 1.01f)
    EXPECT_EQ(gpu::mappedDepth(map, depth) < 2.0f, depth < 2.0f) << depth;
}

TEST(DisparityMap, TheGuardBandOfTheFramesParametersCoversEveryMappedDepth) {
  // `s3d render` sizes the guard band from maxSeparation, the zero-parallax distance and the nearest depth allowed
  // (guard_band.h), before the map exists; the map keeps the frame's nearest and farthest depth, so no mapped depth
  // needs more displacement than the band gives. The plane at the nearest depth (1 m, no negative parallax) and
  // inside the range (2 m, negative parallax down to the nearest depth); depths swept from the nearest to 1e5 m
  // and the sky. Tolerance 1e-6 of the bound: float depths.
  constexpr double kSeparation = 0.03;
  constexpr std::uint32_t kWidthPx = 1280;
  for (const float zeroParallax : {1.0f, 2.0f}) {
    const gpu::DisparityMapConstants map = corridorMap(zeroParallax);
    const double bound = maxDisplacement(kSeparation, zeroParallax, 1.0);
    const GuardBand band = guardBandFor(kSeparation, zeroParallax, 1.0, kWidthPx, 1u << 30);
    ASSERT_FALSE(band.capped);
    std::vector<float> depths{kSky};
    for (float depth = 1.0f; depth < 1e5f; depth *= 1.001f) depths.push_back(depth);
    for (const float depth : depths) {
      const double displacement = std::abs(
          double(gpu::parallaxFromDepth(float(kSeparation), zeroParallax, gpu::mappedDepth(map, depth))));
      EXPECT_LE(displacement, bound * (1.0 + 1e-6)) << "depth " << depth << ", plane " << zeroParallax;
      EXPECT_LE(displacement * kWidthPx, double(band.columns - 1) + 1e-3) << "depth " << depth;
    }
  }
}

TEST(DisparityMap, ThePopulatedDepthsGetMoreOfTheParallaxRangeThanTheLinearMapping) {
  // Parallax 1 - zpp / d (zpp = the nearest depth, 1 m): the sky at 1, the nearest pixel at 0. Linearly the
  // far wall at 38 m is already at 0.974: the empty depths behind it take 2.6 % of the range and the 3..38 m gap
  // 30 %. Mapped, the gap behind the far wall shrinks and the walls' own spans grow.
  const gpu::DisparityMapConstants map = corridorMap();
  auto parallax = [&](float depth) { return 1.0 - 1.0 / double(gpu::mappedDepth(map, depth)); };
  auto linear = [](float depth) { return 1.0 - 1.0 / double(depth); };
  EXPECT_LT(1.0 - parallax(41.75f), 1.0 - linear(41.75f));                     // the empty depths behind it
  EXPECT_GT(parallax(41.75f) - parallax(38.0f), linear(41.75f) - linear(38.0f));  // the far wall's own span
  EXPECT_GT(parallax(3.0f) - parallax(1.0f), linear(3.0f) - linear(1.0f));        // the near walls' span
  EXPECT_LT(parallax(38.0f) - parallax(3.0f), linear(38.0f) - linear(3.0f));      // the empty gap between them
}

TEST(DisparityMap, AStrengthOutsideItsRangeIsRefused) {
  const DepthRange range = reduceDepthRangeReference(corridor());
  EXPECT_THROW(nonlinearDisparityMap(range, 1.0f, 0.95f), std::invalid_argument);
  EXPECT_THROW(nonlinearDisparityMap(range, 1.0f, -0.1f), std::invalid_argument);
  EXPECT_THROW(nonlinearDisparityMap(range, 0.0f), std::invalid_argument);
  const gpu::DisparityMapConstants none = nonlinearDisparityMap(range, 1.0f, 0.0f);  // strength 0: linear
  for (float depth : {1.5f, 2.5f, 39.0f}) EXPECT_NEAR(gpu::mappedDepth(none, depth), depth, depth * 1e-6f);
}

TEST(DisparityMap, AFrameOfOneDepthGetsTheIdentity) {
  EXPECT_LT(nonlinearDisparityMap(reduceDepthRangeReference(DepthImage(8, 8, 3.0f)), 3.0f).knotCount, 2);
  EXPECT_LT(nonlinearDisparityMap(reduceDepthRangeReference(DepthImage(8, 8, kSky)), 3.0f).knotCount, 2);
}

TEST(DisparityMap, ItsSegmentsReproduceTheMapAtTheirEnds) {
  const gpu::DisparityMapConstants map = corridorMap();
  const std::vector<DisparityMapSegment> segments = disparityMapSegments(map);
  ASSERT_EQ(int(segments.size()), map.knotCount - 1);
  EXPECT_EQ(segments.front().inverseDepthBegin, 0.0);
  EXPECT_TRUE(std::isinf(segments.back().inverseDepthEnd));
  for (int i = 0; i + 1 < map.knotCount; ++i) {
    const DisparityMapSegment& s = segments[i];
    for (int end : {i, i + 1})  // float knots: 1e-6 relative
      EXPECT_NEAR(s.intercept + s.slope * map.inverseDepth[end], map.mapped[end], 1e-6 * map.mapped[end] + 1e-9) << i;
  }
}

class DisparityMapGpu : public test::VulkanTest {};

TEST_F(DisparityMapGpu, MatchesTheReferencePixelByPixel) {
  // 67x41 (not a multiple of the 8x8 groups): log-uniform depths from 0.5 m to 100 km, sky, NaN, zero and
  // negative pixels. GLSL division may be 2.5 ULP off a correctly rounded one (the C++ side): 1e-6 relative.
  DepthImage depth(67, 41);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> exponent(-0.3f, 5.0f);
  std::uniform_int_distribution<int> kind(0, 19);
  for (float& value : depth.pixels) {
    const int k = kind(random);
    value = k == 0 ? kSky : k == 1 ? std::numeric_limits<float>::quiet_NaN() : k == 2 ? (random() % 2 ? 0.0f : -3.0f)
                                                                                     : std::pow(10.0f, exponent(random));
  }
  const gpu::DisparityMapConstants map = nonlinearDisparityMap(reduceDepthRangeReference(depth), 0.5f);
  ASSERT_GE(map.knotCount, 5);
  const DepthImage expected = mappedDepthImage(depth, map);
  const DepthImage gpu = mapDepthOnGpu(context(), depth, map);
  int differing = 0;
  for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
    const float e = expected.pixels[i], g = gpu.pixels[i];
    if (std::isnan(e) || std::isinf(e) || !(e > 0.0f)) {
      differing += std::isnan(e) ? !std::isnan(g) : std::bit_cast<std::uint32_t>(e) != std::bit_cast<std::uint32_t>(g);
      continue;
    }
    differing += !(std::abs(g - e) <= 1e-6f * e);
  }
  EXPECT_EQ(differing, 0);
}

TEST_F(DisparityMapGpu, TheStereoPassOnTheMappedDepthMatchesTheReferenceOnIt) {
  // The whole GPU path (map, then the search method) against the C++ one (mapDepthReference, then the C++
  // reference of the pass): the curve reaches every pixel's parallax alike. Tolerance 1 level of 8 bits, as the
  // stereo pass's own test (the filter's fused multiply-add and the unorm store).
  const test::SyntheticView view = test::makeBlockView(96, 24, 5, 0.8f, 8, 6, true);
  StereoParameters parameters{0.05f, 0.8f, -1.0f};
  parameters.method = StereoMethod::Search;
  const gpu::DisparityMapConstants map = nonlinearDisparityMap(reduceDepthRangeReference(view.depth), 0.8f);
  ASSERT_GE(map.knotCount, 3);
  const gpu::StereoConstants c = makeStereoConstants(parameters, 96, 24);
  const StereoPair expected = synthesizeStereoReference(view.color, mappedDepthImage(view.depth, map), c);
  const StereoPair actual = synthesizeStereoOnGpu(context(), view.color, mapDepthOnGpu(context(), view.depth, map), c);
  EXPECT_LE(test::largestChannelDifference(actual.left, expected.left), 1);
  EXPECT_LE(test::largestChannelDifference(actual.right, expected.right), 1);
  // ... and the map changed the eyes: the curve is not the identity on this frame.
  const StereoPair linear = synthesizeStereoReference(view.color, view.depth, c);
  EXPECT_GT(test::largestChannelDifference(linear.left, expected.left), 1);
}

}  // namespace
}  // namespace s3d::stereo
