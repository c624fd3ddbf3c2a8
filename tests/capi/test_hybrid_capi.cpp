// The hybrid for a host's renderer through the C API (S3D_METHOD_HYBRID): the search's eyes, the masks written as
// depth (far where the host re-draws) equal to the built-in hybrid's, the eye cameras of the center camera, and the
// calls and fields that are refused, named as the C caller spells them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "capi_test_context.h"
#include "s3d/s3d.h"
#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_pass.h"
#include "s3d/stereo/stereo_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::test {
namespace {

constexpr std::uint32_t kWidth = 64, kHeight = 48;
constexpr float kSeparation = 0.05f, kZeroParallax = 2.0f, kBudget = 0.2f;
// Every image stays in GENERAL; each submission is waited for, and the barriers name every earlier access.
constexpr vk::ImageState kGeneral{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};
// The masks wait in the layout s3d copies into; the host (the test) synchronizes them itself (stage 0).
constexpr vk::ImageState kCopyTarget{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};

s3d_host_image copyTarget(const vk::Image& image) {
  return {image.image, image.view, image.format, kCopyTarget.layout, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, 0};
}

class CApiHybrid : public VulkanTest {
 protected:
  void SetUp() override {
    VulkanTest::SetUp();
    view_ = makeBlockView(kWidth, kHeight, 5, 0.6f, 7, 5, false);
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const auto image = [&](VkFormat format, VkImageUsageFlags flags) {
      return vk::createImage(context(), format, kWidth, kHeight, flags);
    };
    color_ = image(VK_FORMAT_R8G8B8A8_UNORM, usage);
    depth_ = image(VK_FORMAT_R32_SFLOAT, usage);
    left_ = image(VK_FORMAT_R8G8B8A8_UNORM, usage);
    right_ = image(VK_FORMAT_R8G8B8A8_UNORM, usage);
    const VkImageUsageFlags maskUsage =
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    leftMask_ = image(VK_FORMAT_D32_SFLOAT, maskUsage);
    rightMask_ = image(VK_FORMAT_D32_SFLOAT, maskUsage);
    vk::uploadImage(context(), color_, std::as_bytes(std::span(view_.color.pixels)), kGeneral);
    vk::uploadImage(context(), depth_, std::as_bytes(std::span(view_.depth.pixels)), kGeneral);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* i : {&left_, &right_}) vk::transition(cmd, *i, vk::kUndefined, kGeneral);
      for (const vk::Image* i : {&leftMask_, &rightMask_}) vk::transition(cmd, *i, vk::kUndefined, kCopyTarget);
    });
    s3d_default_stereo_frame_desc(&desc_);
    desc_.width = kWidth;
    desc_.height = kHeight;
    desc_.color_format = VK_FORMAT_R8G8B8A8_UNORM;
    desc_.depth_format = VK_FORMAT_R32_SFLOAT;
    desc_.method = S3D_METHOD_HYBRID;
    desc_.hybrid_budget = kBudget;
    s3d_default_stereo_frame_dispatch(&dispatch_);
    dispatch_.color = cImage(color_);
    dispatch_.depth = cImage(depth_);
    dispatch_.left = cImage(left_);
    dispatch_.right = cImage(right_);
    dispatch_.left_mask = copyTarget(leftMask_);
    dispatch_.right_mask = copyTarget(rightMask_);
    dispatch_.max_separation = kSeparation;
    dispatch_.zero_parallax_distance = kZeroParallax;
    std::memcpy(dispatch_.center_view, glm::value_ptr(centerView()), sizeof dispatch_.center_view);
    std::memcpy(dispatch_.center_projection, glm::value_ptr(centerProjection()), sizeof dispatch_.center_projection);
  }

  static glm::mat4 centerView() { return glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.1f, 0.0f)); }
  static glm::mat4 centerProjection() {
    glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(50.0f), float(kWidth) / float(kHeight), 0.1f, 50.0f);
    p[1][1] = -p[1][1];
    return p;
  }
  stereo::StereoParameters parameters() const {
    stereo::StereoParameters p;
    p.method = stereo::StereoMethod::Hybrid;
    p.hybridBase = stereo::StereoMethod::Search;
    p.hybridBudget = kBudget;
    p.maxSeparation = kSeparation;
    p.zeroParallaxDistance = kZeroParallax;
    return p;
  }
  std::vector<std::uint8_t> readMask(const vk::Image& mask) {
    const std::vector<std::byte> bytes = vk::readbackImage(context(), mask, kCopyTarget);
    std::vector<float> depth(bytes.size() / sizeof(float));
    std::memcpy(depth.data(), bytes.data(), bytes.size());
    std::vector<std::uint8_t> result;
    for (float d : depth) {
      EXPECT_TRUE(d == 0.0f || d == 1.0f) << d;  // the near or the far value, nothing between
      result.push_back(d == 1.0f ? 1 : 0);
    }
    return result;
  }
  // The masks the host received are the built-in classification's for `p`, and not empty; returns the left one.
  std::vector<std::uint8_t> expectBuiltInMasks(const stereo::StereoParameters& p) {
    const stereo::HybridGpuResult builtIn =
        stereo::classifyHybridOnGpu(context(), view_.depth, stereo::makeHybridConstants(p, kWidth, kHeight));
    const std::vector<std::uint8_t> left = readMask(leftMask_), right = readMask(rightMask_);
    EXPECT_GT(std::count(left.begin(), left.end(), 1), 0);
    EXPECT_EQ(left, builtIn.leftMask);
    EXPECT_EQ(right, builtIn.rightMask);
    return left;
  }
  ImageRGBA8 readEye(const vk::Image& eye) {
    const std::vector<std::byte> bytes = vk::readbackImage(context(), eye, kGeneral);
    ImageRGBA8 result(kWidth, kHeight);
    std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
    return result;
  }

  SyntheticView view_;
  vk::Image color_, depth_, left_, right_, leftMask_, rightMask_;
  s3d_stereo_frame_desc desc_{};
  s3d_stereo_frame_dispatch dispatch_{};
};

