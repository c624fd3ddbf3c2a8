// The iterative gather method: its solver on hand-made depth layers, the GPU pass held to the C++
// implementation, and its error against the two-pass reference next to the seed's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <tuple>

#include "s3d/frame/layered_reference.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/iterative_pass.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

using View = test::SyntheticView;
using test::largestChannelDifference;

// Random color, depth in blocks of 1-9 columns and 3 rows (some sky, some in front of the zero-parallax plane).
View makeRandomView(std::uint32_t width, std::uint32_t height, unsigned seed) {
  return test::makeBlockView(width, height, seed, 0.6f, 9, 3, true);
}

// A near box (red 255) at depth boxDepth over a background (red 0, green ramp) at backgroundDepth.
constexpr std::uint32_t kBoxWidth = 200, kBoxBegin = 80, kBoxEnd = 120;  // box columns [80, 120)
View makeBoxView(float backgroundDepth, float boxDepth) {
  View view{ImageRGBA8(kBoxWidth, 1), DepthImage(kBoxWidth, 1, backgroundDepth)};
  for (std::uint32_t x = 0; x < kBoxWidth; ++x) {
    std::uint8_t* pixel = view.color.at(x, 0);
    bool box = x >= kBoxBegin && x < kBoxEnd;
    pixel[0] = box ? 255 : 0;
    pixel[1] = std::uint8_t(x);
    pixel[3] = 255;
    if (box) *view.depth.at(x, 0) = boxDepth;
  }
  return view;
}

// First and last column of the run of box pixels (red above half) through column `inside`; a lone blend
// of box and background elsewhere (a filter tap straddling the box's edge) is not part of the box.
std::pair<int, int> boxExtent(const ImageRGBA8& eye, int inside) {
  auto isBox = [&](int x) { return x >= 0 && x < int(eye.width) && eye.at(std::uint32_t(x), 0)[0] > 127; };
  if (!isBox(inside)) return {-1, -1};
  int first = inside, last = inside;
  while (isBox(first - 1)) --first;
  while (isBox(last + 1)) ++last;
  return {first, last};
}

TEST(IterativeReference, IterationCountIsValidated) {
  StereoParameters parameters;
  EXPECT_THROW(makeIterativeConstants(parameters, 0, 64, 8), std::invalid_argument);
  EXPECT_THROW(makeIterativeConstants(parameters, S3D_ITERATIVE_MAX_ITERATIONS + 1, 64, 8), std::invalid_argument);
  parameters.maxSeparation = NAN;
  EXPECT_THROW(makeIterativeConstants(parameters, kDefaultIterations, 64, 8), std::invalid_argument);
}

TEST(IterativeReference, StartTapsRunFromTheTargetToTheSkysDisplacementAndCropMatchesTheSeed) {
  StereoParameters parameters;
  parameters.maxSeparation = 0.1f;  // 14 px at width 140
  gpu::IterativeConstants c = makeIterativeConstants(parameters, kDefaultIterations, 140, 4);
  gpu::StereoConstants seed = makeSeedConstants(parameters, 140, 4);
  ASSERT_EQ(c.startTapCount, S3D_ITERATIVE_START_TAPS);
  EXPECT_EQ(c.startTapOffsetPx[0], 0);
  EXPECT_EQ(c.startTapOffsetPx[c.startTapCount - 1], 14);
  EXPECT_EQ(c.cropBegin, seed.cropBegin);
  EXPECT_EQ(c.cropEnd, seed.cropEnd);
}

TEST(IterativeReference, SkyGivesExactlyMaxSeparationAndTheSeedsImage) {
  StereoParameters parameters{0.05f, 1.5f, -1.0f};
  gpu::IterativeConstants c = makeIterativeConstants(parameters, kDefaultIterations, 120, 3);
  EXPECT_EQ(gpu::iterativeParallaxPx(c, INFINITY), c.maxParallaxPx);
  EXPECT_EQ(c.maxParallaxPx, 0.05f * 120.0f);
  View view = makeRandomView(120, 3, 5);
  std::fill(view.depth.pixels.begin(), view.depth.pixels.end(), INFINITY);
  for (int x = c.cropBegin; x < c.cropEnd; ++x) {
    IterativeSample left = solveIterativePixel(view.depth, x, 1, Eye::Left, c);
    IterativeSample right = solveIterativePixel(view.depth, x, 1, Eye::Right, c);
    EXPECT_EQ(left.sourcePosition, float(x) + c.maxParallaxPx);
    EXPECT_EQ(right.sourcePosition, float(x) - c.maxParallaxPx);
    EXPECT_FALSE(left.filled);
    EXPECT_FALSE(right.filled);
  }
  // Uniform depth has one solution, the seed's: same positions, same filter, same bytes.
  StereoPair iterative = synthesizeIterativeReference(view.color, view.depth, c);
  StereoPair seed = synthesizeStereoReference(view.color, view.depth, makeSeedConstants(parameters, 120, 3));
  EXPECT_EQ(iterative.left.pixels, seed.left.pixels);
  EXPECT_EQ(iterative.right.pixels, seed.right.pixels);
}

