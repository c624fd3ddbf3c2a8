// Frame-compatible stereo outputs: anaglyph colour mixing and side-by-side / top-and-bottom packing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/srgb.h"

namespace s3d::stereo {
namespace {

ImageRGBA8 solidImage(std::uint32_t width, std::uint32_t height, std::uint8_t r, std::uint8_t g, std::uint8_t b,
                      std::uint8_t a = 255) {
  ImageRGBA8 image(width, height);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    image.pixels[i * 4 + 0] = r;
    image.pixels[i * 4 + 1] = g;
    image.pixels[i * 4 + 2] = b;
    image.pixels[i * 4 + 3] = a;
  }
  return image;
}

// Every pixel distinct (and eye-specific via `tag`) so misplaced copies are detectable.
ImageRGBA8 labelledImage(std::uint32_t width, std::uint32_t height, std::uint8_t tag) {
  ImageRGBA8 image(width, height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = static_cast<std::uint8_t>(x);
      p[1] = static_cast<std::uint8_t>(y);
      p[2] = tag;
      p[3] = static_cast<std::uint8_t>(200 + x % 50);
    }
  return image;
}

void setPixel(ImageRGBA8& image, std::uint32_t x, std::uint32_t y, std::uint8_t r, std::uint8_t g, std::uint8_t b,
              std::uint8_t a = 255) {
  std::uint8_t* p = image.at(x, y);
  p[0] = r;
  p[1] = g;
  p[2] = b;
  p[3] = a;
}

TEST(Srgb, EveryEightBitCodeSurvivesDecodeThenEncode) {
  // Exact: adjacent codes are far apart in linear light compared with float rounding error.
  for (int code = 0; code < 256; ++code)
    EXPECT_EQ(encodeSrgb8(decodeSrgb8(static_cast<std::uint8_t>(code))), code) << "code " << code;
}

TEST(Srgb, EncodeClampsOutOfRangeAndNan) {
  EXPECT_EQ(encodeSrgb8(-0.5f), 0);
  EXPECT_EQ(encodeSrgb8(2.0f), 255);
  EXPECT_EQ(encodeSrgb8(std::nanf("")), 0);
}

TEST(AnaglyphDubois, IdenticalGrayEyesStayGray) {
  // Rows of ML+MR sum to 0.999, 1.000, 1.000, so a gray pair maps to (almost) the same gray;
  // +-1 level covers the 0.1% red loss and rounding.
  const ImageRGBA8 gray = solidImage(3, 2, 128, 128, 128);
  const ImageRGBA8 anaglyph = makeAnaglyphDubois(gray, gray);
  ASSERT_EQ(anaglyph.width, 3u);
  ASSERT_EQ(anaglyph.height, 2u);
  for (std::size_t i = 0; i < anaglyph.pixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(anaglyph.pixels[i * 4 + c], 128, 1);
    EXPECT_EQ(anaglyph.pixels[i * 4 + 3], 255);
  }
}

TEST(AnaglyphDubois, PureRedLeftBlackRightMatchesHandComputation) {
  // Linear left = (1,0,0), right = 0 -> first column of ML = (0.456, -0.040, -0.015) -> clamp (0.456, 0, 0).
  // sRGB(0.456) = 1.055 * 0.456^(1/2.4) - 0.055 = 0.70561 -> 0.70561 * 255 = 179.93 -> 180. Exact: far from .5.
  const ImageRGBA8 anaglyph = makeAnaglyphDubois(solidImage(1, 1, 255, 0, 0), solidImage(1, 1, 0, 0, 0));
  EXPECT_EQ(anaglyph.pixels[0], 180);
  EXPECT_EQ(anaglyph.pixels[1], 0);
  EXPECT_EQ(anaglyph.pixels[2], 0);
  EXPECT_EQ(anaglyph.pixels[3], 255);
}

TEST(AnaglyphDubois, BlackLeftPureBlueRightMatchesHandComputation) {
  // Linear right = (0,0,1) -> third column of MR = (-0.002, -0.018, 1.226) -> clamp (0, 0, 1) -> (0, 0, 255).
  const ImageRGBA8 anaglyph = makeAnaglyphDubois(solidImage(1, 1, 0, 0, 0), solidImage(1, 1, 0, 0, 255));
  EXPECT_EQ(anaglyph.pixels[0], 0);
  EXPECT_EQ(anaglyph.pixels[1], 0);
  EXPECT_EQ(anaglyph.pixels[2], 255);
}

TEST(AnaglyphDubois, AlphaIsOpaqueWhateverTheEyesCarry) {
  const ImageRGBA8 anaglyph = makeAnaglyphDubois(solidImage(1, 1, 10, 20, 30, 7), solidImage(1, 1, 10, 20, 30, 9));
  EXPECT_EQ(anaglyph.pixels[3], 255);
}

TEST(AnaglyphDubois, MismatchedEyeSizesThrow) {
  EXPECT_THROW(makeAnaglyphDubois(solidImage(2, 2, 0, 0, 0), solidImage(3, 2, 0, 0, 0)), std::invalid_argument);
}

TEST(PackingModeParsing, AcceptsHalfAndFull) {
  EXPECT_EQ(parsePackingMode("half"), PackingMode::Half);
  EXPECT_EQ(parsePackingMode("full"), PackingMode::Full);
}

TEST(PackingModeParsing, UnknownNameThrowsListingChoices) {
  try {
    parsePackingMode("quarter");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("quarter"), std::string::npos) << message;
    EXPECT_NE(message.find("half"), std::string::npos) << message;
    EXPECT_NE(message.find("full"), std::string::npos) << message;
  }
}

