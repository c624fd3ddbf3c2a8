// The hybrid's base depth: each eye pixel takes the center's device depth at the texel the gather base filters it
// from, and the GPU pass equals the C++ reference texel for texel.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <span>
#include <vector>

#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_base_depth.h"
#include "s3d/stereo/hybrid_base_depth_pass.h"
#include "s3d/stereo/stereo_pass.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

constexpr std::uint32_t kWidth = 200, kHeight = 3;

StereoParameters searchHybrid(float maxSeparation) {
  StereoParameters parameters;
  parameters.method = StereoMethod::Hybrid;
  parameters.hybridBase = StereoMethod::Search;
  parameters.maxSeparation = maxSeparation;
  parameters.zeroParallaxDistance = 1.0f;
  parameters.edgeCrop = 0.0f;
  return parameters;
}

// Depth steps on every row: sky on the left, a far wall, a near block, a first-person weapon (linear depth 0.3,
// device depth in its own slice below 0.1) and a slanted floor, each row shifted so the rows differ.
DepthImage steppedLinearDepth() {
  DepthImage depth(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::uint32_t u = x + 3 * y;
      *depth.at(x, y) = u < 20 ? INFINITY : u < 60 ? 6.0f : u < 100 ? 1.5f : u < 130 ? 4.0f : u < 160 ? 0.3f
                                                                                                       : 2.0f + 0.05f * float(u - 160);
    }
  return depth;
}

// A value of its own per texel (so a texel off by one shows), in the layer's slice as the renderer's device depth.
DepthImage distinctDeviceDepth(const DepthImage& linear) {
  DepthImage device(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float unique = float(y * kWidth + x) / float(kWidth * kHeight);
      const float d = *linear.at(x, y);
      *device.at(x, y) = std::isinf(d) ? 1.0f : d < 1.0f ? 0.01f + 0.08f * unique : 0.2f + 0.7f * unique;
    }
  return device;
}

// Tolerance: none. At depth 2 the parallax is 0.05 * (1 - 1 / 2) * 200 = 5 px: the left eye takes the texel 5 to
// the right, the right eye the one 5 to the left, clamped to the row.
TEST(HybridBaseDepth, TakesTheDeviceDepthOfTheTexelTheGatherSamples) {
  const DepthImage linear(kWidth, kHeight, 2.0f);
  DepthImage device(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) *device.at(x, y) = float(x) / 1000.0f;
  const std::array<DepthImage, 2> eyes =
      hybridBaseDepthReference(linear, device, makeHybridConstants(searchHybrid(0.05f), kWidth, kHeight));
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      EXPECT_EQ(*eyes[0].at(x, y), float(std::min(x + 5, kWidth - 1)) / 1000.0f) << x;
      EXPECT_EQ(*eyes[1].at(x, y), float(x < 5 ? 0 : x - 5) / 1000.0f) << x;
    }
}

TEST(HybridBaseDepth, RefusesABaseWithoutASourceColumn) {
  StereoParameters parameters = searchHybrid(0.05f);
  parameters.hybridBase = StereoMethod::Iterative;
  const DepthImage depth(kWidth, kHeight, 2.0f);
  EXPECT_THROW(hybridBaseDepthReference(depth, depth, makeHybridConstants(parameters, kWidth, kHeight)),
               std::invalid_argument);
}

class HybridBaseDepthPassTest : public test::VulkanTest {};

// Tolerance: none (the same taps, the same precise source column, the same rounding). Both eyes of a view with
// sky, steps, a first-person layer and a slope, at two separations (the second reaches past the row's ends), from
// a 4-tap search (the short tap pipeline) and a 9-tap one (the full array).
TEST_F(HybridBaseDepthPassTest, MatchesTheCppReferenceTexelForTexel) {
  const DepthImage linear = steppedLinearDepth();
  const DepthImage device = distinctDeviceDepth(linear);
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  const vk::Image linearImage = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth, kHeight, usage);
  const vk::Image deviceImage =
      vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth, kHeight, VK_IMAGE_USAGE_SAMPLED_BIT | usage);
  constexpr vk::ImageState kSampledByCompute{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  vk::uploadImage(context(), linearImage, std::as_bytes(std::span(linear.pixels)), vk::kComputeRead);
  vk::uploadImage(context(), deviceImage, std::as_bytes(std::span(device.pixels)), kSampledByCompute);
  const vk::Image left = HybridBaseDepthPass::createEyeDepth(context(), kWidth, kHeight);
  const vk::Image right = HybridBaseDepthPass::createEyeDepth(context(), kWidth, kHeight);
  const HybridBaseDepthPass pass(context());
  for (const auto& [maxSeparation, taps] : {std::pair{0.05f, 4}, std::pair{0.2f, 4}, std::pair{0.2f, 9}}) {
    StereoParameters parameters = searchHybrid(maxSeparation);
    parameters.searchTaps = taps;
    const gpu::HybridConstants c = makeHybridConstants(parameters, kWidth, kHeight);
    ASSERT_EQ(c.baseTapCount, taps);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      vk::transition(cmd, left, vk::kUndefined, vk::kComputeWrite);
      vk::transition(cmd, right, vk::kUndefined, vk::kComputeWrite);
      pass.record(cmd, linearImage, deviceImage, left, right, c);
    });
    const std::array<DepthImage, 2> expected = hybridBaseDepthReference(linear, device, c);
    int eye = 0;
    for (const vk::Image* image : {&left, &right}) {
      const std::vector<std::byte> bytes = vk::readbackImage(context(), *image, vk::kComputeWrite);
      std::vector<float> got(bytes.size() / sizeof(float));
      std::memcpy(got.data(), bytes.data(), bytes.size());
      EXPECT_EQ(got, expected[eye].pixels)
          << "separation " << maxSeparation << ", " << taps << " taps" << (eye == 0 ? " left" : " right");
      ++eye;
    }
    EXPECT_NE(expected[0].pixels, expected[1].pixels);  // the eyes do sample different texels
  }
}

