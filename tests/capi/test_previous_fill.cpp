// The previous-frame fill: the forward method's holes take what the previous frame's eye showed there, found by
// reprojecting with depth and camera motion; the GPU pass, and a host's stereo frame in C++ and through the C API,
// held to the C++ implementation over a moving camera's frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "capi_test_context.h"
#include "s3d/s3d.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/forward_pass.h"
#include "s3d/stereo/previous_fill.h"
#include "s3d/stereo/previous_fill_pass.h"
#include "s3d/stereo/reprojection.h"
#include "s3d/stereo/stereo_frame.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

using test::largestChannelDifference;

// A textured background wall at depth 10 and a textured slab at depth 2 over world x in [-0.3, 0.3], seen by
// cameras on the x axis looking down -z: an analytic scene whose center views and true eyes are exact.
constexpr std::uint32_t kWidth = 128, kHeight = 16;
constexpr float kSeparation = 0.05f, kZeroParallax = 3.0f;  // slab -3.2 px, wall +4.5 px: holes about 8 px wide

glm::mat4 centerProjection() {
  glm::mat4 p(0.0f);
  p[0][0] = 1.0f;                                  // tangent +-1 over the width
  p[1][1] = -float(kWidth) / float(kHeight);       // square pixels, y down
  p[2][3] = -1.0f;
  p[3][2] = 0.1f;
  return p;
}

glm::mat4 viewAt(float cameraX) { return glm::translate(glm::mat4(1.0f), glm::vec3(-cameraX, 0.0f, 0.0f)); }

struct Frame {
  ImageRGBA8 color;
  DepthImage depth;
};

// What a camera (view = a translation along x, any off-axis projection) sees of the scene.
Frame render(const glm::mat4& view, const glm::mat4& projection) {
  Frame frame{ImageRGBA8(kWidth, kHeight), DepthImage(kWidth, kHeight)};
  const float cameraX = -view[3][0];
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float tx = ((2.0f * (float(x) + 0.5f) / float(kWidth) - 1.0f) + projection[2][0]) / projection[0][0];
      const float ty = ((2.0f * (float(y) + 0.5f) / float(kHeight) - 1.0f) + projection[2][1]) / projection[1][1];
      float depth = 2.0f;
      float worldX = cameraX + tx * depth;
      const bool slab = worldX >= -0.3f && worldX < 0.3f;
      if (!slab) depth = 10.0f, worldX = cameraX + tx * depth;
      const float worldY = ty * depth;
      std::uint8_t* pixel = frame.color.at(x, y);
      pixel[0] = std::uint8_t(slab ? 40 : 128 + 100 * std::sin(worldX * 9.0f));
      pixel[1] = std::uint8_t(slab ? 200 + 40 * std::sin(worldX * 30.0f) : 128 + 100 * std::cos(worldY * 7.0f + worldX));
      pixel[2] = std::uint8_t(slab ? 60 : std::fmod(std::abs(worldX) * 300.0f, 256.0f));
      pixel[3] = 255;
      *frame.depth.at(x, y) = depth;
    }
  return frame;
}

StereoParameters forwardParameters() {
  StereoParameters p;
  p.method = StereoMethod::Forward;
  p.maxSeparation = kSeparation;
  p.zeroParallaxDistance = kZeroParallax;
  p.edgeCrop = 0.0f;
  return p;
}

EyeCamera eyeCamera(float cameraX, Eye eye) {
  return offAxisEyeCamera(viewAt(cameraX), centerProjection(), eye, kSeparation, kZeroParallax);
}

std::array<gpu::EyeMotion, 2> motionBetween(float currentX, float previousX) {
  std::array<gpu::EyeMotion, 2> motion;
  for (Eye eye : {Eye::Left, Eye::Right}) {
    const EyeCamera now = eyeCamera(currentX, eye), before = eyeCamera(previousX, eye);
    motion[eye == Eye::Left ? 0 : 1] = eyeMotion(now.view, now.projection, before.view, before.projection);
  }
  return motion;
}