TEST(SideBySide, FullPlacesEveryPixelExactly) {
  const ImageRGBA8 left = labelledImage(3, 2, 1);
  const ImageRGBA8 right = labelledImage(3, 2, 2);
  const ImageRGBA8 frame = makeSideBySide(left, right, PackingMode::Full);
  ASSERT_EQ(frame.width, 6u);
  ASSERT_EQ(frame.height, 2u);
  for (std::uint32_t y = 0; y < 2; ++y)
    for (std::uint32_t x = 0; x < 3; ++x)
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(frame.at(x, y)[c], left.at(x, y)[c]) << "left eye at " << x << "," << y;
        EXPECT_EQ(frame.at(x + 3, y)[c], right.at(x, y)[c]) << "right eye at " << x << "," << y;
      }
}

TEST(SideBySide, HalfAveragesPixelPairsInLinearLight) {
  // Black + white averaged in linear light is 0.5 -> sRGB 188 (not the 127/128 of averaging codes).
  ImageRGBA8 left = solidImage(4, 1, 0, 0, 0);
  setPixel(left, 1, 0, 255, 255, 255);
  setPixel(left, 2, 0, 255, 255, 255);
  setPixel(left, 3, 0, 255, 255, 255);
  const ImageRGBA8 right = solidImage(4, 1, 50, 100, 150);
  const ImageRGBA8 frame = makeSideBySide(left, right, PackingMode::Half);
  ASSERT_EQ(frame.width, 4u);
  ASSERT_EQ(frame.height, 1u);
  const int expectedMid = encodeSrgb8(0.5f);
  EXPECT_EQ(expectedMid, 188);                // sRGB(0.5) = 0.7354 * 255 = 187.5 -> 188
  EXPECT_EQ(frame.at(0, 0)[0], expectedMid);  // pair (black, white)
  EXPECT_EQ(frame.at(1, 0)[0], 255);          // pair (white, white)
  // Equal pairs average to themselves exactly.
  EXPECT_EQ(frame.at(2, 0)[0], 50);
  EXPECT_EQ(frame.at(2, 0)[1], 100);
  EXPECT_EQ(frame.at(3, 0)[2], 150);
}

TEST(SideBySide, HalfAveragesAlphaLinearly) {
  ImageRGBA8 left = solidImage(2, 1, 0, 0, 0, 0);
  setPixel(left, 1, 0, 0, 0, 0, 200);
  const ImageRGBA8 frame = makeSideBySide(left, left, PackingMode::Half);
  EXPECT_EQ(frame.at(0, 0)[3], 100);  // (0 + 200) / 2, exact
}

TEST(SideBySide, HalfOddWidthGivesLeftEyeTheSpareColumnAndKeepsWidth) {
  // W = 3: left eye gets 2 columns (each covers 1.5 source columns), right eye 1 column (all 3).
  ImageRGBA8 eye = solidImage(3, 1, 0, 0, 0);
  setPixel(eye, 2, 0, 255, 255, 255);
  const ImageRGBA8 frame = makeSideBySide(eye, eye, PackingMode::Half);
  ASSERT_EQ(frame.width, 3u);
  EXPECT_EQ(frame.at(0, 0)[0], 0);                       // source columns 0 and half of 1: all black
  EXPECT_EQ(frame.at(1, 0)[0], encodeSrgb8(2.0f / 3.0f));  // half of black column 1 + white column 2
  EXPECT_EQ(frame.at(2, 0)[0], encodeSrgb8(1.0f / 3.0f));  // right eye: mean of all three
}

TEST(SideBySide, HalfOfSinglePixelWideEyesThrows) {
  EXPECT_THROW(makeSideBySide(solidImage(1, 2, 0, 0, 0), solidImage(1, 2, 0, 0, 0), PackingMode::Half),
               std::invalid_argument);
}

TEST(TopAndBottom, FullPlacesLeftEyeOnTopExactly) {
  const ImageRGBA8 left = labelledImage(2, 3, 1);
  const ImageRGBA8 right = labelledImage(2, 3, 2);
  const ImageRGBA8 frame = makeTopAndBottom(left, right, PackingMode::Full);
  ASSERT_EQ(frame.width, 2u);
  ASSERT_EQ(frame.height, 6u);
  for (std::uint32_t y = 0; y < 3; ++y)
    for (std::uint32_t x = 0; x < 2; ++x)
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(frame.at(x, y)[c], left.at(x, y)[c]) << "left eye at " << x << "," << y;
        EXPECT_EQ(frame.at(x, y + 3)[c], right.at(x, y)[c]) << "right eye at " << x << "," << y;
      }
}

TEST(TopAndBottom, HalfAveragesRowPairsInLinearLight) {
  ImageRGBA8 left = solidImage(1, 2, 0, 0, 0);
  setPixel(left, 0, 1, 255, 255, 255);
  const ImageRGBA8 right = solidImage(1, 2, 7, 7, 7);
  const ImageRGBA8 frame = makeTopAndBottom(left, right, PackingMode::Half);
  ASSERT_EQ(frame.width, 1u);
  ASSERT_EQ(frame.height, 2u);
  EXPECT_EQ(frame.at(0, 0)[0], encodeSrgb8(0.5f));  // left eye on top: mean of black and white rows
  EXPECT_EQ(frame.at(0, 1)[0], 7);                  // right eye below, equal rows unchanged
}

TEST(TopAndBottom, MismatchedEyeSizesThrow) {
  EXPECT_THROW(makeTopAndBottom(solidImage(2, 2, 0, 0, 0), solidImage(2, 3, 0, 0, 0), PackingMode::Full),
               std::invalid_argument);
}

}  // namespace
}  // namespace s3d::stereo