TEST(IterativeReference, ZeroSeparationReproducesTheCenterViewBitForBit) {
  View view = makeRandomView(61, 17, 7);
  gpu::IterativeConstants c = makeIterativeConstants(StereoParameters{0.0f, 2.0f, 0.0f}, kDefaultIterations, 61, 17);
  StereoPair pair = synthesizeIterativeReference(view.color, view.depth, c);
  EXPECT_EQ(pair.left.pixels, view.color.pixels);
  EXPECT_EQ(pair.right.pixels, view.color.pixels);
}

TEST(IterativeReference, NearBoxEdgesLandWithinOnePixelWhereTheSeedMisplacesThem) {
  // maxSeparation 20 px; the box at 1.25 zpp moves 4 px, the background ~20 px. Analytically the left eye
  // shows the box over [80 - 4, 119 - 4] and the right eye over [80 + 4, 119 + 4]. The seed's taps
  // (10, 13, 20 px) miss the box from inside its last 6 px, so it clones background there: a halo.
  StereoParameters parameters{0.1f, 1.0f, -1.0f};
  for (float background : {INFINITY, 40.0f}) {
    View view = makeBoxView(background, 1.25f);
    const float boxShift = gpu::parallaxFromDepth(parameters.maxSeparation, parameters.zeroParallaxDistance, 1.25f) * float(kBoxWidth);
    const float firstLeft = float(kBoxBegin) - boxShift, lastLeft = float(kBoxEnd - 1) - boxShift;
    const float firstRight = float(kBoxBegin) + boxShift, lastRight = float(kBoxEnd - 1) + boxShift;

    StereoPair iterative = synthesizeIterativeReference(
        view.color, view.depth, makeIterativeConstants(parameters, kDefaultIterations, kBoxWidth, 1));
    const int middle = int(kBoxBegin + kBoxEnd) / 2;  // inside the box in both eyes
    auto [leftFirst, leftLast] = boxExtent(iterative.left, middle);
    auto [rightFirst, rightLast] = boxExtent(iterative.right, middle);
    EXPECT_LE(std::abs(float(leftFirst) - firstLeft), 1.0f) << background;
    EXPECT_LE(std::abs(float(leftLast) - lastLeft), 1.0f) << background;
    EXPECT_LE(std::abs(float(rightFirst) - firstRight), 1.0f) << background;
    EXPECT_LE(std::abs(float(rightLast) - lastRight), 1.0f) << background;

    StereoPair seed = synthesizeStereoReference(view.color, view.depth, makeSeedConstants(parameters, kBoxWidth, 1));
    EXPECT_GT(std::abs(float(boxExtent(seed.left, middle).second) - lastLeft), 4.0f) << background;
    EXPECT_GT(std::abs(float(boxExtent(seed.right, middle).first) - firstRight), 4.0f) << background;
  }
}

TEST(IterativeReference, DisocclusionIsFilledFromTheBackgroundAndMarked) {
  // Left of the box the left eye sees background the center view hides behind it (columns
  // [80 - backgroundShift, 80 - boxShift)); no source maps there, so it is filled from the background side
  // (never with the box) and, with markFilled, alpha 0 flags it. Everything else is a solution: flag 255.
  StereoParameters parameters{0.1f, 1.0f, -1.0f};
  View view = makeBoxView(INFINITY, 1.25f);
  gpu::IterativeConstants c = makeIterativeConstants(parameters, kDefaultIterations, kBoxWidth, 1);
  EXPECT_EQ(c.markFilled, 0);  // by default the eyes carry the center's alpha, as every method's do
  c.markFilled = 1;
  StereoPair pair = synthesizeIterativeReference(view.color, view.depth, c);
  for (int x = c.cropBegin; x < c.cropEnd; ++x) {
    const bool hole = x >= 61 && x <= 75;  // [60, 76) less the edge columns the filter blends
    const std::uint8_t* pixel = pair.left.at(std::uint32_t(x), 0);
    if (hole) {
      EXPECT_LT(pixel[0], 128) << x;  // background, not the stretched box
      EXPECT_EQ(pixel[3], 0) << x;
      EXPECT_TRUE(solveIterativePixel(view.depth, x, 0, Eye::Left, c).filled) << x;
    } else if (x < 59 || x > 76) {
      EXPECT_EQ(pixel[3], 255) << x;
    }
  }
  c.markFilled = 0;
  StereoPair unmarked = synthesizeIterativeReference(view.color, view.depth, c);
  for (std::uint32_t x = 0; x < kBoxWidth; ++x) EXPECT_EQ(unmarked.left.at(x, 0)[3], 255) << x;
}