TEST_F(CApiHybrid, MasksCamerasAndEyesOfOneFrame) {
  CContext c(context());
  s3d_stereo_frame frame = nullptr;
  ASSERT_EQ(s3d_stereo_frame_create(c.get(), &desc_, &frame), S3D_SUCCESS) << s3d_last_error();
  s3d_eye_cameras cameras{};
  s3d_result result = S3D_ERROR_UNKNOWN;
  context().submitAndWait([&](VkCommandBuffer cmd) { result = s3d_stereo_frame_record_hybrid_masks(frame, cmd, &dispatch_, &cameras); });
  ASSERT_EQ(result, S3D_SUCCESS) << s3d_last_error();
  // No overlay: nothing follows the host's draw, and the call succeeds.
  context().submitAndWait([&](VkCommandBuffer cmd) { result = s3d_stereo_frame_record_hybrid_composite(frame, cmd, &dispatch_); });
  EXPECT_EQ(result, S3D_SUCCESS) << s3d_last_error();
  s3d_stereo_frame_destroy(frame);
  expectBuiltInMasks(parameters());

  // The eyes are the search's (1 level: the reference's rounding, as test_stereo_pass).
  stereo::StereoParameters search = parameters();
  search.method = stereo::StereoMethod::Search;
  const stereo::StereoPair expected = stereo::synthesizeStereoReference(
      view_.color, view_.depth, stereo::makeStereoConstants(search, kWidth, kHeight));
  EXPECT_LE(largestChannelDifference(readEye(left_), expected.left), 1);
  EXPECT_LE(largestChannelDifference(readEye(right_), expected.right), 1);

  // The cameras, column-major, left then right: the off-axis eyes of the center camera.
  for (stereo::Eye eye : {stereo::Eye::Left, stereo::Eye::Right}) {
    const stereo::EyeCamera want =
        stereo::offAxisEyeCamera(centerView(), centerProjection(), eye, kSeparation, kZeroParallax);
    const bool isLeft = eye == stereo::Eye::Left;
    EXPECT_EQ(glm::make_mat4(isLeft ? cameras.left_view : cameras.right_view), want.view);
    EXPECT_EQ(glm::make_mat4(isLeft ? cameras.left_projection : cameras.right_projection), want.projection);
  }
}

