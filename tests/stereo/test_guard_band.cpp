// Guard band: the width bound, the rescaled parameters, the wide reference cameras (to 1e-4 px, double
// precision) and full-frame eyes from the C++ reference of the pass.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/stereo/guard_band.h"

namespace s3d::stereo {
namespace {

constexpr std::uint32_t kNoRenderedWidthCap = 1u << 30;

TEST(GuardBand, ZeroParallaxAtTheNearestDepthNeedsTheSeparationPlusTheFilterTexel) {
  EXPECT_DOUBLE_EQ(maxDisplacement(0.02, 0.1, 0.1), 0.02);  // nothing in front of the screen: sky's m is the most
  const GuardBand band = guardBandFor(0.02, 0.1, 0.1, 1280, kNoRenderedWidthCap);
  EXPECT_EQ(band.columns, 27u);  // ceil(25.6) + 1
  EXPECT_FALSE(band.capped);
  EXPECT_EQ(band.renderedWidth(1280), 1334u);
}

TEST(GuardBand, NoSeparationNeedsNoBand) {
  const GuardBand band = guardBandFor(0.0, 1.0, 0.1, 1280, kNoRenderedWidthCap);
  EXPECT_EQ(band.columns, 0u);
  StereoParameters p;
  p.maxSeparation = 0.0f;
  EXPECT_EQ(makeStereoConstants(guardBandParameters(p, 1280, band), 1280, 8).cropBegin, 0);
}

TEST(GuardBand, NegativeParallaxBeyondTheSeparationWidensTheBand) {
  // zpp 1, nearest 0.1: parallax m (1 - 10) = -9 m, larger than the sky's m.
  EXPECT_NEAR(maxDisplacement(0.02, 1.0, 0.1), 0.18, 1e-15);
  EXPECT_EQ(guardBandFor(0.02, 1.0, 0.1, 1280, kNoRenderedWidthCap).columns, 232u);  // ceil(230.4) + 1
}

TEST(GuardBand, HugeSeparationIsCappedAtHalfTheOutputWidthAndTheLargestImage) {
  const GuardBand band = guardBandFor(0.25, 10.0, 0.1, 1280, kNoRenderedWidthCap);  // 24.75 widths needed
  EXPECT_EQ(band.neededColumns, 31681u);
  EXPECT_EQ(band.columns, 640u);
  EXPECT_TRUE(band.capped);
  EXPECT_EQ(guardBandFor(0.25, 1.0, 1.0, 16000, 16384).columns, 192u);  // (16384 - 16000) / 2
  EXPECT_EQ(guardBandFor(0.02, 1.0e6, 1.0e-6, 1280, kNoRenderedWidthCap).columns, 640u);  // no overflow
}

TEST(GuardBand, BoundsTheParallaxOfEveryDepthFromTheNearestOnAndIsReached) {
  for (double zpp : {0.1, 1.0, 7.0}) {
    for (double nearest : {0.1, 0.5, 1.0, 7.0}) {
      const double bound = maxDisplacement(0.03, zpp, nearest);
      double largest = 0.0;
      for (double d = nearest; d < 1.0e7; d *= 1.01)
        largest = std::max(largest, std::abs(0.03 * (1.0 - zpp / d)));
      largest = std::max(largest, 0.03);  // the sky (+inf)
      EXPECT_LE(largest, bound * (1.0 + 1e-12));
      EXPECT_NEAR(largest, bound, 1e-12) << "zpp " << zpp << " nearest " << nearest;
    }
  }
}

TEST(GuardBand, WideParametersKeepTheParallaxInPixelsAndCropExactlyTheBand) {
  for (std::uint32_t width : {1u, 7u, 320u, 1280u, 1920u, 7680u}) {
    for (float m : {0.001f, 0.02f, 0.04f, 0.25f}) {
      StereoParameters p;
      p.maxSeparation = m;
      const GuardBand band = guardBandFor(m, 1.0, 1.0, width, 16384);
      const std::uint32_t wide = band.renderedWidth(width);
      const StereoParameters w = guardBandParameters(p, width, band);
      const gpu::StereoConstants c = makeStereoConstants(w, wide, 4);
      EXPECT_EQ(c.cropBegin, int(band.columns)) << width << " " << m;
      EXPECT_EQ(c.cropEnd, int(wide - band.columns)) << width << " " << m;
      for (float depth : {0.5f, 1.0f, 3.0f, INFINITY}) {
        // Float math as the pass does it: the rescaled separation times the wide width, 1e-4 px.
        const double narrowPx = double(gpu::parallaxFromDepth(m, 1.0f, depth)) * width;
        const double widePx = double(gpu::parallaxFromDepth(w.maxSeparation, 1.0f, depth)) * wide;
        EXPECT_NEAR(widePx, narrowPx, 1e-4 * std::max(1.0, std::abs(narrowPx) / 100.0)) << width << " " << m;
      }
    }
  }
}

// Output column of a world point through a camera whose image is `width` columns wide.
double column(const glm::dmat4& view, const glm::dmat4& projection, const glm::dvec3& world, double width) {
  const glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
  return (clip.x / clip.w * 0.5 + 0.5) * width;
}

glm::dmat4 perspective(double aspect) {
  glm::dmat4 p = glm::perspectiveRH_ZO(1.0, aspect, 0.1, 1000.0);
  p[1][1] = -p[1][1];
  return p;
}

TEST(GuardBand, WideReferenceEyesSeeThePointsWhereTheOutputEyesDoShiftedByTheBand) {
  // The reference eyes rendered on the wide frame with the wide parameters are the output eyes plus `columns`
  // on the left: the same eye offset (2 m zpp / P00 is unchanged) and the same shift in pixels.
  const double width = 1280.0, height = 720.0, m = 0.02, zpp = 1.5;
  const GuardBand band = guardBandFor(m, zpp, zpp, 1280, kNoRenderedWidthCap);
  const double wide = band.renderedWidth(1280);
  const double wideM = m * width / wide;
  const glm::dmat4 view = glm::lookAt(glm::dvec3(1.0, 1.7, 6.0), glm::dvec3(0.3, 1.2, -4.0), glm::dvec3(0, 1, 0));
  const glm::dmat4 narrowProjection = perspective(width / height), wideProjection = perspective(wide / height);
  const glm::dmat4 worldFromView = glm::inverse(view);
  for (Eye eye : {Eye::Left, Eye::Right}) {
    const EyeCameraT<double> narrow = offAxisEyeCamera(view, narrowProjection, eye, m, zpp);
    const EyeCameraT<double> wideEye = offAxisEyeCamera(view, wideProjection, eye, wideM, zpp);
    for (double depth : {0.2, 1.5, 10.0, 900.0}) {
      for (double ndcX : {-1.2, -0.5, 0.0, 0.9, 1.1}) {  // beyond +-1: points only the band shows
        const glm::dvec3 world(worldFromView * glm::dvec4(ndcX * depth / narrowProjection[0][0], 0.2 * depth, -depth, 1.0));
        EXPECT_NEAR(column(wideEye.view, wideEye.projection, world, wide) - double(band.columns),
                    column(narrow.view, narrow.projection, world, width), 1e-4)
            << "depth " << depth << " ndc " << ndcX;
      }
    }
  }
}

TEST(GuardBand, EyesFromTheWideCenterAreFullFrameAndMatchTheCroppedPassInsideItsCrop) {
  // 64 columns at m = 1/16: 4 px of separation, band 5, crop 4 without the band. Depths behind the screen.
  const std::uint32_t width = 64, height = 3;
  StereoParameters p;
  p.maxSeparation = 0.0625f;
  p.zeroParallaxDistance = 1.0f;
  const GuardBand band = guardBandFor(p.maxSeparation, 1.0, 1.0, width, 16384);
  const std::uint32_t wide = band.renderedWidth(width);
  ImageRGBA8 center(wide, height);
  DepthImage depth(wide, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < wide; ++x) {
      std::uint8_t* c = center.at(x, y);
      c[0] = std::uint8_t(20 + 3 * x), c[1] = std::uint8_t(40 + 7 * y), c[2] = std::uint8_t(200 - x), c[3] = 255;
      depth.at(x, y)[0] = (x / 9) % 2 ? 1.3f + 0.1f * float(y) : 6.0f;  // bars in front of a far wall
    }
  const StereoPair wideEyes = synthesizeStereoReference(center, depth, makeStereoConstants(guardBandParameters(p, width, band), wide, height));
  const StereoPair narrowEyes = synthesizeStereoReference(cropColumns(center, band.columns, width),
                                                          cropColumns(depth, band.columns, width),
                                                          makeStereoConstants(p, width, height));
  const int crop = makeStereoConstants(p, width, height).cropBegin;
  ASSERT_EQ(crop, 4);
  for (auto [wideEye, narrowEye] : {std::pair{&wideEyes.left, &narrowEyes.left}, std::pair{&wideEyes.right, &narrowEyes.right}}) {
    const ImageRGBA8 eye = cropColumns(*wideEye, band.columns, width);
    for (std::uint32_t y = 0; y < height; ++y)
      for (std::uint32_t x = 0; x < width; ++x) {
        EXPECT_EQ(eye.at(x, y)[3], 255) << "column " << x << " is black";
        if (int(x) < crop || int(x) >= int(width) - crop) continue;
        // 1 level: the rescaled separation differs from 1/16 in the last float bit, which can move a
        // bilinear weight across an 8-bit rounding boundary.
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(eye.at(x, y)[ch], narrowEye->at(x, y)[ch], 1) << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace s3d::stereo