TEST(IterativeReference, CarriesTheWeaponMaskInAlphaAndIsTheCenterViewAtZeroSeparation) {
  // The weapon mask travels in alpha (0 on first-person pixels); the HUD fades by it in the eyes. Without a fill
  // flag the iterative method must carry it like the seed does, and at maxSeparation 0 reproduce every byte.
  View view = makeBoxView(INFINITY, 1.25f);
  for (std::uint32_t x = 20; x < 40; ++x) view.color.at(x, 0)[3] = 0;  // a weapon over columns [20, 40)
  for (std::uint32_t x = 40; x < 42; ++x) view.color.at(x, 0)[3] = 128;  // its anti-aliased edge
  StereoParameters parameters{0.0f, 1.0f, 0.0f};
  const gpu::IterativeConstants c = makeIterativeConstants(parameters, kDefaultIterations, kBoxWidth, 1);
  const StereoPair pair = synthesizeIterativeReference(view.color, view.depth, c);
  EXPECT_EQ(pair.left.pixels, view.color.pixels);
  EXPECT_EQ(pair.right.pixels, view.color.pixels);
}

TEST(IterativeReference, InvalidAndExtremeDepthsGiveFiniteSourcesWithinTheSeparation) {
  // Sky, zero, negative, NaN, denormal and huge depths: the parallax is bounded, so every source is finite
  // and at most maxSeparation away; also with maxSeparation 0, where 0 * inf would be NaN.
  const float depths[] = {INFINITY, 0.0f, -3.0f, NAN, 1e-40f, 1e30f, 0.4f, 2.0f, 7.0f};
  DepthImage depth(90, 1);
  for (std::uint32_t x = 0; x < 90; ++x) *depth.at(x, 0) = depths[(x * 7 + x / 5) % 9];
  for (float separation : {0.1f, 0.0f}) {
    gpu::IterativeConstants c = makeIterativeConstants(StereoParameters{separation, 1.0f, 0.0f}, kDefaultIterations, 90, 1);
    for (int x = 0; x < 90; ++x)
      for (Eye eye : {Eye::Left, Eye::Right}) {
        IterativeSample sample = solveIterativePixel(depth, x, 0, eye, c);
        ASSERT_TRUE(std::isfinite(sample.sourcePosition)) << x;
        EXPECT_LE(std::abs(sample.sourcePosition - float(x)), c.maxParallaxPx) << x;
      }
  }
}

class IterativeGpu : public test::VulkanTest {};

TEST_F(IterativeGpu, MatchesTheCppImplementationWithinOneLevel) {
  // Tolerance 1 level of 8 bits: the GPU may fuse the color filter's multiply-add and round the unorm store
  // differently from std::lround. Every decision (texel picks, residual test, candidate choice) is made on
  // the same IEEE float values on both sides (`precise` keeps the GPU from fusing the position update), so
  // no pixel may pick another source.
  for (auto [width, height, separation, iterations] :
       {std::tuple{64u, 32u, 0.05f, kDefaultIterations}, std::tuple{37u, 11u, 0.1f, 1},
        std::tuple{128u, 9u, 0.02f, S3D_ITERATIVE_MAX_ITERATIONS}, std::tuple{150u, 12u, 0.2f, 3}}) {
    View view = makeRandomView(width, height, width);
    gpu::IterativeConstants c = makeIterativeConstants(StereoParameters{separation, 2.0f, -1.0f}, iterations, width, height);
    StereoPair expected = synthesizeIterativeReference(view.color, view.depth, c);
    StereoPair actual = synthesizeIterativeOnGpu(context(), view.color, view.depth, c);
    EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1) << width << "x" << height;
    EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1) << width << "x" << height;
  }
}

