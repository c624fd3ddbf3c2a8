// The HUD pass on a host's images: element layers (s3d's uploaded ones and the host's own RGBA8/BGRA8 images)
// blended over both eyes at their parallax, faded by the weapon mask, held to the C++ reference (compositeHud);
// inside HostStereoPass before packing; 2 and 3 frames in flight and two recordings in one command buffer, with
// synchronization validation on (TestHost).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "s3d/hud/hud_pass.h"
#include "s3d/stereo/output_formats.h"
#include "stereo_test_views.h"
#include "test_host.h"

namespace s3d::test {
namespace {

using hud::HudElementFrame;
using hud::HudLayer;
using hud::HudPass;
using hud::HudPassDesc;
using hud::HudPassElement;
using stereo::HostImage;

constexpr std::uint32_t kWidth = 160, kHeight = 96;
constexpr vk::ImageState kShaderRead{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
constexpr vk::ImageState kCopiedOut{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                    VK_ACCESS_2_TRANSFER_READ_BIT};

HostImage hostImage(const vk::Image& image, const vk::ImageState& state) {
  return {image.image, image.view, image.format, state.layout, state.stage, state.access};
}
HostImage synchronizedByHost(const vk::Image& image, VkImageLayout layout) {
  return {image.image, image.view, image.format, layout, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
}

// Random colour whose alpha is a weapon mask: 0 on the weapon (bottom right), a soft edge, 255 elsewhere.
ImageRGBA8 eyeWithMask(unsigned seed) {
  std::mt19937 random(seed);
  ImageRGBA8 eye(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      std::uint8_t* p = eye.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(random() & 255u);
      const bool weapon = x >= 100 && y >= 50, edge = x >= 96 && x < 100 && y >= 50;
      p[3] = weapon ? 0 : edge ? std::uint8_t(60 * (x - 95)) : 255;
    }
  return eye;
}

// A host's layer: random colour, alpha from fully transparent through partial to opaque.
ImageRGBA8 randomLayer(std::uint32_t width, std::uint32_t height, unsigned seed) {
  std::mt19937 random(seed);
  ImageRGBA8 layer(width, height);
  for (std::size_t i = 0; i < layer.pixels.size(); ++i) layer.pixels[i] = std::uint8_t(random() & 255u);
  for (std::size_t i = 3; i < layer.pixels.size(); i += 16) layer.pixels[i] = 0;
  for (std::size_t i = 7; i < layer.pixels.size(); i += 16) layer.pixels[i] = 255;
  return layer;
}

std::vector<std::byte> bytesOf(const ImageRGBA8& image, VkFormat format) {
  std::vector<std::byte> bytes(image.pixels.size());
  std::memcpy(bytes.data(), image.pixels.data(), bytes.size());
  if (format == VK_FORMAT_B8G8R8A8_UNORM)
    for (std::size_t i = 0; i < bytes.size(); i += 4) std::swap(bytes[i], bytes[i + 2]);
  return bytes;
}

// The scene of every test: the built-in panels and crosshair, then two host layers (RGBA8 at the left edge, so the
// left eye clips it, and BGRA8), with fractional parallaxes, fades behind the weapon and one hidden element.
struct HudScene {
  std::vector<HudLayer> layers;  // the reference's copy of every element, host layers included
  std::vector<HudElementFrame> frames;
  HudPassDesc desc;
  VkFormat hostFormats[2] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM};

  explicit HudScene(unsigned seed) {
    layers = hud::builtInHudLayers(kWidth, kHeight);  // health, ammo, crosshair
    layers.push_back({"radar", randomLayer(13, 9, seed), {2.0f, 30.0f, 0, 0}});
    layers.push_back({"tag", randomLayer(7, 5, seed + 1), {104.0f, 60.0f, 3, 2}});  // over the weapon
    frames = {{3.3f, true, false}, {-1.7f, false, true}, {2.5f, false, false}, {4.6f, true, false},
              {-0.5f + 0.1f * float(seed % 3), true, false}};
    desc.width = kWidth;
    desc.height = kHeight;
    for (std::size_t i = 0; i < layers.size(); ++i)
      desc.elements.push_back(i < 3 ? HudPassElement::uploaded(layers[i])
                                    : HudPassElement::hostLayer(layers[i].name, layers[i].pixels.width,
                                                                layers[i].pixels.height, layers[i].placement));
  }
  stereo::StereoPair expected(const stereo::StereoPair& eyes) const {
    stereo::StereoPair result = eyes;
    hud::compositeHud(result.left, stereo::Eye::Left, layers, frames);
    hud::compositeHud(result.right, stereo::Eye::Right, layers, frames);
    return result;
  }
};

class HudPassTest : public HostContextTest {
 public:
  using HostContextTest::context_;  // the frames-in-flight helper below uses it
  vk::Image eye(const ImageRGBA8& content, const vk::ImageState& state) {
    vk::Image image = vk::createImage(*context_, VK_FORMAT_R8G8B8A8_UNORM, content.width, content.height,
                                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(*context_, image, bytesOf(content, image.format), state);
    return image;
  }
  vk::Image layer(const ImageRGBA8& pixels, VkFormat format, const vk::ImageState& state) {
    vk::Image image = vk::createImage(*context_, format, pixels.width, pixels.height,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(*context_, image, bytesOf(pixels, format), state);
    return image;
  }
  std::vector<vk::Image> hostLayers(const HudScene& scene, const vk::ImageState& state) {
    std::vector<vk::Image> images;
    for (int i = 0; i < 2; ++i) images.push_back(layer(scene.layers[3 + i].pixels, scene.hostFormats[i], state));
    return images;
  }
  ImageRGBA8 read(const vk::Image& image, const vk::ImageState& state) {
    ImageRGBA8 result(image.width, image.height);
    const std::vector<std::byte> bytes = vk::readbackImage(*context_, image, state);
    std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
    return result;
  }
};

// 1 level: the shader's float division may differ from the CPU's by an ulp (Vulkan allows 2.5), which moves a blend
// that lands within that of a half level to the other side; everything else is the same float arithmetic.
constexpr int kHudTolerance = 1;

TEST_F(HudPassTest, ElementsBlendedOverBothEyesAreTheReferenceHud) {
  const HudScene scene(1);
  const HudPass pass(*context_, scene.desc);
  const stereo::StereoPair before{eyeWithMask(10), eyeWithMask(11)};
  vk::Image left = eye(before.left, kCopiedOut), right = eye(before.right, kCopiedOut);
  const std::vector<vk::Image> layers = hostLayers(scene, kShaderRead);
  const HostImage hostLayerImages[] = {hostImage(layers[0], kShaderRead), hostImage(layers[1], kShaderRead)};
  runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
    pass.record(cmd, scene.frames, hostLayerImages, hostImage(left, kCopiedOut), hostImage(right, kCopiedOut));
  });
  const stereo::StereoPair expected = scene.expected(before);
  EXPECT_GT(largestChannelDifference(expected.left, before.left), 100) << "the HUD drew something";
  EXPECT_LE(largestChannelDifference(read(left, kCopiedOut), expected.left), kHudTolerance);
  EXPECT_LE(largestChannelDifference(read(right, kCopiedOut), expected.right), kHudTolerance);
}

TEST_F(HudPassTest, ImagesTheHostSynchronizesItselfGiveTheSameHud) {
  const HudScene scene(2);
  const HudPass pass(*context_, scene.desc);
  const stereo::StereoPair before{eyeWithMask(20), eyeWithMask(21)};
  vk::Image left = eye(before.left, vk::kComputeWrite), right = eye(before.right, vk::kComputeWrite);
  const vk::ImageState computeRead{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  const std::vector<vk::Image> layers = hostLayers(scene, computeRead);
  const HostImage hostLayerImages[] = {synchronizedByHost(layers[0], computeRead.layout),
                                       synchronizedByHost(layers[1], computeRead.layout)};
  runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
    pass.record(cmd, scene.frames, hostLayerImages, synchronizedByHost(left, VK_IMAGE_LAYOUT_GENERAL),
                synchronizedByHost(right, VK_IMAGE_LAYOUT_GENERAL));
  });
  const stereo::StereoPair expected = scene.expected(before);
  EXPECT_LE(largestChannelDifference(read(left, vk::kComputeWrite), expected.left), kHudTolerance);
  EXPECT_LE(largestChannelDifference(read(right, vk::kComputeWrite), expected.right), kHudTolerance);
}

// The stereo pass's own eyes for a block view, and the same view's images for further recordings.
struct StereoInput {
  SyntheticView view = makeBlockView(kWidth, kHeight, 7, 0.6f, 7, 5, false);
  stereo::HostFrame frame;
  StereoInput() {
    stereo::StereoParameters parameters;
    parameters.maxSeparation = 0.04f;
    parameters.zeroParallaxDistance = 3.0f;
    frame.stereo = stereo::makeStereoConstants(parameters, kWidth, kHeight);
  }
};

TEST_F(HudPassTest, InsideTheHostStereoPassEyesAndPackedTargetsCarryTheHud) {
  const StereoInput input;
  const HudScene scene(3);
  const HudPass hud(*context_, scene.desc);
  vk::Image color = layer(input.view.color, VK_FORMAT_R8G8B8A8_UNORM, kShaderRead);
  vk::Image depth = vk::createImage(*context_, VK_FORMAT_R32_SFLOAT, kWidth, kHeight,
                                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(*context_, depth, std::as_bytes(std::span(input.view.depth.pixels)), kShaderRead);
  const std::vector<vk::Image> layers = hostLayers(scene, kShaderRead);
  const HostImage hostLayerImages[] = {hostImage(layers[0], kShaderRead), hostImage(layers[1], kShaderRead)};
  auto eyesOf = [&](const hud::HudOverlay* overlay) {
    stereo::HostStereoPass pass(*context_, {kWidth, kHeight, color.format, depth.format, stereo::HostOutput::TwoEyes});
    vk::Image left = eye(ImageRGBA8(kWidth, kHeight), kCopiedOut), right = eye(ImageRGBA8(kWidth, kHeight), kCopiedOut);
    const HostImage l = hostImage(left, kCopiedOut), r = hostImage(right, kCopiedOut);
    runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
      pass.record(cmd, hostImage(color, kShaderRead), hostImage(depth, kShaderRead), input.frame, &l, &r, nullptr, overlay);
    });
    return stereo::StereoPair{read(left, kCopiedOut), read(right, kCopiedOut)};
  };
  const stereo::StereoPair own = eyesOf(nullptr);  // the pass's eyes without HUD, then the reference HUD on them
  const stereo::StereoPair expected = scene.expected(own);
  const hud::HudOverlay overlay = hud.overlay(scene.frames, hostLayerImages);
  const stereo::StereoPair withHud = eyesOf(&overlay);
  EXPECT_LE(largestChannelDifference(withHud.left, expected.left), kHudTolerance);
  EXPECT_LE(largestChannelDifference(withHud.right, expected.right), kHudTolerance);

