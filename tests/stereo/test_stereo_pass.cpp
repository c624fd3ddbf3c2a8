// The stereo pass: Listing 4.5's behavior, and the GPU pass held to the C++ reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "s3d/stereo/stereo.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

using test::largestChannelDifference;
using test::SyntheticView;

// Random color, depth in 7x5 blocks with sharp edges, a quarter sky.
SyntheticView makeSyntheticView(std::uint32_t width, std::uint32_t height, unsigned seed) {
  return test::makeBlockView(width, height, seed, 0.3f, 7, 5, false);
}

TEST(StereoReference, ParallaxIsZeroAtTheZeroParallaxPlaneAndMaxSeparationAtInfinity) {
  EXPECT_FLOAT_EQ(gpu::parallaxFromDepth(0.02f, 3.0f, 3.0f), 0.0f);
  EXPECT_FLOAT_EQ(gpu::parallaxFromDepth(0.02f, 3.0f, INFINITY), 0.02f);
  EXPECT_FLOAT_EQ(gpu::parallaxFromDepth(0.02f, 3.0f, 1.5f), -0.02f);  // twice as close: out of the screen
}

TEST(StereoReference, SeedConstantsRoundTheTapsToWholePixels) {
  StereoParameters parameters;
  parameters.maxSeparation = 0.02f;  // 25.6 px at 1280
  gpu::StereoConstants c = makeSeedConstants(parameters, 1280, 720);
  EXPECT_EQ(c.tapCount, 3);
  EXPECT_EQ(c.tapOffsetPx[0], 13);  // 12.8
  EXPECT_EQ(c.tapOffsetPx[1], 17);  // 16.896
  EXPECT_EQ(c.tapOffsetPx[2], 26);  // 25.6
  EXPECT_EQ(c.cropBegin, 26);       // crop defaults to maxSeparation, rounded up
  EXPECT_EQ(c.cropEnd, 1280 - 26);
}

