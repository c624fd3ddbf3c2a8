// The disparity budget's depth range through the C API (s3d_depth_reduction): a host's D32 depth buffer reduced as
// it is gives the range of the stereo depth it holds, and the calls refuse what is missing, named as C spells it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "capi_test_context.h"
#include "s3d/gpu/linear_depth.h"
#include "s3d/s3d.h"
#include "s3d/stereo/depth_range.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "vulkan_test.h"

namespace s3d::test {
namespace {

constexpr std::uint32_t kWidth = 64, kHeight = 48;
constexpr float kNear = 0.1f, kFar = 100.0f;

class CApiDepthReduction : public VulkanTest {};

// Tolerance: nearest and farthest within 1e-5 relative (the GPU's division may round a linearized depth to the
// neighbouring float); the sky count exactly.
TEST_F(CApiDepthReduction, AHostsD32DepthGivesTheRangeOfItsLinearDepth) {
  // Rows of depth from 1 m to 48 m, the last eight rows sky (device depth 1).
  s3d_projection projection{};
  projection.near_plane = kNear;
  projection.far_plane = kFar;
  stereo::HostProjection cpp;  // the C projection's: no first-person layer, its planes unset
  cpp.nearPlane = kNear;
  cpp.farPlane = kFar;
  cpp.firstPersonDepthRange = 0.0f;
  cpp.firstPersonNear = cpp.firstPersonFar = 0.0f;
  const gpu::LinearDepthParams params = stereo::linearDepthParams(cpp, 1.0f, 1.0f);
  std::vector<float> device(std::size_t(kWidth) * kHeight);
  DepthImage expected(kWidth, kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const float linear = 1.0f + float(y);
      const float d = y >= kHeight - 8 ? 1.0f : kFar / (kFar - kNear) - kNear * kFar / ((kFar - kNear) * linear);
      device[y * kWidth + x] = d;
      expected.pixels[y * kWidth + x] = gpu::stereoDepthFromDevice(params, d);
    }
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::Image depth = vk::createImage(context(), VK_FORMAT_D32_SFLOAT, kWidth, kHeight, usage);
  const vk::ImageState readable{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};
  vk::uploadImage(context(), depth, std::as_bytes(std::span(device)), readable);
  const CContext c(context());
  s3d_depth_reduction reduction = nullptr;
  ASSERT_EQ(s3d_depth_reduction_create(c.get(), &reduction), S3D_SUCCESS) << s3d_last_error();
  const s3d_host_image image{depth.image, depth.view, depth.format, readable.layout, VK_PIPELINE_STAGE_2_NONE,
                             VK_ACCESS_2_NONE, 0};
  s3d_result recorded = S3D_SUCCESS;
  context().submitAndWait([&](VkCommandBuffer cmd) {
    recorded = s3d_depth_reduction_record(reduction, cmd, &image, kWidth, kHeight, &projection, 1.0f, 1.0f);
  });
  ASSERT_EQ(recorded, S3D_SUCCESS) << s3d_last_error();
  s3d_depth_range range{};
  ASSERT_EQ(s3d_depth_reduction_result(reduction, &range), S3D_SUCCESS) << s3d_last_error();
  const stereo::DepthRange reference = stereo::reduceDepthRangeReference(expected);
  EXPECT_NEAR(range.nearest, reference.nearest, 1e-5f * reference.nearest);
  EXPECT_NEAR(range.farthest, reference.farthest, 1e-5f * reference.farthest);
  EXPECT_EQ(range.sky_pixels, std::uint64_t(kWidth) * 8);
  ASSERT_NE(range.histogram, nullptr);
  EXPECT_EQ(range.histogram_bins, std::uint32_t(reference.bins.size()));
  s3d_depth_reduction_destroy(reduction);
}

TEST_F(CApiDepthReduction, MissingArgumentsAreRefusedByTheirCNames) {
  const CContext c(context());
  EXPECT_EQ(s3d_depth_reduction_create(nullptr, nullptr), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("context"), std::string::npos) << s3d_last_error();
  s3d_depth_reduction reduction = nullptr;
  ASSERT_EQ(s3d_depth_reduction_create(c.get(), &reduction), S3D_SUCCESS) << s3d_last_error();
  s3d_depth_range range{};
  EXPECT_EQ(s3d_depth_reduction_result(reduction, nullptr), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("out"), std::string::npos) << s3d_last_error();
  EXPECT_EQ(s3d_depth_reduction_result(nullptr, &range), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("reduction"), std::string::npos) << s3d_last_error();
  s3d_depth_reduction_destroy(reduction);
}

}  // namespace
}  // namespace s3d::test