  using stereo::HostOutput;
  const std::pair<HostOutput, ImageRGBA8> cases[] = {
      {HostOutput::Anaglyph, stereo::makeAnaglyphDubois(expected.left, expected.right)},
      {HostOutput::SideBySideHalf, stereo::makeSideBySide(expected.left, expected.right, stereo::PackingMode::Half)}};
  for (const auto& [mode, packed] : cases) {
    stereo::HostStereoPass pass(*context_, {kWidth, kHeight, color.format, depth.format, mode});
    vk::Image target = eye(ImageRGBA8(pass.packedWidth(), pass.packedHeight()), kCopiedOut);
    const HostImage t = hostImage(target, kCopiedOut);
    runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
      pass.record(cmd, hostImage(color, kShaderRead), hostImage(depth, kShaderRead), input.frame, nullptr, nullptr, &t,
                  &overlay);
    });
    // The HUD's level plus the packing's (float sRGB decode/encode against the reference's tables and rounding).
    EXPECT_LE(largestChannelDifference(read(target, kCopiedOut), packed), kHudTolerance + 1) << "output " << int(mode);
  }
}

// One HUD pass, per-frame eyes and host layers, every frame submitted before any is waited for (or all recorded
// into one command buffer); each frame's eyes are its own reference HUD.
void expectFramesInFlight(HudPassTest& t, int frames, bool oneCommandBuffer) {
  const HudScene shape(4);
  const HudPass pass(*t.context_, shape.desc);
  struct Frame {
    HudScene scene;
    stereo::StereoPair before;
    vk::Image left, right;
    std::vector<vk::Image> layers;
    std::vector<HostImage> hostLayers;
  };
  std::vector<Frame> all;
  for (int f = 0; f < frames; ++f) {
    Frame frame{HudScene(40 + unsigned(f)), {eyeWithMask(50 + unsigned(f)), eyeWithMask(60 + unsigned(f))}, {}, {}, {}, {}};
    frame.left = t.eye(frame.before.left, kCopiedOut);
    frame.right = t.eye(frame.before.right, kCopiedOut);
    frame.layers = t.hostLayers(frame.scene, kShaderRead);
    for (const vk::Image& image : frame.layers) frame.hostLayers.push_back(hostImage(image, kShaderRead));
    all.push_back(std::move(frame));
  }
  runFramesInFlight(sharedTestHost(), frames, oneCommandBuffer, [&](VkCommandBuffer cmd, int f) {
    pass.record(cmd, all[f].scene.frames, all[f].hostLayers, hostImage(all[f].left, kCopiedOut),
                hostImage(all[f].right, kCopiedOut));
  });
  for (const Frame& frame : all) {
    const stereo::StereoPair expected = frame.scene.expected(frame.before);
    EXPECT_LE(largestChannelDifference(t.read(frame.left, kCopiedOut), expected.left), kHudTolerance);
    EXPECT_LE(largestChannelDifference(t.read(frame.right, kCopiedOut), expected.right), kHudTolerance);
  }
}

