// The stereo pass inside a host's frame: the host's formats and layouts in, its eyes or one packed target out,
// each held to the C++ reference; synchronization validation on (TestHost) for single frames, two recordings in
// one command buffer and 2-3 frames in flight.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/hdr_gather.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/stereo/output_formats.h"
#include "host_pass_fixture.h"

namespace s3d::test {
namespace {

TEST(HostProjection, LinearDepthComesBackFromEveryDepthConvention) {
  for (bool reversed : {false, true})
    for (bool infinite : {false, true}) {
      HostProjection p;
      p.nearPlane = 0.5f;
      p.farPlane = 100.0f;
      p.reversedZ = reversed;
      p.infiniteFarPlane = infinite;
      const gpu::LinearDepthParams params = stereo::linearDepthParams(p, 0.0f, 1.0f);
      for (float z : {0.7f, 3.0f, 40.0f})
        EXPECT_NEAR(gpu::stereoDepthFromDevice(params, deviceDepth(p, z)), z, z * 1e-4f)
            << "reversed " << reversed << " infinite " << infinite;
      EXPECT_TRUE(std::isinf(gpu::stereoDepthFromDevice(params, reversed ? 0.0f : 1.0f)));  // the cleared sky
    }
}

TEST(HostProjection, TheFirstPersonLayerIsLinearizedWithItsOwnProjectionAndPushed) {
  HostProjection p;
  p.nearPlane = 0.5f;
  p.farPlane = 100.0f;
  p.firstPersonDepthRange = 0.1f;
  p.firstPersonNear = 0.05f;
  p.firstPersonFar = 5.0f;
  const gpu::LinearDepthParams params = stereo::linearDepthParams(p, 1.0f, 2.0f);
  EXPECT_NEAR(gpu::stereoDepthFromDevice(params, deviceDepth(p, 0.8f)), 1.0f + 2.0f * 0.8f, 1e-3f);  // weapon, pushed
  EXPECT_NEAR(gpu::stereoDepthFromDevice(params, deviceDepth(p, 30.0f)), 30.0f, 30.0f * 1e-4f);      // world
}

TEST_F(HostStereoPassTest, SynchronizationValidationIsOnAndReportsAMissingBarrier) {
  // Two clears of one image without a barrier between them: a write-after-write hazard only sync validation sees.
  vk::Image image = vk::createImage(*context_, VK_FORMAT_R8G8B8A8_UNORM, 8, 8, VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  runOnHostQueue([&](VkCommandBuffer cmd) {
    vk::transition(cmd, image, vk::kUndefined, vk::kTransferDestination);
    const VkClearColorValue black{};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
    vkCmdClearColorImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
  });
  const std::vector<std::string> messages = host().messages();
  EXPECT_TRUE(std::any_of(messages.begin(), messages.end(),
                          [](const std::string& m) { return m.find("SYNC-HAZARD") != std::string::npos; }))
      << messages.size() << " message(s)";
  host().clearMessages();  // expected here
}

TEST_F(HostStereoPassTest, Rgba8ColourAndD32DepthGiveTheReferenceEyes) {
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
}
TEST_F(HostStereoPassTest, SrgbColourIsReadAsItsDisplayValues) {
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_D32_SFLOAT);
}
TEST_F(HostStereoPassTest, Bgra8ColourIsReadInItsChannelOrder) {
  expectReferenceEyes(VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R32_SFLOAT);
}
TEST_F(HostStereoPassTest, Bgra8SrgbColourIsReadAsItsDisplayValues) {
  expectReferenceEyes(VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R32_SFLOAT);
}
TEST_F(HostStereoPassTest, D24S8DepthGivesTheReferenceEyesOfItsQuantizedDepth) {
  if (!supports(VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
    GTEST_SKIP() << "the device has no sampled D24S8";
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D24_UNORM_S8_UINT);
}
TEST_F(HostStereoPassTest, D16DepthGivesTheReferenceEyesOfItsQuantizedDepth) {
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D16_UNORM);
}
TEST_F(HostStereoPassTest, ReversedZWithAnInfiniteFarPlaneGivesTheReferenceEyes) {
  frame_.projection.reversedZ = true;
  frame_.projection.infiniteFarPlane = true;
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
}
TEST_F(HostStereoPassTest, TheFirstPersonDepthRangeIsLinearizedAndPushed) {
  frame_.projection.firstPersonDepthRange = 0.1f;
  frame_.projection.firstPersonNear = 0.05f;
  frame_.projection.firstPersonFar = 5.0f;
  frame_.weaponDepthOffset = 1.0f;
  frame_.weaponDepthScale = 1.5f;
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
}

// With a first-person range the gather converts every tap: a weapon pushed behind the world is taken at its pushed
// depth, and a push that reverses the layer's order (negative scale) at its own. The view: blocks of 1-3 columns at
// depths 0.6-3.4, about half of them nearer than 2 (the fixture's weapon), so a side's taps often meet both layers
// and several depths of each.
void useMixedLayerBlocks(HostStereoPassTest& t) {
  t.view_ = makeBlockView(kWidth, kHeight, 5, 0.6f, 3, 5, true);
  for (float& z : t.view_.depth.pixels)
    if (std::isfinite(z)) z = 0.6f + std::fmod(z, 2.8f);
}
TEST_F(HostStereoPassTest, AWeaponPushedBehindTheWorldIsTakenAtItsPushedDepth) {
  useMixedLayerBlocks(*this);
  frame_.projection.firstPersonDepthRange = 0.1f;
  frame_.projection.firstPersonNear = 0.05f;
  frame_.projection.firstPersonFar = 5.0f;
  frame_.weaponDepthOffset = 20.0f;
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
}
TEST_F(HostStereoPassTest, APushReversingTheFirstPersonLayersOrderIsTakenAtItsPushedDepth) {
  useMixedLayerBlocks(*this);
  frame_.projection.reversedZ = true;
  frame_.projection.firstPersonDepthRange = 0.1f;
  frame_.projection.firstPersonNear = 0.05f;
  frame_.projection.firstPersonFar = 5.0f;
  frame_.weaponDepthOffset = 6.0f;
  frame_.weaponDepthScale = -1.0f;
  expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
}

// The gather has a pipeline for a depth buffer of one layer and one for a first-person range, picked per frame by
// the projection: one pass follows a host that turns its weapon layer on and off, each frame to the reference. The
// weapon is pushed behind the world (useMixedLayerBlocks), where the one-layer path's order of keys would be wrong.
TEST_F(HostStereoPassTest, OnePassFollowsTheFirstPersonRangeFromFrameToFrame) {
  useMixedLayerBlocks(*this);
  const stereo::HostStereoPass pass(*context_, {kWidth, kHeight, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT,
                                                HostOutput::TwoEyes, false, stereo::HostInputRead::Direct});
  frame_.projection.firstPersonNear = 0.05f;
  frame_.projection.firstPersonFar = 5.0f;
  frame_.weaponDepthOffset = 20.0f;
  for (float range : {0.0f, 0.1f, 0.0f}) {
    frame_.projection.firstPersonDepthRange = range;
    DepthImage expectedLinear;
    const stereo::StereoPair gpu = eyesOf(pass, &expectedLinear);
    const stereo::StereoPair cpu = stereo::synthesizeStereoReference(view_.color, expectedLinear, frame_.stereo);
    // 1 level: the reference's rounding, as expectReferenceEyes.
    EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << "first-person range " << range;
    EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << "first-person range " << range;
  }
}

// Device depth nearer than the range's near end, and NaN, hold no surface: each reads as the zero-parallax plane
// (stereoDepthFromDevice), among taps of both layers (converted per tap) or of the world alone (the gather takes
// the minimum in device depth and converts once).
void expectOutOfRangeDepthReadsAsTheScreen(HostStereoPassTest& t, float outOfRange, bool firstPersonLayer) {
  if (firstPersonLayer) {
    t.frame_.projection.firstPersonDepthRange = 0.1f;
    t.frame_.projection.firstPersonNear = 0.05f;
    t.frame_.projection.firstPersonFar = 5.0f;
    t.frame_.weaponDepthOffset = 1.0f;
  }
  t.editDepth_ = [outOfRange](DepthUpload& depth) {
    for (std::size_t i = 3; i < depth.expectedLinear.pixels.size(); i += 11) {
      const float d = (i / 11) % 2 ? std::nanf("") : outOfRange;
      std::memcpy(&depth.bytes[i * 4], &d, 4);
      depth.expectedLinear.pixels[i] = 0.0f;  // sanitized to the zero-parallax plane by the reference
    }
  };
  t.expectReferenceEyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
}
TEST_F(HostStereoPassTest, DepthBelowZeroAndNaNReadAsTheZeroParallaxPlane) {
  expectOutOfRangeDepthReadsAsTheScreen(*this, -0.25f, false);
}
TEST_F(HostStereoPassTest, DepthBelowZeroAndNaNReadAsTheZeroParallaxPlaneNextToAFirstPersonLayer) {
  expectOutOfRangeDepthReadsAsTheScreen(*this, -0.25f, true);
}
TEST_F(HostStereoPassTest, ReversedDepthAboveOneAndNaNReadAsTheZeroParallaxPlane) {
  frame_.projection.reversedZ = true;
  expectOutOfRangeDepthReadsAsTheScreen(*this, 1.25f, false);
}
TEST_F(HostStereoPassTest, ReversedDepthAboveOneAndNaNReadAsTheZeroParallaxPlaneNextToAFirstPersonLayer) {
  frame_.projection.reversedZ = true;
  expectOutOfRangeDepthReadsAsTheScreen(*this, 1.25f, true);
}

// Each packed target is output_formats.cpp applied to the eye bytes it was made from. The packing pass and the
// gather's full packings take the eyes as stored (the store's conversion, which Vulkan lets round ties either
// way); the gather's anaglyph and half packings round each eye byte half away from zero, as the C++ reference does.
// A tie rounded the other way moves an eye byte by one level, and a dark anaglyph channel by up to three.
TEST_F(HostStereoPassTest, EveryPackedTargetIsOutputFormatsAppliedToTheEyeBytesItIsMadeFrom) {
  DepthImage expectedLinear;
  const stereo::StereoPair own = eyes(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, &expectedLinear);
  const stereo::StereoPair reference = stereo::synthesizeStereoReference(view_.color, expectedLinear, frame_.stereo);
  vk::Image color = uploaded(VK_FORMAT_R8G8B8A8_UNORM, colorBytes(view_.color, VK_FORMAT_R8G8B8A8_UNORM), kShaderRead);
  const std::vector<std::byte> depthBytes = depthUpload(VK_FORMAT_R32_SFLOAT).bytes;
  vk::Image depth = uploaded(VK_FORMAT_R32_SFLOAT, depthBytes, kShaderRead);
  using stereo::PackingMode;
  auto packed = [](HostOutput mode, const stereo::StereoPair& eyes) {
    switch (mode) {
      case HostOutput::SideBySideHalf: return stereo::makeSideBySide(eyes.left, eyes.right, PackingMode::Half);
      case HostOutput::SideBySideFull: return stereo::makeSideBySide(eyes.left, eyes.right, PackingMode::Full);
      case HostOutput::TopBottomHalf: return stereo::makeTopAndBottom(eyes.left, eyes.right, PackingMode::Half);
      case HostOutput::TopBottomFull: return stereo::makeTopAndBottom(eyes.left, eyes.right, PackingMode::Full);
      default: return stereo::makeAnaglyphDubois(eyes.left, eyes.right);
    }
  };
  for (HostOutput mode : {HostOutput::SideBySideHalf, HostOutput::SideBySideFull, HostOutput::TopBottomHalf,
                          HostOutput::TopBottomFull, HostOutput::Anaglyph})
    for (stereo::HostInputRead read : {stereo::HostInputRead::Direct, stereo::HostInputRead::Convert}) {
      const bool gatherRoundsTheEyes = read == stereo::HostInputRead::Direct && mode != HostOutput::SideBySideFull &&
                                       mode != HostOutput::TopBottomFull;
      const ImageRGBA8 expected = packed(mode, gatherRoundsTheEyes ? reference : own);
      stereo::HostStereoPass pass(*context_, {kWidth, kHeight, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, mode, false,
                                              read});
      ASSERT_EQ(pass.packedWidth(), expected.width);
      ASSERT_EQ(pass.packedHeight(), expected.height);
      vk::Image target = output(pass.eyeFormat(), pass.packedWidth(), pass.packedHeight());
      const HostImage targetHost = hostImage(target, kCopiedOut);
      runOnHostQueue([&](VkCommandBuffer cmd) {
        pass.record(cmd, hostImage(color, kShaderRead), hostImage(depth, kShaderRead), frame_, nullptr, nullptr, &targetHost);
      });
      const ImageRGBA8 result = toImage(vk::readbackImage(*context_, target, kCopiedOut), expected.width, expected.height);
      // 1 level: float sRGB decode/encode on the GPU against the reference's tables and rounding.
      EXPECT_LE(largestChannelDifference(result, expected), 1) << "output " << int(mode) << " read " << int(read);
    }
}

TEST_F(HostStereoPassTest, HalfPackingsOfAnOddSizeGiveTheSpareColumnAndRowToTheFirstEye) {
  // 47 x 31: each packed pixel of the gather's own half packing box-filters two or three eye pixels.
  constexpr std::uint32_t width = 47, height = 31;
  const SyntheticView view = makeBlockView(width, height, 11, 0.6f, 7, 5, false);
  const gpu::StereoConstants constants = stereo::makeStereoConstants(parameters_, width, height);
  const stereo::StereoPair reference = stereo::synthesizeStereoReference(view.color, view.depth, constants);
  auto upload = [&](VkFormat format, std::span<const std::byte> bytes) {
    vk::Image image =
        vk::createImage(*context_, format, width, height, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(*context_, image, bytes, kShaderRead);
    return image;
  };
  vk::Image color = upload(VK_FORMAT_R8G8B8A8_UNORM, std::as_bytes(std::span(view.color.pixels)));
  vk::Image depth = upload(VK_FORMAT_R32_SFLOAT, std::as_bytes(std::span(view.depth.pixels)));
  stereo::HostFrame frame = frame_;
  frame.stereo = constants;
  using stereo::PackingMode;
  const std::pair<HostOutput, ImageRGBA8> cases[] = {
      {HostOutput::SideBySideHalf, stereo::makeSideBySide(reference.left, reference.right, PackingMode::Half)},
      {HostOutput::TopBottomHalf, stereo::makeTopAndBottom(reference.left, reference.right, PackingMode::Half)}};
  for (const auto& [mode, expected] : cases)
    for (stereo::HostInputRead read : {stereo::HostInputRead::Direct, stereo::HostInputRead::Convert}) {
      stereo::HostStereoPass pass(*context_,
                                  {width, height, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, mode, false, read});
      vk::Image target = output(pass.eyeFormat(), pass.packedWidth(), pass.packedHeight());
      const HostImage targetHost = hostImage(target, kCopiedOut);
      runOnHostQueue([&](VkCommandBuffer cmd) {
        pass.record(cmd, hostImage(color, kShaderRead), hostImage(depth, kShaderRead), frame, nullptr, nullptr, &targetHost);
      });
      const ImageRGBA8 packed = toImage(vk::readbackImage(*context_, target, kCopiedOut), width, height);
      // 1 level: the eyes' rounding against the reference's (test_stereo_pass), then the same filter.
      EXPECT_LE(largestChannelDifference(packed, expected), 1) << "output " << int(mode) << " read " << int(read);
    }
}

// HDR colour before tone mapping: gathered in half floats at the reference's source columns.
void expectHdrEyes(HostStereoPassTest& test, VkFormat format);

TEST_F(HostStereoPassTest, Rgba16fColourGivesHalfFloatEyesAtTheReferenceColumns) {
  expectHdrEyes(*this, VK_FORMAT_R16G16B16A16_SFLOAT);
}
TEST_F(HostStereoPassTest, B10G11R11ColourGivesHalfFloatEyesAtTheReferenceColumns) {
  expectHdrEyes(*this, VK_FORMAT_B10G11R11_UFLOAT_PACK32);
}

TEST_F(HostStereoPassTest, StorageInputsSkipTheConversionAndGiveTheSameEyes) {
  const std::vector<std::byte> depthBytes = depthUpload(VK_FORMAT_R32_SFLOAT).bytes;
  const vk::ImageState computeWritten{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  vk::Image color = uploaded(VK_FORMAT_R8G8B8A8_UNORM, colorBytes(view_.color, VK_FORMAT_R8G8B8A8_UNORM), computeWritten,
                             VK_IMAGE_USAGE_STORAGE_BIT);
  vk::Image depth = uploaded(VK_FORMAT_R32_SFLOAT, depthBytes, computeWritten, VK_IMAGE_USAGE_STORAGE_BIT);
  stereo::HostStereoPass pass(*context_, {kWidth, kHeight, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT,
                                          HostOutput::TwoEyes, true});
  EXPECT_FALSE(pass.convertsInputs());
  vk::Image left = output(pass.eyeFormat(), kWidth, kHeight), right = output(pass.eyeFormat(), kWidth, kHeight);
  const HostImage leftHost = hostImage(left, kCopiedOut), rightHost = hostImage(right, kCopiedOut);
  runOnHostQueue([&](VkCommandBuffer cmd) {
    pass.record(cmd, hostImage(color, computeWritten), hostImage(depth, computeWritten), frame_, &leftHost, &rightHost, nullptr);
  });
  const stereo::StereoPair cpu = stereo::synthesizeStereoReference(view_.color, view_.depth, frame_.stereo);
  EXPECT_LE(largestChannelDifference(toImage(vk::readbackImage(*context_, left, kCopiedOut), kWidth, kHeight), cpu.left), 1);
  EXPECT_LE(largestChannelDifference(toImage(vk::readbackImage(*context_, right, kCopiedOut), kWidth, kHeight), cpu.right), 1);
}

// Frames in flight: one pass, per-frame host images, all frames submitted before any is waited for; then
// two recordings into one command buffer. Each frame's eyes are its own reference's.
void expectFramesInFlight(HostStereoPassTest& test, int frames, bool oneCommandBuffer);

TEST_F(HostStereoPassTest, TwoFramesInFlightEachGiveTheirReferenceEyes) { expectFramesInFlight(*this, 2, false); }
TEST_F(HostStereoPassTest, ThreeFramesInFlightEachGiveTheirReferenceEyes) { expectFramesInFlight(*this, 3, false); }
TEST_F(HostStereoPassTest, TwoRecordingsInOneCommandBufferEachGiveTheirReferenceEyes) {
  expectFramesInFlight(*this, 2, true);
}

TEST_F(HostStereoPassTest, AnUnsupportedColourFormatIsRefusedNamingTheChoices) {
  try {
    stereo::HostStereoPass pass(*context_, {kWidth, kHeight, VK_FORMAT_R5G6B5_UNORM_PACK16, VK_FORMAT_D32_SFLOAT,
                                            HostOutput::TwoEyes, false});
    FAIL() << "accepted R5G6B5";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("RGBA16F"), std::string::npos) << error.what();
  }
}

void expectHdrEyes(HostStereoPassTest& t, VkFormat format) {
  // Linear HDR colour up to 8, stored as the format stores it; the reference gathers the stored values.
  ImageRGBA32F center(kWidth, kHeight);
  std::vector<std::byte> bytes;
  for (std::size_t i = 0; i < center.pixelCount(); ++i) {
    glm::vec4 c = glm::vec4(t.view_.color.pixels[i * 4], t.view_.color.pixels[i * 4 + 1], t.view_.color.pixels[i * 4 + 2],
                            t.view_.color.pixels[i * 4 + 3]) / 32.0f;
    if (format == VK_FORMAT_B10G11R11_UFLOAT_PACK32) {
      const std::uint32_t packed = glm::packF2x11_1x10(glm::vec3(c));
      c = glm::vec4(glm::unpackF2x11_1x10(packed), 1.0f);
      bytes.insert(bytes.end(), reinterpret_cast<const std::byte*>(&packed), reinterpret_cast<const std::byte*>(&packed) + 4);
    } else {
      const glm::u16vec4 half = glm::packHalf(c);
      c = glm::unpackHalf(half);
      bytes.insert(bytes.end(), reinterpret_cast<const std::byte*>(&half), reinterpret_cast<const std::byte*>(&half) + 8);
    }
    std::memcpy(center.at(std::uint32_t(i % kWidth), std::uint32_t(i / kWidth)), &c, sizeof c);
  }
  const std::vector<std::byte> depthBytes = t.depthUpload(VK_FORMAT_R32_SFLOAT).bytes;
  vk::Image color = t.uploaded(format, bytes, kShaderRead);
  vk::Image depth = t.uploaded(VK_FORMAT_R32_SFLOAT, depthBytes, kShaderRead);
  for (stereo::HostInputRead read : {stereo::HostInputRead::Direct, stereo::HostInputRead::Convert}) {
    stereo::HostStereoPass pass(*t.context_, {kWidth, kHeight, format, VK_FORMAT_R32_SFLOAT, HostOutput::TwoEyes, false, read});
    ASSERT_EQ(pass.eyeFormat(), VK_FORMAT_R16G16B16A16_SFLOAT);
    vk::Image left = t.output(pass.eyeFormat(), kWidth, kHeight), right = t.output(pass.eyeFormat(), kWidth, kHeight);
    const HostImage leftHost = hostImage(left, kCopiedOut), rightHost = hostImage(right, kCopiedOut);
    t.runOnHostQueue([&](VkCommandBuffer cmd) {
      pass.record(cmd, hostImage(color, kShaderRead), hostImage(depth, kShaderRead), t.frame_, &leftHost, &rightHost, nullptr);
    });
    const stereo::HdrStereoPair expected = stereo::synthesizeHdrReference(center, t.view_.depth, t.parameters_);
    for (auto [image, reference] : {std::pair{&left, &expected.left}, std::pair{&right, &expected.right}}) {
      const std::vector<std::byte> texels = vk::readbackImage(*t.context_, *image, kCopiedOut);
      float largest = 0.0f;
      for (std::size_t i = 0; i < reference->pixels.size(); ++i) {
        std::uint16_t half;
        std::memcpy(&half, texels.data() + i * 2, 2);
        const float got = glm::unpackHalf1x16(half), want = reference->pixels[i];
        largest = std::max(largest, std::abs(got - want) / std::max(1.0f, std::abs(want)));
      }
      // Half-float storage of the filtered result: 2^-11 relative, plus the filter's float rounding.
      EXPECT_LE(largest, 1.5e-3f) << (read == stereo::HostInputRead::Direct ? "direct" : "converted");
    }
  }
}

void expectFramesInFlight(HostStereoPassTest& t, int frames, bool oneCommandBuffer) {
  stereo::HostStereoPass pass(*t.context_, {kWidth, kHeight, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT,
                                            HostOutput::TwoEyes, false});
  struct Frame {
    SyntheticView view;
    DepthImage expectedLinear;
    vk::Image color, depth, left, right;
    HostImage leftHost, rightHost;
  };
  std::vector<Frame> all(frames);
  for (int f = 0; f < frames; ++f) {
    Frame& frame = all[f];
    frame.view = makeBlockView(kWidth, kHeight, 100 + unsigned(f), 0.6f, 7, 5, false);
    DepthUpload depth = hardwareDepth(frame.view.depth, VK_FORMAT_D32_SFLOAT, t.frame_);
    frame.expectedLinear = depth.expectedLinear;
    frame.color = t.uploaded(VK_FORMAT_R8G8B8A8_UNORM, colorBytes(frame.view.color, VK_FORMAT_R8G8B8A8_UNORM), kShaderRead);
    frame.depth = t.uploaded(VK_FORMAT_D32_SFLOAT, depth.bytes, kDepthWritten, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    frame.left = t.output(pass.eyeFormat(), kWidth, kHeight);
    frame.right = t.output(pass.eyeFormat(), kWidth, kHeight);
    frame.leftHost = hostImage(frame.left, kCopiedOut);
    frame.rightHost = hostImage(frame.right, kCopiedOut);
  }
  runFramesInFlight(t.host(), frames, oneCommandBuffer, [&](VkCommandBuffer cmd, int f) {
    pass.record(cmd, hostImage(all[f].color, kShaderRead), hostImage(all[f].depth, kDepthWritten), t.frame_,
                &all[f].leftHost, &all[f].rightHost, nullptr);
  });
  for (Frame& frame : all) {
    const stereo::StereoPair cpu = stereo::synthesizeStereoReference(frame.view.color, frame.expectedLinear, t.frame_.stereo);
    EXPECT_LE(largestChannelDifference(toImage(vk::readbackImage(*t.context_, frame.left, kCopiedOut), kWidth, kHeight), cpu.left), 1);
    EXPECT_LE(largestChannelDifference(toImage(vk::readbackImage(*t.context_, frame.right, kCopiedOut), kWidth, kHeight), cpu.right), 1);
  }
}

// The depth range of a host's depth buffer as it is (stereo::DepthRangePass::recordHost), against the reference
// reduction of the stereo depth the host pass sees for it (hardwareDepth's expectedLinear: linearized, the weapon
// pushed). Tolerance: nearest and farthest within 1e-5 relative and histogram counts within 1 % of the pixels in
// all, because the GPU's division may round a linearized depth to the neighbouring float and so across a bin edge.
TEST_F(HostStereoPassTest, TheDepthRangeOfAHostsDepthBufferIsThatOfTheStereoDepthItHolds) {
  for (VkFormat format : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM, VK_FORMAT_R32_SFLOAT}) {
    if (!supports(format, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) continue;
    const bool hardware = format != VK_FORMAT_R32_SFLOAT;
    const DepthUpload depth = depthUpload(format);
    const vk::ImageState state = hardware ? kDepthWritten : kShaderRead;
    vk::Image image = uploaded(format, depth.bytes, state, hardware ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : 0);
    const stereo::DepthRangePass pass(*context_);
    runOnHostQueue([&](VkCommandBuffer cmd) {
      pass.recordHost(cmd, hostImage(image, state), kWidth, kHeight, frame_.projection, frame_.weaponDepthOffset,
                      frame_.weaponDepthScale);
    });
    const stereo::DepthRange gpu = pass.result();
    const stereo::DepthRange cpu = stereo::reduceDepthRangeReference(depth.expectedLinear);
    EXPECT_NEAR(gpu.nearest, cpu.nearest, 1e-5f * cpu.nearest) << int(format);
    EXPECT_NEAR(gpu.farthest, cpu.farthest, 1e-5f * cpu.farthest) << int(format);
    EXPECT_EQ(gpu.skyPixels, cpu.skyPixels) << int(format);
    std::uint64_t moved = 0;
    for (std::size_t b = 0; b < cpu.bins.size(); ++b)
      moved += std::uint64_t(std::abs(std::int64_t(gpu.bins[b]) - std::int64_t(cpu.bins[b])));
    EXPECT_LE(moved, std::uint64_t(kWidth) * kHeight / 100) << int(format);
  }
}

TEST_F(HostStereoPassTest, TheDepthRangeOfAnUnreadableDepthBufferWithoutABarrierIsRefused) {
  vk::Image image = uploaded(VK_FORMAT_R32_SFLOAT, std::vector<std::byte>(std::size_t(kWidth) * kHeight * 4), kShaderRead);
  stereo::HostImage host = hostImage(image, kShaderRead);
  host.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  host.stage = VK_PIPELINE_STAGE_2_NONE;
  const stereo::DepthRangePass pass(*context_);
  try {
    runOnHostQueue([&](VkCommandBuffer cmd) { pass.recordHost(cmd, host, kWidth, kHeight, frame_.projection); });
    ADD_FAILURE() << "an unreadable layout without a barrier was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("layout"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace s3d::test
