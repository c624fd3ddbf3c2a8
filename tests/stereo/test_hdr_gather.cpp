// The stereo methods on the linear HDR center view (hdr_gather.h): the same source columns as the C++
// references of the display-space passes, so the HDR error measures the same synthesis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "s3d/stereo/forward.h"
#include "s3d/stereo/hdr_gather.h"
#include "s3d/stereo/iterative.h"
#include "stereo_test_views.h"

namespace s3d::stereo {
namespace {

// The 8-bit image as unorm floats (what the shaders' imageLoad returns), gathered, then stored back as unorm.
ImageRGBA8 gatherAsUnorm(const ImageRGBA8& center, const std::vector<float>& columns) {
  ImageRGBA32F asFloat(center.width, center.height);
  for (std::size_t i = 0; i < center.pixels.size(); ++i) asFloat.pixels[i] = float(center.pixels[i]) / 255.0f;
  const ImageRGBA32F gathered = gatherRows(asFloat, columns);
  ImageRGBA8 stored(center.width, center.height);
  for (std::size_t i = 0; i < stored.pixels.size(); ++i)
    stored.pixels[i] = std::uint8_t(std::lround(std::clamp(gathered.pixels[i], 0.0f, 1.0f) * 255.0f));
  return stored;
}

TEST(HdrGather, ReproducesEveryMethodsReferenceBitForBitOnDisplayColor) {
  // Same columns, same filter arithmetic as row_sampling.h: exact, alpha included (the iterative reference's
  // fill marks are switched off).
  const test::SyntheticView view = test::makeBlockView(53, 7, 11, 0.3f, 6, 3, true);
  for (StereoMethod method : {StereoMethod::Seed, StereoMethod::Search, StereoMethod::Iterative}) {
    StereoParameters parameters{0.06f, 2.0f, -1.0f};
    parameters.method = method;
    const SourceColumns columns = referenceSourceColumns(view.depth, parameters);
    StereoPair expected;
    if (method == StereoMethod::Iterative) {
      gpu::IterativeConstants c = makeIterativeConstants(parameters, parameters.iterations, 53, 7);
      c.markFilled = 0;
      expected = synthesizeIterativeReference(view.color, view.depth, c);
    } else {
      expected = synthesizeStereoReference(view.color, view.depth, makeStereoConstants(parameters, 53, 7));
    }
    EXPECT_EQ(gatherAsUnorm(view.color, columns.left).pixels, expected.left.pixels) << methodName(method);
    EXPECT_EQ(gatherAsUnorm(view.color, columns.right).pixels, expected.right.pixels) << methodName(method);
  }
}

TEST(HdrGather, TheForwardMethodMatchesItsDisplayReferenceWithinOneLevel) {
  // Same samples (filter positions, hole means); a mean of unorm floats may round the other way: 1 level.
  test::SyntheticView view = test::makeBlockView(53, 7, 11, 0.3f, 6, 3, true);
  StereoParameters parameters{0.06f, 2.0f, -1.0f};
  parameters.method = StereoMethod::Forward;
  ImageRGBA32F asFloat(53, 7);
  for (std::size_t i = 0; i < view.color.pixels.size(); ++i) asFloat.pixels[i] = float(view.color.pixels[i]) / 255.0f;
  const HdrStereoPair hdr = synthesizeHdrReference(asFloat, view.depth, parameters);
  const StereoPair expected = synthesizeForwardReference(view.color, view.depth, makeForwardConstants(parameters, 53, 7));
  for (auto [eye, reference] : {std::pair{&hdr.left, &expected.left}, std::pair{&hdr.right, &expected.right}})
    for (std::size_t i = 0; i < reference->pixels.size(); ++i)
      ASSERT_LE(std::abs(int(std::lround(std::clamp(eye->pixels[i], 0.0f, 1.0f) * 255.0f)) - int(reference->pixels[i])), 1) << i;
}

TEST(HdrGather, KeepsValuesAboveOneAndCropsToBlack) {
  // Linear HDR is not clamped: a highlight of 40 moves with the sky's parallax (5 px of 50) unchanged.
  ImageRGBA32F center(50, 1, 0.5f);
  center.at(30, 0)[0] = 40.0f;
  const DepthImage sky(50, 1, INFINITY);
  const HdrStereoPair eyes = synthesizeHdrReference(center, sky, StereoParameters{0.1f, 1.0f, -1.0f});
  EXPECT_EQ(eyes.left.at(25, 0)[0], 40.0f);
  EXPECT_EQ(eyes.right.at(35, 0)[0], 40.0f);
  EXPECT_EQ(eyes.left.at(2, 0)[0], 0.0f);  // inside the 5-column crop
  EXPECT_EQ(eyes.left.at(2, 0)[3], 1.0f);
}

}  // namespace
}  // namespace s3d::stereo