TEST_F(HudPassTest, TwoFramesInFlightEachGiveTheirReferenceHud) { expectFramesInFlight(*this, 2, false); }
TEST_F(HudPassTest, ThreeFramesInFlightEachGiveTheirReferenceHud) { expectFramesInFlight(*this, 3, false); }
TEST_F(HudPassTest, TwoRecordingsInOneCommandBufferEachGiveTheirReferenceHud) { expectFramesInFlight(*this, 2, true); }

TEST_F(HudPassTest, HalfFloatEyesAreRefusedNamingTheEyeFormat) {
  const HudScene scene(5);
  const HudPass pass(*context_, scene.desc);
  vk::Image hdr = vk::createImage(*context_, VK_FORMAT_R16G16B16A16_SFLOAT, kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  const std::vector<vk::Image> layers = hostLayers(scene, kShaderRead);
  const HostImage hostLayerImages[] = {hostImage(layers[0], kShaderRead), hostImage(layers[1], kShaderRead)};
  const HostImage eyeImage = synchronizedByHost(hdr, VK_IMAGE_LAYOUT_GENERAL);
  try {
    runOnHostQueue(host(), [&](VkCommandBuffer cmd) { pass.record(cmd, scene.frames, hostLayerImages, eyeImage, eyeImage); });
    FAIL() << "accepted RGBA16F eyes";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("R8G8B8A8_UNORM"), std::string::npos) << error.what();
  }
}

