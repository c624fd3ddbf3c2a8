// A host's stereo frame with its comfort rules in one object (host_comfort_frame.h): the budget follows the depth
// its reduction ring saw framesInFlight frames ago, the eyes are the plain stereo frame's with the state's
// parameters, and bad calls are refused naming the field. Synchronization validation on (TestHost): the reduction
// and the stereo frame both barrier the host's D32 depth from its depth-attachment state.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "host_pass_fixture.h"
#include "io_test_support.h"
#include "s3d/comfort/display_profile.h"
#include "s3d/comfort/host_comfort_frame.h"
#include "s3d/stereo/depth_range.h"

namespace s3d::test {
namespace {

using comfort::HostComfortFrame;
using comfort::HostComfortFrameDesc;
using comfort::HostComfortInput;

constexpr float kHostSeparation = 0.03f, kHostZeroParallax = 100.0f, kCrosshair = 10.0f;

// One frame's host images: colour, D32 depth as a renderer leaves it, two eyes the host copies out next.
struct FrameImages {
  vk::Image color, depth, left, right;
  DepthImage linear;  // the stereo depth the depth buffer holds
};

class HostComfortFrameTest : public HostStereoPassTest {
 public:
  HostComfortFrameDesc desc(bool budget, std::uint32_t framesInFlight = 2, bool allowNegativeParallax = false) const {
    HostComfortFrameDesc d;
    d.stereo.width = kWidth;
    d.stereo.height = kHeight;
    d.stereo.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
    d.stereo.depthFormat = VK_FORMAT_D32_SFLOAT;
    if (budget) d.budget = comfort::disparityBudget(comfort::builtInDisplayProfile("tv55"));
    d.allowNegativeParallax = allowNegativeParallax;
    d.framesInFlight = framesInFlight;
    return d;
  }
  static HostComfortInput input(std::uint32_t slot) {
    HostComfortInput in;
    in.frameSlot = slot;
    in.parameters.maxSeparation = kHostSeparation;
    in.parameters.zeroParallaxDistance = kHostZeroParallax;
    in.crosshairDistance = kCrosshair;  // no ray cast: the crosshair stays there
    return in;
  }
  // Frame k's depths: the view's scaled by 1 + 0.1 k, so each frame's nearest differs.
  FrameImages images(int k, VkFormat eyeFormat) {
    DepthImage linear = view_.depth;
    for (float& z : linear.pixels) z *= 1.0f + 0.1f * float(k);
    const DepthUpload depth = hardwareDepth(linear, VK_FORMAT_D32_SFLOAT, frame_);
    return {uploaded(VK_FORMAT_R8G8B8A8_UNORM, colorBytes(view_.color, VK_FORMAT_R8G8B8A8_UNORM), kShaderRead),
            uploaded(VK_FORMAT_D32_SFLOAT, depth.bytes, kDepthWritten, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT),
            output(eyeFormat, kWidth, kHeight), output(eyeFormat, kWidth, kHeight), depth.expectedLinear};
  }
  stereo::StereoFrameDispatch dispatch(const FrameImages& i) const {
    stereo::StereoFrameDispatch d;
    d.color = hostImage(i.color, kShaderRead);
    d.depth = hostImage(i.depth, kDepthWritten);
    d.left = hostImage(i.left, kCopiedOut);
    d.right = hostImage(i.right, kCopiedOut);
    d.projection = frame_.projection;
    d.maxSeparation = 0.2f;  // replaced by the state's
    d.zeroParallaxDistance = 0.7f;
    return d;
  }
  stereo::StereoPair eyes(const FrameImages& i) {
    return {toImage(vk::readbackImage(*context_, i.left, kCopiedOut), kWidth, kHeight),
            toImage(vk::readbackImage(*context_, i.right, kCopiedOut), kWidth, kHeight)};
  }
  // Frame k of `frame`: update, then the reduction and the stereo frame in one submission on the host's queue.
  comfort::FrameComfortState runFrame(HostComfortFrame& frame, int k) {
    const FrameImages i = images(k, frame.stereoFrame().eyeFormat());
    const comfort::FrameComfortState state =
        frame.update(input(std::uint32_t(k) % frame.desc().framesInFlight));
    runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, dispatch(i)); });
    return state;
  }
};