TEST_F(IterativeGpu, ZeroSeparationReproducesTheCenterViewBitForBit) {
  View view = makeRandomView(61, 17, 7);
  gpu::IterativeConstants c = makeIterativeConstants(StereoParameters{0.0f, 2.0f, 0.0f}, kDefaultIterations, 61, 17);
  StereoPair pair = synthesizeIterativeOnGpu(context(), view.color, view.depth, c);
  EXPECT_EQ(pair.left.pixels, view.color.pixels);
  EXPECT_EQ(pair.right.pixels, view.color.pixels);
}

TEST_F(IterativeGpu, InvalidAndExtremeDepthsMatchTheCppImplementation) {
  // A NaN anywhere in the solver would reach the color (the unorm store turns it into 0), and differ from C++.
  const float depths[] = {INFINITY, 0.0f, -3.0f, NAN, 1e-40f, 1e30f, 0.4f, 2.0f, 7.0f};
  View view = makeRandomView(90, 4, 3);
  for (std::uint32_t i = 0; i < view.depth.pixels.size(); ++i) view.depth.pixels[i] = depths[(i * 7 + i / 5) % 9];
  for (float separation : {0.1f, 0.0f}) {
    gpu::IterativeConstants c = makeIterativeConstants(StereoParameters{separation, 1.0f, 0.0f}, kDefaultIterations, 90, 4);
    StereoPair expected = synthesizeIterativeReference(view.color, view.depth, c);
    StereoPair actual = synthesizeIterativeOnGpu(context(), view.color, view.depth, c);
    EXPECT_LE(largestChannelDifference(actual.left, expected.left), 1) << separation;
    EXPECT_LE(largestChannelDifference(actual.right, expected.right), 1) << separation;
  }
}

class IterativeCourtyard : public test::VulkanTest {};

TEST_F(IterativeCourtyard, IsAtLeastAsCloseToTheTwoPassReferenceAsTheSeed) {
  constexpr std::uint32_t width = 320, height = 180;
  const StereoParameters parameters;  // defaults, as `s3d render`
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  renderer::DeferredRenderer deferred(context(), width, height);
  deferred.setScene(scene);
  const renderer::ViewMatrices center = renderer::centerViewMatrices(
      scene, float(width) / float(height), {parameters.weaponDepthOffset, parameters.weaponDepthScale});
  (void)deferred.render(center);
  const ImageRGBA8 color = deferred.readDisplayColor();
  const DepthImage depth = deferred.readLinearDepth();
  (void)deferred.render(frame::referenceEyeView(scene, center, Eye::Left, parameters));
  const ImageRGBA8 leftReference = deferred.readDisplayColor();
  (void)deferred.render(frame::referenceEyeView(scene, center, Eye::Right, parameters));
  const ImageRGBA8 rightReference = deferred.readDisplayColor();

  const gpu::StereoConstants seedConstants = makeSeedConstants(parameters, width, height);
  const StereoPair seed = synthesizeStereoOnGpu(context(), color, depth, seedConstants);
  const StereoPair iterative = synthesizeIterativeOnGpu(
      context(), color, depth, makeIterativeConstants(parameters, kDefaultIterations, width, height));
  const std::uint32_t crop = std::uint32_t(seedConstants.cropBegin);
  const std::vector<std::uint8_t> halo = haloMask(depth, std::uint32_t(std::ceil(parameters.maxSeparation * float(width))));
  for (auto [name, seedEye, iterativeEye, reference] :
       {std::tuple{"left", &seed.left, &iterative.left, &leftReference},
        std::tuple{"right", &seed.right, &iterative.right, &rightReference}}) {
    const RegionErrors seedError = compareByRegion(*seedEye, *reference, crop, halo);
    const RegionErrors iterativeError = compareByRegion(*iterativeEye, *reference, crop, halo);
    std::printf("courtyard %ux%u %s eye PSNR dB (all / halo / rest): seed %.2f / %.2f / %.2f, iterative %.2f / %.2f / %.2f\n",
                width, height, name, seedError.all.psnrDb, seedError.halo.psnrDb, seedError.rest.psnrDb,
                iterativeError.all.psnrDb, iterativeError.halo.psnrDb, iterativeError.rest.psnrDb);
    EXPECT_GE(iterativeError.all.psnrDb, seedError.all.psnrDb) << name;
  }
}

}  // namespace
}  // namespace s3d::stereo