// The description's cell and score floor reach the masks: 2x2 cells and a floor of half a pixel give the built-in
// classification's masks for those parameters, and other masks than the defaults (cells of one pixel below 1280
// columns, floor 0.15).
TEST_F(CApiHybrid, TheCellAndTheScoreFloorReachTheMasks) {
  CContext c(context());
  s3d_stereo_frame frame = nullptr;
  desc_.hybrid_cell = 2;
  desc_.hybrid_score_floor = 0.5f;
  ASSERT_EQ(s3d_stereo_frame_create(c.get(), &desc_, &frame), S3D_SUCCESS) << s3d_last_error();
  s3d_eye_cameras cameras{};
  s3d_result result = S3D_ERROR_UNKNOWN;
  context().submitAndWait([&](VkCommandBuffer cmd) { result = s3d_stereo_frame_record_hybrid_masks(frame, cmd, &dispatch_, &cameras); });
  ASSERT_EQ(result, S3D_SUCCESS) << s3d_last_error();
  s3d_stereo_frame_destroy(frame);

  stereo::StereoParameters cells = parameters();
  cells.hybridCell = 2;
  cells.hybridScoreFloor = 0.5f;
  const std::vector<std::uint8_t> left = expectBuiltInMasks(cells);
  const stereo::HybridGpuResult defaults =
      stereo::classifyHybridOnGpu(context(), view_.depth, stereo::makeHybridConstants(parameters(), kWidth, kHeight));
  EXPECT_NE(left, defaults.leftMask);
}

TEST_F(CApiHybrid, RefusesWhatTheHybridCannotTakeNamingTheField) {
  CContext c(context());
  s3d_stereo_frame frame = nullptr;
  s3d_stereo_frame_desc bad = desc_;
  bad.output = S3D_OUTPUT_SIDE_BY_SIDE_HALF;
  EXPECT_EQ(s3d_stereo_frame_create(c.get(), &bad, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("s3d_stereo_frame_desc.output"), std::string::npos) << s3d_last_error();
  bad = desc_;
  bad.hybrid_budget = 1.5f;
  EXPECT_EQ(s3d_stereo_frame_create(c.get(), &bad, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("s3d_stereo_frame_desc.hybrid_budget"), std::string::npos) << s3d_last_error();
  bad = desc_;
  bad.hybrid_cell = 3;
  EXPECT_EQ(s3d_stereo_frame_create(c.get(), &bad, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("s3d_stereo_frame_desc.hybrid_cell 3"), std::string::npos) << s3d_last_error();
  bad = desc_;
  bad.hybrid_score_floor = -1.0f;
  EXPECT_EQ(s3d_stereo_frame_create(c.get(), &bad, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("s3d_stereo_frame_desc.hybrid_score_floor"), std::string::npos)
      << s3d_last_error();

  ASSERT_EQ(s3d_stereo_frame_create(c.get(), &desc_, &frame), S3D_SUCCESS) << s3d_last_error();
  s3d_eye_cameras cameras{};
  s3d_stereo_frame_dispatch d = dispatch_;
  d.right_mask = {};
  // Refused before anything is recorded: the command buffer stays empty.
  context().submitAndWait([&](VkCommandBuffer cmd) {
    EXPECT_EQ(s3d_stereo_frame_record(frame, cmd, &dispatch_), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("s3d_stereo_frame_record_hybrid_masks"), std::string::npos);
    EXPECT_EQ(s3d_stereo_frame_record_hybrid_masks(frame, cmd, &d, &cameras), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("dispatch.right_mask"), std::string::npos) << s3d_last_error();
    d.right_mask = cImage(left_);
    EXPECT_EQ(s3d_stereo_frame_record_hybrid_masks(frame, cmd, &d, &cameras), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("dispatch.right_mask.format"), std::string::npos) << s3d_last_error();
    EXPECT_EQ(s3d_stereo_frame_record_hybrid_masks(frame, cmd, &dispatch_, nullptr), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("cameras"), std::string::npos) << s3d_last_error();
  });
  s3d_stereo_frame_destroy(frame);

  s3d_stereo_frame_desc search = desc_;
  search.method = S3D_METHOD_SEARCH;
  ASSERT_EQ(s3d_stereo_frame_create(c.get(), &search, &frame), S3D_SUCCESS) << s3d_last_error();
  context().submitAndWait([&](VkCommandBuffer cmd) {
    EXPECT_EQ(s3d_stereo_frame_record_hybrid_masks(frame, cmd, &dispatch_, &cameras), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("S3D_METHOD_HYBRID"), std::string::npos) << s3d_last_error();
  });
  s3d_stereo_frame_destroy(frame);
}

}  // namespace
}  // namespace s3d::test