// Mean absolute error (levels, RGB) of an eye against the true eye over the given pixels.
double meanError(const ImageRGBA8& eye, const ImageRGBA8& truth, const std::vector<std::size_t>& pixels) {
  double sum = 0.0;
  for (std::size_t i : pixels)
    for (int c = 0; c < 3; ++c) sum += std::abs(int(eye.pixels[i * 4 + std::size_t(c)]) - int(truth.pixels[i * 4 + std::size_t(c)]));
  return pixels.empty() ? 0.0 : sum / double(3 * pixels.size());
}

std::vector<std::size_t> holes(const DepthImage& depth, float direction, const gpu::ForwardConstants& c) {
  std::vector<std::size_t> result;
  for (int y = 0; y < c.height; ++y) {
    const std::vector<std::uint32_t> keys = forwardSplatRow(depth, y, direction, c);
    for (int x = 0; x < c.width; ++x)
      if (keys[std::size_t(x)] == S3D_FORWARD_EMPTY) result.push_back(std::size_t(y) * std::size_t(c.width) + std::size_t(x));
  }
  return result;
}

const gpu::ForwardConstants kConstants = makeForwardConstants(forwardParameters(), kWidth, kHeight);
// The host tests' camera positions along x, a frame each.
constexpr float kHostPositions[3] = {0.0f, 0.3f, 0.45f};

TEST(PreviousFrameFill, FillsTheHolesTheMovingCameraSawBefore) {
  // The camera moves right by the eyes' half separation per frame (0.3): the previous center stood where the
  // left eye stands now, so the previous left eye had the wall behind the slab's left edge.
  const Frame before = render(viewAt(0.0f), centerProjection()), now = render(viewAt(0.3f), centerProjection());
  const ForwardWithHistory first = synthesizeForwardWithPreviousFrameReference(before.color, before.depth, kConstants,
                                                                              motionBetween(0.0f, 0.0f), nullptr);
  const ForwardWithHistory filled = synthesizeForwardWithPreviousFrameReference(
      now.color, now.depth, kConstants, motionBetween(0.3f, 0.0f), &first.history);
  const StereoPair plain = synthesizeForwardReference(now.color, now.depth, kConstants);
  const EyeCamera leftEye = eyeCamera(0.3f, Eye::Left);
  const Frame truth = render(leftEye.view, leftEye.projection);
  const std::vector<std::size_t> leftHoles = holes(now.depth, 1.0f, kConstants);
  ASSERT_GT(leftHoles.size(), 4u * kHeight);
  EXPECT_EQ(filled.counts[0].holePixels, leftHoles.size());
  EXPECT_GT(filled.counts[0].filledFromPrevious, leftHoles.size() / 2);
  const double plainError = meanError(plain.left, truth.color, leftHoles);
  const double filledError = meanError(filled.eyes.left, truth.color, leftHoles);
  EXPECT_LT(filledError, plainError / 2.0) << plainError << " -> " << filledError;
  // Covered pixels are the forward method's, untouched.
  for (std::size_t i = 0; i < plain.left.pixelCount(); ++i) {
    if (std::find(leftHoles.begin(), leftHoles.end(), i) != leftHoles.end()) continue;
    ASSERT_EQ(std::memcmp(&plain.left.pixels[i * 4], &filled.eyes.left.pixels[i * 4], 4), 0) << i;
  }
}

TEST(PreviousFrameFill, OnAStaticCameraTheHolesKeepTheirFill) {
  const Frame frame = render(viewAt(0.0f), centerProjection());
  const std::array<gpu::EyeMotion, 2> still = motionBetween(0.0f, 0.0f);
  const ForwardWithHistory first = synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants, still, nullptr);
  const ForwardWithHistory second =
      synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants, still, &first.history);
  // The previous eye shows each hole's own fill at its own depth: nothing changes (1 level: the bilinear
  // weights of a static round trip are 1 within float rounding).
  EXPECT_GT(second.counts[0].filledFromPrevious, 0u);
  EXPECT_LE(largestChannelDifference(second.eyes.left, first.eyes.left), 1);
  EXPECT_LE(largestChannelDifference(second.eyes.right, first.eyes.right), 1);
}