TEST(StereoReference, AbsurdParametersAreRejectedWithTheirName) {
  StereoParameters parameters;
  parameters.maxSeparation = 0.9f;
  EXPECT_THROW(
      {
        try {
          validate(parameters);
        } catch (const std::invalid_argument& error) {
          EXPECT_NE(std::string(error.what()).find("maxSeparation"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
  parameters = {};
  parameters.zeroParallaxDistance = NAN;
  EXPECT_THROW(validate(parameters), std::invalid_argument);
  parameters = {};
  parameters.zeroParallaxDistance = 0.0f;
  EXPECT_THROW(validate(parameters), std::invalid_argument);
}

TEST(StereoReference, FlatDepthShiftsTheLeftEyeByTheParallax) {
  // Uniform depth 2 * zpp: parallax = maxSeparation / 2 = 4 px at width 80, so left(x) = center(x + 4).
  ImageRGBA8 center(80, 4);
  for (std::uint32_t y = 0; y < 4; ++y)
    for (std::uint32_t x = 0; x < 80; ++x) center.at(x, y)[0] = std::uint8_t(x * 3);
  DepthImage depth(80, 4, 2.0f);
  StereoParameters parameters{0.1f, 1.0f, -1.0f};
  StereoPair pair = synthesizeStereoReference(center, depth, makeSeedConstants(parameters, 80, 4));
  EXPECT_EQ(pair.left.at(40, 1)[0], center.at(44, 1)[0]);
  EXPECT_EQ(pair.right.at(40, 1)[0], center.at(36, 1)[0]);
  EXPECT_EQ(pair.left.at(3, 1)[0], 0);  // inside the 8-column crop
}

TEST(StereoReference, ANearOccluderInTheSearchRangeShrinksTheParallax) {
  // Listing 4.5's occlusion rule: the minimum depth over the taps wins, so background pixels whose search
  // range reaches a near object take the object's (smaller) parallax instead of sampling across it.
  ImageRGBA8 center(100, 1);
  for (std::uint32_t x = 0; x < 100; ++x) center.at(x, 0)[0] = std::uint8_t(2 * x);
  DepthImage depth(100, 1, INFINITY);
  for (std::uint32_t x = 50; x < 60; ++x) *depth.at(x, 0) = 1.0f;  // at the zero-parallax plane
  StereoParameters parameters{0.1f, 1.0f, 0.0f};                  // taps at 5, 7 and 10 px
  StereoPair pair = synthesizeStereoReference(center, depth, makeSeedConstants(parameters, 100, 1));
  EXPECT_EQ(pair.left.at(45, 0)[0], center.at(45, 0)[0]);  // a tap hits the occluder: parallax 0
  EXPECT_EQ(pair.left.at(30, 0)[0], center.at(40, 0)[0]);  // only sky in range: parallax = maxSeparation
}

class StereoPassGpu : public test::VulkanTest {};

TEST_F(StereoPassGpu, MatchesTheCppReferenceWithinOneLevel) {
  // Tolerance 1 level of 8 bits: the GPU may fuse the filter's multiply-add and round the unorm store
  // differently from std::lround; everything else (taps, depth, crop) is integer-exact.
  for (auto [width, height, separation] : {std::tuple{64u, 32u, 0.05f}, std::tuple{37u, 11u, 0.1f}, std::tuple{128u, 9u, 0.02f}}) {
    SyntheticView view = makeSyntheticView(width, height, width);
    StereoParameters parameters{separation, 2.0f, -1.0f};
    gpu::StereoConstants c = makeSeedConstants(parameters, width, height);
    StereoPair expected = synthesizeStereoReference(view.color, view.depth, c);
    StereoPair actual = synthesizeStereoOnGpu(context(), view.color, view.depth, c);
    EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1) << width << "x" << height;
    EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1) << width << "x" << height;
  }
}

TEST_F(StereoPassGpu, ZeroSeparationReproducesTheCenterViewBitForBit) {
  SyntheticView view = makeSyntheticView(61, 17, 7);
  StereoParameters parameters{0.0f, 2.0f, 0.0f};
  gpu::StereoConstants c = makeSeedConstants(parameters, 61, 17);
  StereoPair pair = synthesizeStereoOnGpu(context(), view.color, view.depth, c);
  EXPECT_EQ(pair.left.pixels, view.color.pixels);
  EXPECT_EQ(pair.right.pixels, view.color.pixels);
  StereoPair reference = synthesizeStereoReference(view.color, view.depth, c);
  EXPECT_EQ(reference.left.pixels, view.color.pixels);
}

}  // namespace
}  // namespace s3d::stereo

namespace s3d::stereo {
namespace {

TEST(StereoSearch, TapsAreSpreadEvenlyOverTheSeparationInWholePixels) {
  StereoParameters parameters;
  parameters.method = StereoMethod::Search;
  parameters.searchTaps = 4;
  parameters.maxSeparation = 0.1f;  // 10 px at width 100
  gpu::StereoConstants c = makeStereoConstants(parameters, 100, 10);
  ASSERT_EQ(c.tapCount, 4);
  EXPECT_EQ(c.tapOffsetPx[0], 3);  // 2.5 rounds up
  EXPECT_EQ(c.tapOffsetPx[1], 5);
  EXPECT_EQ(c.tapOffsetPx[2], 8);  // 7.5 rounds up
  EXPECT_EQ(c.tapOffsetPx[3], 10);
}

TEST(StereoSearch, RepeatedOffsetsAreDroppedWhenTheSeparationIsNarrow) {
  StereoParameters parameters;
  parameters.method = StereoMethod::Search;
  parameters.searchTaps = 16;
  parameters.maxSeparation = 0.03f;  // 3 px at width 100: only offsets 0..3 exist
  gpu::StereoConstants c = makeStereoConstants(parameters, 100, 10);
  EXPECT_LE(c.tapCount, 4);
  for (int i = 1; i < c.tapCount; ++i) EXPECT_LT(c.tapOffsetPx[i - 1], c.tapOffsetPx[i]);
}

TEST(StereoSearch, AThinOccluderBetweenTheSeedsTapsIsFoundBySearch) {
  // A 1 px occluder at offset 6 of a 10 px separation: the seed's taps (5, 7, 10) step over it.
  DepthImage depth(40, 1, INFINITY);
  *depth.at(26, 0) = 1.0f;
  ImageRGBA8 center(40, 1);
  for (std::uint32_t x = 0; x < 40; ++x) center.at(x, 0)[0] = std::uint8_t(5 * x);
  StereoParameters parameters{0.25f, 1.0f, 0.0f};  // 10 px at width 40
  StereoParameters search = parameters;
  search.method = StereoMethod::Search;
  search.searchTaps = 10;
  StereoPair seed = synthesizeStereoReference(center, depth, makeStereoConstants(parameters, 40, 1));
  StereoPair found = synthesizeStereoReference(center, depth, makeStereoConstants(search, 40, 1));
  EXPECT_EQ(seed.left.at(20, 0)[0], center.at(30, 0)[0]);   // seed: sky parallax, samples across the occluder
  EXPECT_EQ(found.left.at(20, 0)[0], center.at(20, 0)[0]);  // search: the occluder's zero parallax
}

TEST(StereoSearch, UnknownMethodAndTapCountsAreRejected) {
  EXPECT_THROW(parseStereoMethod("magic"), std::invalid_argument);
  StereoParameters parameters;
  parameters.method = StereoMethod::Search;
  parameters.searchTaps = 0;
  EXPECT_THROW(validate(parameters), std::invalid_argument);
  parameters.searchTaps = S3D_STEREO_MAX_TAPS + 1;
  EXPECT_THROW(validate(parameters), std::invalid_argument);
}

class StereoSearchGpu : public test::VulkanTest {};

TEST_F(StereoSearchGpu, MatchesTheCppReferenceWithinOneLevel) {
  // Same shader as the seed with other taps; same tolerance and reason.
  SyntheticView view = makeSyntheticView(96, 24, 11);
  StereoParameters parameters{0.06f, 2.0f, -1.0f};
  parameters.method = StereoMethod::Search;
  parameters.searchTaps = S3D_STEREO_MAX_TAPS;
  gpu::StereoConstants c = makeStereoConstants(parameters, 96, 24);
  StereoPair expected = synthesizeStereoReference(view.color, view.depth, c);
  StereoPair actual = synthesizeStereoOnGpu(context(), view.color, view.depth, c);
  EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1);
  EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1);
}

}  // namespace
}  // namespace s3d::stereo

