// The host comfort frame through the C API (s3d_host_comfort_frame_*): the same frames give the C++ object's
// state and eyes, and missing arguments and calls out of order are refused, named as the C caller spells them.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "capi_test_context.h"
#include "s3d/comfort/host_comfort_frame.h"
#include "s3d/s3d.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::test {
namespace {

constexpr std::uint32_t kWidth = 48, kHeight = 32, kFramesInFlight = 2;
constexpr float kSeparation = 0.03f, kZeroParallax = 100.0f, kSeconds = 1.0f / 60.0f;
constexpr s3d_display kDisplay{1.2f, 2.5f, 0.065f, 0.0f};  // a 1.2 m wide screen seen from 2.5 m
// Every image stays in GENERAL; each submission is waited for, and the barriers name every earlier access.
constexpr vk::ImageState kGeneral{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};

class CApiHostComfortFrame : public VulkanTest {
 protected:
  void SetUp() override {
    VulkanTest::SetUp();
    view_ = makeBlockView(kWidth, kHeight, 9, 0.6f, 7, 5, false);
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    for (vk::Image* image : {&color_, &left_, &right_})
      *image = vk::createImage(context(), VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, usage);
    depth_ = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth, kHeight, usage);
    vk::uploadImage(context(), color_, std::as_bytes(std::span(view_.color.pixels)), kGeneral);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* i : {&left_, &right_}) vk::transition(cmd, *i, vk::kUndefined, kGeneral);
    });
  }
  // Frame k's linear depth: the view's scaled by 1 + 0.1 k, so the reductions differ per frame.
  void uploadDepth(int k) {
    DepthImage depth = view_.depth;
    for (float& z : depth.pixels) z *= 1.0f + 0.1f * float(k);
    vk::uploadImage(context(), depth_, std::as_bytes(std::span(depth.pixels)), kGeneral);
  }
  s3d_host_comfort_frame_desc cDesc() const {
    s3d_host_comfort_frame_desc desc{};
    s3d_default_stereo_frame_desc(&desc.stereo);
    desc.stereo.width = kWidth;
    desc.stereo.height = kHeight;
    desc.stereo.color_format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.stereo.depth_format = VK_FORMAT_R32_SFLOAT;
    desc.display = &kDisplay;
    desc.frames_in_flight = kFramesInFlight;
    return desc;
  }
  comfort::HostComfortFrameDesc cppDesc() const {
    comfort::HostComfortFrameDesc desc;
    desc.stereo.width = kWidth;
    desc.stereo.height = kHeight;
    desc.stereo.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
    desc.stereo.depthFormat = VK_FORMAT_R32_SFLOAT;
    comfort::DisplayProfile display;
    display.screenWidthMeters = kDisplay.screen_width_meters;
    display.viewingDistanceMeters = kDisplay.viewing_distance_meters;
    display.interocularMeters = kDisplay.interocular_meters;
    desc.budget = comfort::disparityBudget(display);
    desc.framesInFlight = kFramesInFlight;
    return desc;
  }
  static s3d_host_comfort_input cInput(std::uint32_t slot) {
    s3d_host_comfort_input input{};
    input.frame_slot = slot;
    input.frame.camera_aim[2] = -1.0f;
    input.frame.camera_near = 0.1f;
    s3d_default_stereo_parameters(&input.frame.parameters);
    input.frame.parameters.max_separation = kSeparation;
    input.frame.parameters.zero_parallax_distance = kZeroParallax;
    input.frame.width = kWidth;
    input.frame.crosshair_distance = 10.0f;
    input.frame.crosshair_margin = 0.25f;
    input.frame_seconds = kSeconds;
    return input;
  }
  static comfort::HostComfortInput cppInput(std::uint32_t slot) {
    comfort::HostComfortInput input;
    input.frameSlot = slot;
    input.camera = {glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.1f};
    input.parameters.maxSeparation = kSeparation;
    input.parameters.zeroParallaxDistance = kZeroParallax;
    input.crosshairDistance = 10.0f;
    input.crosshairMargin = 0.25f;
    input.seconds = kSeconds;
    return input;
  }
  s3d_stereo_frame_dispatch cDispatch() const {
    s3d_stereo_frame_dispatch d;
    s3d_default_stereo_frame_dispatch(&d);
    d.color = cImage(color_);
    d.depth = cImage(depth_);
    d.left = cImage(left_);
    d.right = cImage(right_);
    return d;
  }
  static stereo::HostImage cppImage(const s3d_host_image& i) {
    return {i.image, i.view, i.format, i.layout, i.stage, i.access, i.layer};
  }
  stereo::StereoFrameDispatch cppDispatch() const {
    const s3d_stereo_frame_dispatch c = cDispatch();
    stereo::StereoFrameDispatch d;
    d.color = cppImage(c.color);
    d.depth = cppImage(c.depth);
    d.left = cppImage(c.left);
    d.right = cppImage(c.right);
    return d;
  }
  stereo::StereoPair readEyes() {
    auto read = [&](const vk::Image& eye) {
      const std::vector<std::byte> bytes = vk::readbackImage(context(), eye, kGeneral);
      ImageRGBA8 image(kWidth, kHeight);
      std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
      return image;
    };
    return {read(left_), read(right_)};
  }

  SyntheticView view_;
  vk::Image color_, depth_, left_, right_;
};