TEST(PreviousFrameFill, TheWeaponsHistoryNeverFillsAHole) {
  // The weapon (alpha 0 in the eyes) moves with the camera, not with the world: mark the whole previous frame as
  // weapon and nothing may come from it.
  const Frame before = render(viewAt(0.0f), centerProjection()), now = render(viewAt(0.3f), centerProjection());
  ForwardWithHistory first = synthesizeForwardWithPreviousFrameReference(before.color, before.depth, kConstants,
                                                                        motionBetween(0.0f, 0.0f), nullptr);
  for (EyeHistory& eye : first.history)
    for (std::size_t i = 3; i < eye.color.pixels.size(); i += 4) eye.color.pixels[i] = 0;
  const ForwardWithHistory second = synthesizeForwardWithPreviousFrameReference(
      now.color, now.depth, kConstants, motionBetween(0.3f, 0.0f), &first.history);
  EXPECT_GT(second.counts[0].holePixels, 0u);
  EXPECT_EQ(second.counts[0].filledFromPrevious, 0u);
  EXPECT_EQ(second.counts[1].filledFromPrevious, 0u);
}

TEST(PreviousFrameFill, TheOccluderNeverFillsItsOwnDisocclusion) {
  // A previous frame that showed the slab (depth 2) everywhere, on a static camera: the holes beside the slab find
  // it at their own position, at the occluder's depth, and must keep the forward method's fill.
  const Frame frame = render(viewAt(0.0f), centerProjection());
  const std::array<gpu::EyeMotion, 2> still = motionBetween(0.0f, 0.0f);
  ForwardWithHistory first = synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants, still, nullptr);
  for (EyeHistory& eye : first.history)
    for (float& d : eye.depth.pixels) d = 2.0f;
  const ForwardWithHistory second =
      synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants, still, &first.history);
  // Columns [16, 112): the holes beside the slab (the image's outer columns have holes with one covered side
  // only, which no occluder bounds).
  const StereoPair plain = synthesizeForwardReference(frame.color, frame.depth, kConstants);
  for (auto [eye, expected] : {std::pair{&second.eyes.left, &plain.left}, std::pair{&second.eyes.right, &plain.right}})
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 16; x < 112; ++x)
        ASSERT_EQ(std::memcmp(eye->at(x, y), expected->at(x, y), 4), 0) << x << "," << y;
  EXPECT_GE(second.counts[0].holePixels, 10u * kHeight);  // about 7 columns beside the slab, 4 at the border
}

TEST(PreviousFrameFill, WithoutHistoryItIsTheForwardMethod) {
  const Frame frame = render(viewAt(0.0f), centerProjection());
  const ForwardWithHistory first =
      synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants, motionBetween(0.0f, 0.0f), nullptr);
  const StereoPair plain = synthesizeForwardReference(frame.color, frame.depth, kConstants);
  EXPECT_EQ(first.eyes.left.pixels, plain.left.pixels);
  EXPECT_EQ(first.eyes.right.pixels, plain.right.pixels);
  EXPECT_EQ(first.counts[0].filledFromPrevious, 0u);
}

TEST(PreviousFrameFill, NeedsTheForwardMethod) {
  StereoParameters p = forwardParameters();
  p.previousFrameFill = true;
  EXPECT_NO_THROW(validate(p));
  p.method = StereoMethod::Search;
  EXPECT_THROW(validate(p), std::invalid_argument);
}

TEST(PreviousFrameFill, RefusesTheNonlinearMapping) {
  // The fill reprojects the previous eyes as views of one pair of eye cameras; a nonlinear map's eyes are not.
  StereoParameters p = forwardParameters();
  p.previousFrameFill = true;
  p.disparityMapping = DisparityMapping::Nonlinear;
  EXPECT_THROW(validate(p), std::invalid_argument);
  p.previousFrameFill = false;
  EXPECT_NO_THROW(validate(p));  // the forward method itself takes the mapped depth like any other
}