namespace s3d::stereo {
namespace {

class StereoHardCasesGpu : public test::VulkanTest {};

TEST_F(StereoHardCasesGpu, InvalidDepthIsReadAsTheZeroParallaxPlaneOnGpuAndCpu) {
  // NaN, zero and negative depth carry no information: read as the zero-parallax distance, so a
  // neighbourhood of such pixels stays in place; never NaN or garbage. Exact: parallax is exactly 0.
  SyntheticView view = makeSyntheticView(40, 6, 3);
  for (std::uint32_t x = 0; x < 40; ++x) *view.depth.at(x, 2) = (x % 3 == 0) ? NAN : (x % 3 == 1) ? 0.0f : -5.0f;
  StereoParameters parameters{0.05f, 2.0f, 0.0f};
  gpu::StereoConstants c = makeStereoConstants(parameters, 40, 6);
  StereoPair gpu = synthesizeStereoOnGpu(context(), view.color, view.depth, c);
  StereoPair cpu = synthesizeStereoReference(view.color, view.depth, c);
  for (std::uint32_t x = 0; x < 40; ++x)
    for (int channel = 0; channel < 4; ++channel) {
      EXPECT_EQ(gpu.left.at(x, 2)[channel], view.color.at(x, 2)[channel]) << x;
      EXPECT_EQ(cpu.left.at(x, 2)[channel], view.color.at(x, 2)[channel]) << x;
    }
}

TEST(StereoHardCases, SkyEverywhereShiftsByExactlyMaxSeparation) {
  // +inf depth: parallax = maxSeparation exactly (never NaN); 0.1 of 50 px = 5 px.
  ImageRGBA8 center(50, 1);
  for (std::uint32_t x = 0; x < 50; ++x) center.at(x, 0)[0] = std::uint8_t(x * 5);
  DepthImage sky(50, 1, INFINITY);
  StereoPair pair = synthesizeStereoReference(center, sky, makeStereoConstants({0.1f, 1.0f, 0.0f}, 50, 1));
  for (std::uint32_t x = 0; x < 45; ++x) EXPECT_EQ(pair.left.at(x, 0)[0], center.at(x + 5, 0)[0]) << x;
}

TEST(StereoHardCases, OneByOneImageIsItsOwnEyes) {
  ImageRGBA8 center(1, 1, 77);
  DepthImage depth(1, 1, 3.0f);
  StereoPair pair = synthesizeStereoReference(center, depth, makeStereoConstants({0.02f, 1.0f, 0.0f}, 1, 1));
  EXPECT_EQ(pair.left.pixels, center.pixels);  // every tap and sample clamps to the only pixel
}

}  // namespace
}  // namespace s3d::stereo