// Tolerance: exact. The object hands the controller the range its reduction read, as the reference does here.
TEST_F(HostComfortFrameTest, WithTheBudgetTheParametersAreTheControllersChoiceForTheReducedDepth) {
  HostComfortFrame frame(*context_, desc(true));
  comfort::DisparityBudgetController reference(*desc(true).budget, false);
  for (int k = 0; k < 5; ++k) {
    const comfort::FrameComfortState state = runFrame(frame, k);
    if (k < 2) {  // the ring has not filled: no range yet, the host's parameters as given
      EXPECT_EQ(frame.depthRange(), nullptr) << "frame " << k;
      EXPECT_EQ(state.parameters.maxSeparation, kHostSeparation) << "frame " << k;
      continue;
    }
    ASSERT_NE(frame.depthRange(), nullptr) << "frame " << k;
    comfort::BudgetFrameInput hints;
    hints.crosshairDepth = kCrosshair;
    const std::optional<comfort::BudgetChoice> choice = reference.update(*frame.depthRange(), hints, input(0).seconds);
    ASSERT_TRUE(choice.has_value()) << "frame " << k;
    ASSERT_TRUE(state.budget.has_value()) << "frame " << k;
    EXPECT_EQ(state.parameters.maxSeparation, choice->parameters.maxSeparation) << "frame " << k;
    EXPECT_EQ(state.parameters.zeroParallaxDistance, choice->parameters.zeroParallaxDistance) << "frame " << k;
    EXPECT_NE(state.parameters.zeroParallaxDistance, kHostZeroParallax) << "frame " << k << ": the budget chose";
  }
}

// Tolerance: bit for bit. The object records the same stereo frame, only its parameters come from the state.
TEST_F(HostComfortFrameTest, TheEyesAreAPlainStereoFramesWithTheStatesParameters) {
  HostComfortFrame frame(*context_, desc(true));
  for (int k = 0; k < 2; ++k) (void)runFrame(frame, k);
  const FrameImages i = images(2, frame.stereoFrame().eyeFormat());
  const comfort::FrameComfortState state = frame.update(input(0));
  ASSERT_TRUE(state.budget.has_value());
  runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, dispatch(i)); });
  const stereo::StereoPair comforted = eyes(i);

  stereo::StereoFrame plain(*context_, desc(true).stereo);
  stereo::StereoFrameDispatch d = dispatch(i);
  d.maxSeparation = state.parameters.maxSeparation;
  d.zeroParallaxDistance = state.parameters.zeroParallaxDistance;
  d.weaponDepthOffset = state.parameters.weaponDepthOffset;
  d.weaponDepthScale = state.parameters.weaponDepthScale;
  runOnHostQueue([&](VkCommandBuffer cmd) { plain.record(cmd, d); });
  const stereo::StereoPair reference = eyes(i);
  EXPECT_EQ(comforted.left.pixels, reference.left.pixels);
  EXPECT_EQ(comforted.right.pixels, reference.right.pixels);
  EXPECT_NE(comforted.left.pixels, comforted.right.pixels);  // a real displacement, not two copies of the center
}

// Tolerance: exact; the hold sets the plane to the reduction's nearest depth as it is.
TEST_F(HostComfortFrameTest, WithoutABudgetTheHostsParametersPassThroughWithTheNoNegativeParallaxRules) {
  HostComfortFrame held(*context_, desc(false));
  HostComfortFrame allowed(*context_, desc(false, 2, true));
  for (int k = 0; k < 3; ++k) {
    const comfort::FrameComfortState h = runFrame(held, k);
    const comfort::FrameComfortState a = runFrame(allowed, k);
    EXPECT_FALSE(h.budget.has_value());
    EXPECT_EQ(h.parameters.maxSeparation, kHostSeparation) << "frame " << k;
    EXPECT_EQ(a.parameters.maxSeparation, kHostSeparation) << "frame " << k;
    EXPECT_EQ(a.parameters.zeroParallaxDistance, kHostZeroParallax) << "frame " << k;
    if (k < 2) {
      EXPECT_EQ(h.parameters.zeroParallaxDistance, kHostZeroParallax) << "frame " << k << ": nothing reduced yet";
    } else {  // the plane held at the nearest depth the reduction saw, nearer than the host's 100
      ASSERT_NE(held.depthRange(), nullptr);
      EXPECT_EQ(h.parameters.zeroParallaxDistance, held.depthRange()->nearest) << "frame " << k;
      EXPECT_TRUE(h.zeroParallaxLimited);
    }
  }
}

// Tolerance: nearest and farthest within 1e-5 relative (the GPU's division may round a linearized depth to the
// neighbouring float, as test_depth_range); frames' nearest depths differ by 10 %, far beyond it.
TEST_F(HostComfortFrameTest, WithTwoFramesInFlightFrameKReadsTheReductionOfFrameKMinus2) {
  HostComfortFrame frame(*context_, desc(true, 2));
  std::vector<stereo::DepthRange> reduced;  // the reference range of each frame's depth
  for (int k = 0; k < 5; ++k) {
    const FrameImages i = images(k, frame.stereoFrame().eyeFormat());
    reduced.push_back(stereo::reduceDepthRangeReference(i.linear));
    (void)frame.update(input(std::uint32_t(k % 2)));
    if (k >= 2) {
      ASSERT_NE(frame.depthRange(), nullptr) << "frame " << k;
      const stereo::DepthRange& expected = reduced[std::size_t(k - 2)];
      EXPECT_NEAR(frame.depthRange()->nearest, expected.nearest, 1e-5f * expected.nearest) << "frame " << k;
      EXPECT_NEAR(frame.depthRange()->farthest, expected.farthest, 1e-5f * expected.farthest) << "frame " << k;
      EXPECT_EQ(frame.depthRange()->skyPixels, expected.skyPixels) << "frame " << k;
      const stereo::DepthRange& previous = reduced[std::size_t(k - 1)];
      EXPECT_GT(std::abs(frame.depthRange()->nearest - previous.nearest), 1e-3f * previous.nearest) << "frame " << k;
    }
    runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, dispatch(i)); });
  }
}