class PreviousFillPassTest : public test::VulkanTest {};

TEST_F(PreviousFillPassTest, GpuMatchesTheCppReferenceOverTwoFrames) {
  const float positions[3] = {0.0f, 0.3f, 0.45f};
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = [&](VkFormat format) { return vk::createImage(context(), format, kWidth, kHeight, usage); };
  const vk::Image color = image(VK_FORMAT_R8G8B8A8_UNORM), depth = image(VK_FORMAT_R32_SFLOAT);
  const vk::Image left = image(VK_FORMAT_R8G8B8A8_UNORM), right = image(VK_FORMAT_R8G8B8A8_UNORM);
  const ForwardStereoPass forward(context(), StereoKernel::Auto, ForwardKeys::Kept);
  PreviousFillPass fill(context());
  std::optional<ForwardWithHistory> cpu;
  for (int f = 0; f < 3; ++f) {
    const Frame frame = render(viewAt(positions[f]), centerProjection());
    const std::array<gpu::EyeMotion, 2> motion = motionBetween(positions[f], positions[f > 0 ? f - 1 : 0]);
    vk::uploadImage(context(), color, std::as_bytes(std::span(frame.color.pixels)), vk::kComputeRead);
    vk::uploadImage(context(), depth, std::as_bytes(std::span(frame.depth.pixels)), vk::kComputeRead);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      vk::transition(cmd, left, vk::kUndefined, vk::kComputeWrite);
      vk::transition(cmd, right, vk::kUndefined, vk::kComputeWrite);
      forward.record(cmd, color, depth, left, right, kConstants);
      fill.record(cmd, forward, left, right, kConstants, motion);
    });
    fill.advance();
    cpu = synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants, motion,
                                                     cpu ? &cpu->history : nullptr);
    for (auto [eye, expected] : {std::pair{&left, &cpu->eyes.left}, std::pair{&right, &cpu->eyes.right}}) {
      ImageRGBA8 got(kWidth, kHeight);
      const std::vector<std::byte> bytes = vk::readbackImage(context(), *eye, vk::kComputeWrite);
      std::memcpy(got.pixels.data(), bytes.data(), bytes.size());
      // 1 level: the GPU's unorm conversion of a filtered value may round the other way.
      EXPECT_LE(largestChannelDifference(got, *expected), 1) << "frame " << f;
    }
    if (f > 0) {
      EXPECT_GT(cpu->counts[0].filledFromPrevious, 0u);
    }
  }
}

// A host's three frames of the moving camera (the eyes read back after each) against the C++ reference's: `record`
// records frame f's stereo frame from the host's colour and depth into its eyes (GENERAL, the test synchronizes).
void expectHostSequenceMatchesTheReference(
    vk::Context& context, const std::function<void(VkCommandBuffer, int, const vk::Image& color, const vk::Image& depth,
                                                   const vk::Image& left, const vk::Image& right)>& record) {
  auto image = [&](VkFormat format, VkImageUsageFlags usage) {
    return vk::createImage(context, format, kWidth, kHeight, usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  };
  const vk::Image color = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT);
  const vk::Image depth = image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT);
  const vk::Image left = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
  const vk::Image right = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* eye : {&left, &right}) vk::transition(cmd, *eye, vk::kUndefined, vk::kComputeWrite);
  });
  std::optional<ForwardWithHistory> cpu;
  for (int f = 0; f < 3; ++f) {
    const Frame frame = render(viewAt(kHostPositions[f]), centerProjection());
    vk::uploadImage(context, color, std::as_bytes(std::span(frame.color.pixels)), vk::kComputeRead);
    vk::uploadImage(context, depth, std::as_bytes(std::span(frame.depth.pixels)), vk::kComputeRead);
    context.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, f, color, depth, left, right); });
    cpu = synthesizeForwardWithPreviousFrameReference(frame.color, frame.depth, kConstants,
                                                     motionBetween(kHostPositions[f], kHostPositions[f > 0 ? f - 1 : 0]),
                                                     cpu ? &cpu->history : nullptr);
    for (auto [eye, expected] : {std::pair{&left, &cpu->eyes.left}, std::pair{&right, &cpu->eyes.right}}) {
      ImageRGBA8 got(kWidth, kHeight);
      const std::vector<std::byte> bytes = vk::readbackImage(context, *eye, vk::kComputeWrite);
      std::memcpy(got.pixels.data(), bytes.data(), bytes.size());
      EXPECT_LE(largestChannelDifference(got, *expected), 1) << "frame " << f;  // as the pass's own test above
    }
  }
  EXPECT_GT(cpu->counts[0].filledFromPrevious, 0u);  // the last frame's holes took the history
}