std::vector<float> readFloats(vk::Context& context, const vk::Image& image) {
  const std::vector<std::byte> bytes = vk::readbackImage(context, image, vk::kComputeWrite);
  std::vector<float> values(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

// Tolerance: none. The gather that also writes the base depth (one dispatch) writes the eyes the gather pass writes,
// byte for byte, and the depth the reference takes, texel for texel: the seed, a 4-tap and a 9-tap search, with
// cropped edges (black eyes there, depth still written).
TEST_F(HybridBaseDepthPassTest, TheGatherWithTheBaseDepthWritesTheGathersEyesAndTheReferencesDepth) {
  const DepthImage linear = steppedLinearDepth();
  const DepthImage device = distinctDeviceDepth(linear);
  std::vector<std::uint8_t> colour(std::size_t(kWidth) * kHeight * 4);
  std::mt19937 random(5);
  for (std::uint8_t& channel : colour) channel = std::uint8_t(random() % 256);
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  const auto image = [&](VkFormat format, VkImageUsageFlags extra = 0) {
    return vk::createImage(context(), format, kWidth, kHeight, usage | extra);
  };
  const vk::Image centerColor = image(StereoPass::kColorFormat), linearImage = image(VK_FORMAT_R32_SFLOAT);
  const vk::Image deviceImage = image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT);
  constexpr vk::ImageState kSampledByCompute{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  vk::uploadImage(context(), centerColor, std::as_bytes(std::span(colour)), vk::kComputeRead);
  vk::uploadImage(context(), linearImage, std::as_bytes(std::span(linear.pixels)), vk::kComputeRead);
  vk::uploadImage(context(), deviceImage, std::as_bytes(std::span(device.pixels)), kSampledByCompute);
  const vk::Image left = image(StereoPass::kColorFormat), right = image(StereoPass::kColorFormat);
  const vk::Image gatheredLeft = image(StereoPass::kColorFormat), gatheredRight = image(StereoPass::kColorFormat);
  const vk::Image leftDepth = HybridBaseDepthPass::createEyeDepth(context(), kWidth, kHeight);
  const vk::Image rightDepth = HybridBaseDepthPass::createEyeDepth(context(), kWidth, kHeight);
  const HybridBaseDepthPass pass(context());
  const StereoPass gather(context());
  for (const auto& [base, taps] : {std::pair{StereoMethod::Seed, 0}, std::pair{StereoMethod::Search, 4},
                                   std::pair{StereoMethod::Search, 9}}) {
    StereoParameters parameters = searchHybrid(0.2f);
    parameters.hybridBase = base;
    if (taps > 0) parameters.searchTaps = taps;
    parameters.edgeCrop = 0.03f;
    const gpu::StereoConstants constants = makeStereoConstants(displacementParameters(parameters), kWidth, kHeight);
    ASSERT_GT(constants.cropBegin, 0);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* target : {&left, &right, &gatheredLeft, &gatheredRight, &leftDepth, &rightDepth})
        vk::transition(cmd, *target, vk::kUndefined, vk::kComputeWrite);
      pass.recordWithGather(cmd, centerColor, linearImage, deviceImage, left, right, leftDepth, rightDepth, constants);
      gather.record(cmd, centerColor, linearImage, gatheredLeft, gatheredRight, constants);
    });
    const std::array<DepthImage, 2> expected =
        hybridBaseDepthReference(linear, device, makeHybridConstants(parameters, kWidth, kHeight));
    const char* name = taps == 0 ? "seed" : taps == 4 ? "search-4" : "search-9";
    EXPECT_EQ(readFloats(context(), leftDepth), expected[0].pixels) << name;
    EXPECT_EQ(readFloats(context(), rightDepth), expected[1].pixels) << name;
    EXPECT_EQ(vk::readbackImage(context(), left, vk::kComputeWrite),
              vk::readbackImage(context(), gatheredLeft, vk::kComputeWrite)) << name;
    EXPECT_EQ(vk::readbackImage(context(), right, vk::kComputeWrite),
              vk::readbackImage(context(), gatheredRight, vk::kComputeWrite)) << name;
  }
}

TEST_F(HybridBaseDepthPassTest, TheGatherWithTheBaseDepthRefusesImagesOfAnotherSize) {
  const HybridBaseDepthPass pass(context());
  const auto image = [&](std::uint32_t width) {
    return vk::createImage(context(), VK_FORMAT_R32_SFLOAT, width, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  };
  const vk::Image small = image(kWidth / 2), full = image(kWidth);
  const gpu::StereoConstants constants =
      makeStereoConstants(displacementParameters(searchHybrid(0.05f)), kWidth, kHeight);
  context().submitAndWait([&](VkCommandBuffer cmd) {
    EXPECT_THROW(pass.recordWithGather(cmd, full, full, full, full, full, small, full, constants),
                 std::invalid_argument);
  });
}

}  // namespace
}  // namespace s3d::stereo