// Tolerance: exact state and bit-for-bit eyes: both run the same object on the same images.
TEST_F(CApiHostComfortFrame, CreateUpdateRecordGivesTheCppObjectsStateAndEyes) {
  const CContext c(context());
  const s3d_host_comfort_frame_desc desc = cDesc();
  s3d_host_comfort_frame frame = nullptr;
  ASSERT_EQ(s3d_host_comfort_frame_create(c.get(), &desc, &frame), S3D_SUCCESS) << s3d_last_error();
  comfort::HostComfortFrame cpp(context(), cppDesc());
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t slot = std::uint32_t(k) % kFramesInFlight;
    uploadDepth(k);
    const s3d_host_comfort_input input = cInput(slot);
    s3d_frame_comfort_state state{};
    s3d_budget_choice choice{};
    ASSERT_EQ(s3d_host_comfort_frame_update(frame, &input, &state, nullptr, &choice), S3D_SUCCESS) << s3d_last_error();
    const s3d_stereo_frame_dispatch dispatch = cDispatch();
    s3d_result recorded = S3D_SUCCESS;
    context().submitAndWait([&](VkCommandBuffer cmd) { recorded = s3d_host_comfort_frame_record(frame, cmd, &dispatch); });
    ASSERT_EQ(recorded, S3D_SUCCESS) << s3d_last_error();
    const stereo::StereoPair cEyes = readEyes();

    const comfort::FrameComfortState& expected = cpp.update(cppInput(slot));
    context().submitAndWait([&](VkCommandBuffer cmd) { cpp.record(cmd, cppDispatch()); });
    EXPECT_EQ(state.parameters.max_separation, expected.parameters.maxSeparation) << "frame " << k;
    EXPECT_EQ(state.parameters.zero_parallax_distance, expected.parameters.zeroParallaxDistance) << "frame " << k;
    EXPECT_EQ(choice.chosen, k >= int(kFramesInFlight) ? 1 : 0) << "frame " << k << ": the budget once the ring filled";
    EXPECT_EQ(choice.chosen, expected.budget.has_value() ? 1 : 0) << "frame " << k;
    const stereo::StereoPair cppEyes = readEyes();
    EXPECT_EQ(cEyes.left.pixels, cppEyes.left.pixels) << "frame " << k;
    EXPECT_EQ(cEyes.right.pixels, cppEyes.right.pixels) << "frame " << k;
  }
  s3d_host_comfort_frame_destroy(frame);
}

TEST_F(CApiHostComfortFrame, MissingArgumentsAndCallsOutOfOrderAreRefusedByTheirCNames) {
  const CContext c(context());
  const s3d_host_comfort_frame_desc desc = cDesc();
  auto error = [] { return std::string(s3d_last_error()); };
  s3d_host_comfort_frame frame = nullptr;
  EXPECT_EQ(s3d_host_comfort_frame_create(nullptr, &desc, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(error().find("context"), std::string::npos) << error();
  EXPECT_EQ(s3d_host_comfort_frame_create(c.get(), nullptr, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(error().find("desc"), std::string::npos) << error();
  s3d_host_comfort_frame_desc noRing = desc;
  noRing.frames_in_flight = 0;
  EXPECT_EQ(s3d_host_comfort_frame_create(c.get(), &noRing, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(error().find("s3d_host_comfort_frame_desc.frames_in_flight"), std::string::npos) << error();
  ASSERT_EQ(s3d_host_comfort_frame_create(c.get(), &desc, &frame), S3D_SUCCESS) << s3d_last_error();

  s3d_frame_comfort_state state{};
  const s3d_host_comfort_input input = cInput(0);
  EXPECT_EQ(s3d_host_comfort_frame_update(nullptr, &input, &state, nullptr, nullptr), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(error().find("frame"), std::string::npos) << error();
  EXPECT_EQ(s3d_host_comfort_frame_update(frame, nullptr, &state, nullptr, nullptr), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(error().find("input"), std::string::npos) << error();
  EXPECT_EQ(s3d_host_comfort_frame_update(frame, &input, nullptr, nullptr, nullptr), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(error().find("out"), std::string::npos) << error();
  const s3d_host_comfort_input outside = cInput(kFramesInFlight);
  EXPECT_EQ(s3d_host_comfort_frame_update(frame, &outside, &state, nullptr, nullptr), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error(), "s3d_host_comfort_input.frame_slot 2 is outside [0, 2)");

  const s3d_stereo_frame_dispatch dispatch = cDispatch();
  context().submitAndWait([&](VkCommandBuffer cmd) {
    EXPECT_EQ(s3d_host_comfort_frame_record(frame, cmd, &dispatch), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(error(), "s3d_host_comfort_frame_record needs this frame's s3d_host_comfort_frame_update first");
    EXPECT_EQ(s3d_host_comfort_frame_record(nullptr, cmd, &dispatch), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(error().find("frame"), std::string::npos) << error();
    EXPECT_EQ(s3d_host_comfort_frame_record(frame, cmd, nullptr), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(error().find("dispatch"), std::string::npos) << error();
  });
  s3d_host_comfort_frame_destroy(frame);
}

}  // namespace
}  // namespace s3d::test