TEST_F(HudPassTest, AMissingOrWrongHostLayerIsRefusedNamingTheElement) {
  const HudScene scene(6);
  const HudPass pass(*context_, scene.desc);
  vk::Image left = eye(eyeWithMask(1), kCopiedOut), right = eye(eyeWithMask(2), kCopiedOut);
  vk::Image srgb = layer(scene.layers[3].pixels, VK_FORMAT_R8G8B8A8_SRGB, kShaderRead);
  const std::vector<vk::Image> layers = hostLayers(scene, kShaderRead);
  const HostImage wrongFormat[] = {hostImage(srgb, kShaderRead), hostImage(layers[1], kShaderRead)};
  const HostImage missing[] = {HostImage{}, hostImage(layers[1], kShaderRead)};
  auto message = [&](std::span<const HostImage> hostLayers, std::span<const HudElementFrame> frames) {
    try {
      runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
        pass.record(cmd, frames, hostLayers, hostImage(left, kCopiedOut), hostImage(right, kCopiedOut));
      });
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(wrongFormat, scene.frames).find("'radar' must be R8G8B8A8_UNORM"), std::string::npos);
  EXPECT_NE(message(missing, scene.frames).find("layer 'radar' image is missing"), std::string::npos);
  EXPECT_NE(message(std::span(wrongFormat).first(1), scene.frames).find("1 host layer images for 2"), std::string::npos);
  EXPECT_NE(message(wrongFormat, std::span(scene.frames).first(4)).find("4 element states for 5"), std::string::npos);
}

TEST_F(HudPassTest, AnElementWithoutPixelsOrSizeIsRefusedAtConstructionNamingIt) {
  HudPassDesc desc{kWidth, kHeight, {HudPassElement::hostLayer("minimap", 0, 8, {})}};
  try {
    HudPass pass(*context_, desc);
    FAIL() << "accepted a host layer of width 0";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("'minimap'"), std::string::npos) << error.what();
  }
  desc.elements.assign(S3D_HUD_MAX_ELEMENTS + 1, HudPassElement::hostLayer("x", 1, 1, {}));
  EXPECT_THROW(HudPass(*context_, desc), std::invalid_argument);
}

}  // namespace
}  // namespace s3d::test