TEST_F(PreviousFillPassTest, AHostsStereoFrameSequenceMatchesTheCppReference) {
  // The host hands its center camera each frame; the frame derives the eye cameras and their motion itself.
  StereoFrameDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  desc.depthFormat = VK_FORMAT_R32_SFLOAT;
  desc.method = StereoMethod::Forward;
  desc.previousFrameFill = true;
  StereoFrame stereoFrame(context(), desc);
  auto host = [](const vk::Image& i) { return HostImage{i.image, i.view, i.format, VK_IMAGE_LAYOUT_GENERAL}; };
  expectHostSequenceMatchesTheReference(context(), [&](VkCommandBuffer cmd, int f, const vk::Image& color,
                                                       const vk::Image& depth, const vk::Image& left,
                                                       const vk::Image& right) {
    StereoFrameDispatch dispatch;
    dispatch.color = host(color);
    dispatch.depth = host(depth);
    dispatch.left = host(left);
    dispatch.right = host(right);
    dispatch.maxSeparation = kSeparation;
    dispatch.zeroParallaxDistance = kZeroParallax;
    dispatch.edgeCrop = 0.0f;
    dispatch.centerView = viewAt(kHostPositions[f]);
    dispatch.centerProjection = centerProjection();
    stereoFrame.record(cmd, dispatch);
  });
}

TEST_F(PreviousFillPassTest, AHostsStereoFrameSequenceThroughTheCApiMatchesTheCppReference) {
  // The same sequence as a host binding C records it: s3d_stereo_frame_dispatch's camera fields, column-major.
  const test::CContext c(context());
  s3d_stereo_frame_desc desc;
  s3d_default_stereo_frame_desc(&desc);
  desc.width = kWidth;
  desc.height = kHeight;
  desc.color_format = VK_FORMAT_R8G8B8A8_UNORM;
  desc.depth_format = VK_FORMAT_R32_SFLOAT;
  desc.method = S3D_METHOD_FORWARD;
  desc.previous_frame_fill = 1;
  s3d_stereo_frame frame = nullptr;
  ASSERT_EQ(s3d_stereo_frame_create(c.get(), &desc, &frame), S3D_SUCCESS) << s3d_last_error();
  expectHostSequenceMatchesTheReference(context(), [&](VkCommandBuffer cmd, int f, const vk::Image& color,
                                                       const vk::Image& depth, const vk::Image& left,
                                                       const vk::Image& right) {
    s3d_stereo_frame_dispatch dispatch;
    s3d_default_stereo_frame_dispatch(&dispatch);
    dispatch.color = test::cImage(color);
    dispatch.depth = test::cImage(depth);
    dispatch.left = test::cImage(left);
    dispatch.right = test::cImage(right);
    dispatch.max_separation = kSeparation;
    dispatch.zero_parallax_distance = kZeroParallax;
    dispatch.edge_crop = 0.0f;
    const glm::mat4 view = viewAt(kHostPositions[f]), projection = centerProjection();
    std::memcpy(dispatch.center_view, &view[0][0], sizeof dispatch.center_view);
    std::memcpy(dispatch.center_projection, &projection[0][0], sizeof dispatch.center_projection);
    EXPECT_EQ(s3d_stereo_frame_record(frame, cmd, &dispatch), S3D_SUCCESS) << s3d_last_error();
  });
  s3d_stereo_frame_destroy(frame);
}

}  // namespace
}  // namespace s3d::stereo