// Tolerance: bit for bit, eyes and masks. The hybrid's two steps pass through with the state's parameters.
TEST_F(HostComfortFrameTest, TheHybridsTwoStepsAreAPlainStereoFramesWithTheStatesParameters) {
  HostComfortFrameDesc hybrid = desc(true);
  hybrid.stereo.method = stereo::StereoMethod::Hybrid;
  HostComfortFrame frame(*context_, hybrid);
  const FrameImages i = images(0, frame.stereoFrame().eyeFormat());
  // The masks wait in the layout s3d copies into; the test synchronizes them itself (stage NONE).
  const vk::ImageState copyTarget{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                  VK_ACCESS_2_TRANSFER_WRITE_BIT};
  const VkImageUsageFlags maskUsage =
      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  vk::Image leftMask = vk::createImage(*context_, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, maskUsage);
  vk::Image rightMask = vk::createImage(*context_, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, maskUsage);
  context_->submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* mask : {&leftMask, &rightMask}) vk::transition(cmd, *mask, vk::kUndefined, copyTarget);
  });
  stereo::StereoFrameDispatch d = dispatch(i);
  d.leftMask = {leftMask.image, leftMask.view, VK_FORMAT_D32_SFLOAT, copyTarget.layout};
  d.rightMask = {rightMask.image, rightMask.view, VK_FORMAT_D32_SFLOAT, copyTarget.layout};
  d.centerView = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.1f, 0.0f));
  d.centerProjection = glm::perspectiveRH_ZO(glm::radians(50.0f), float(kWidth) / float(kHeight), 0.5f, 100.0f);
  auto masks = [&] {
    return std::array{vk::readbackImage(*context_, leftMask, copyTarget), vk::readbackImage(*context_, rightMask, copyTarget)};
  };

  const comfort::FrameComfortState state = frame.update(input(0));
  // Refused before anything is recorded, so no command buffer is needed.
  EXPECT_EQ(test::errorOf<std::invalid_argument>([&] { frame.recordHybridComposite(VK_NULL_HANDLE, d); }),
            "HostComfortFrame: recordHybridComposite needs this frame's recordHybridMasks first");
  runOnHostQueue([&](VkCommandBuffer cmd) {
    (void)frame.recordHybridMasks(cmd, d);
    frame.recordHybridComposite(cmd, d);
  });
  const stereo::StereoPair comforted = eyes(i);
  const auto comfortedMasks = masks();

  stereo::StereoFrame plain(*context_, hybrid.stereo);
  d.maxSeparation = state.parameters.maxSeparation;
  d.zeroParallaxDistance = state.parameters.zeroParallaxDistance;
  d.weaponDepthOffset = state.parameters.weaponDepthOffset;
  d.weaponDepthScale = state.parameters.weaponDepthScale;
  runOnHostQueue([&](VkCommandBuffer cmd) {
    (void)plain.recordHybridMasks(cmd, d);
    plain.recordHybridComposite(cmd, d);
  });
  EXPECT_EQ(comforted.left.pixels, eyes(i).left.pixels);
  EXPECT_EQ(comforted.right.pixels, eyes(i).right.pixels);
  EXPECT_EQ(comfortedMasks, masks());
}

TEST_F(HostComfortFrameTest, AFrameSlotOutOfRangeAndRecordBeforeUpdateAreRefusedNamingTheField) {
  HostComfortFrame frame(*context_, desc(false, 2));
  EXPECT_EQ(test::errorOf<std::invalid_argument>([&] { (void)frame.update(input(2)); }), "HostComfortInput.frameSlot 2 is outside [0, 2)");
  const FrameImages i = images(0, frame.stereoFrame().eyeFormat());
  const std::string early = test::errorOf<std::invalid_argument>([&] { frame.record(VK_NULL_HANDLE, dispatch(i)); });  // before any command
  EXPECT_NE(early.find("record needs this frame's update"), std::string::npos) << early;
  HostComfortInput slow = input(0);
  slow.seconds = 0.0f;
  const std::string seconds = test::errorOf<std::invalid_argument>([&] { (void)frame.update(slow); });
  EXPECT_NE(seconds.find("HostComfortInput.seconds"), std::string::npos) << seconds;
  HostComfortFrameDesc none = desc(false, 0);
  const std::string ring = test::errorOf<std::invalid_argument>([&] { HostComfortFrame refused(*context_, none); });
  EXPECT_NE(ring.find("HostComfortFrameDesc.framesInFlight is 0"), std::string::npos) << ring;
}

}  // namespace
}  // namespace s3d::test
