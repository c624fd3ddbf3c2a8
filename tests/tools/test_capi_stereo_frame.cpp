// The C API's stereo frame, for every displacement method: a C host's eyes are `s3d render`'s eyes for the same
// rendered frame, and with eye views they are the views job's synthesis of the same center image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "capi_test_context.h"
#include "s3d/stereo/eye_views_reference.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/s3d.h"
#include "s3d/stereo/eye_views.h"
#include "s3d/stereo/synthesis.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::test {
namespace {

using stereo::StereoMethod;

struct Method {
  s3d_method c;
  StereoMethod cpp;
};
const Method kMethods[] = {{S3D_METHOD_SEED, StereoMethod::Seed},
                           {S3D_METHOD_SEARCH, StereoMethod::Search},
                           {S3D_METHOD_ITERATIVE, StereoMethod::Iterative},
                           {S3D_METHOD_FORWARD, StereoMethod::Forward}};
std::string methodLabel(const ::testing::TestParamInfo<Method>& info) { return stereo::methodName(info.param.cpp); }

constexpr std::uint32_t kWidth = 160, kHeight = 90;

// A screen's off-axis pair (samples/views/tv-pair.json's geometry) at kWidth x kHeight: tangents +-0.5 shifted by
// 0.0325 / 2 towards the other eye, converging at 2 m.
stereo::ViewConfiguration tvPair() {
  const double shift = 0.0325 / 2.0, up = std::atan(0.28125);
  stereo::ViewConfiguration views;
  views.eyes[0] = {-0.0325, std::atan(-0.5 + shift), std::atan(0.5 + shift), up, -up, kWidth, kHeight};
  views.eyes[1] = {0.0325, std::atan(-0.5 - shift), std::atan(0.5 - shift), up, -up, kWidth, kHeight};
  return views;
}
s3d_eye_views cViews(const stereo::ViewConfiguration& views) {
  auto eye = [](const stereo::EyeView& e) {
    return s3d_eye_view{float(e.positionX), float(e.angleLeft), float(e.angleRight), float(e.angleUp),
                        float(e.angleDown)};
  };
  return {eye(views.eyes[0]), eye(views.eyes[1]), float(views.worldScale)};
}

// A host's RGBA8 colour and R32F linear depth, its two eyes, and a C stereo frame of `method` over them.
class CApiStereoFrame : public VulkanTest, public ::testing::WithParamInterface<Method> {
 protected:
  void SetUp() override {
    VulkanTest::SetUp();
    c_.emplace(context());
    context().submitAndWait([&](VkCommandBuffer cmd) {
      for (const vk::Image* eye : {&left_, &right_}) vk::transition(cmd, *eye, vk::kUndefined, vk::kComputeWrite);
    });
  }
  void TearDown() override {
    c_.reset();
    VulkanTest::TearDown();
  }
  vk::Image image(VkFormat format, VkImageUsageFlags usage) {
    return vk::createImage(context(), format, kWidth, kHeight,
                           usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  }
  // The eyes of one s3d_stereo_frame_record on the host's center colour and depth.
  stereo::StereoPair cEyes(const ImageRGBA8& center, const DepthImage& depth, s3d_stereo_frame_dispatch dispatch) {
    vk::uploadImage(context(), color_, std::as_bytes(std::span(center.pixels)), vk::kComputeRead);
    vk::uploadImage(context(), depth_, std::as_bytes(std::span(depth.pixels)), vk::kComputeRead);
    s3d_stereo_frame_desc desc;
    s3d_default_stereo_frame_desc(&desc);
    desc.width = kWidth;
    desc.height = kHeight;
    desc.color_format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.depth_format = VK_FORMAT_R32_SFLOAT;
    desc.method = GetParam().c;
    s3d_stereo_frame frame = nullptr;
    EXPECT_EQ(s3d_stereo_frame_create(c_->get(), &desc, &frame), S3D_SUCCESS) << s3d_last_error();
    dispatch.color = cImage(color_);
    dispatch.depth = cImage(depth_);
    dispatch.left = cImage(left_);
    dispatch.right = cImage(right_);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      EXPECT_EQ(s3d_stereo_frame_record(frame, cmd, &dispatch), S3D_SUCCESS) << s3d_last_error();
    });
    s3d_stereo_frame_destroy(frame);
    return {read(left_), read(right_)};
  }
  ImageRGBA8 read(const vk::Image& eye) {
    ImageRGBA8 result(kWidth, kHeight);
    const std::vector<std::byte> bytes = vk::readbackImage(context(), eye, vk::kComputeWrite);
    std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
    return result;
  }

  std::optional<CContext> c_;
  const vk::Image color_ = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT);
  const vk::Image depth_ = image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT);
  const vk::Image left_ = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
  const vk::Image right_ = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
};

TEST_P(CApiStereoFrame, AHostsEyesAreTheRenderJobsEyes) {
  // The same rendered frame through s3d_stereo_frame_record and through the synthesis `s3d render` runs
  // (stereo::synthesizeTimed on the renderer's own images).
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  renderer::DeferredRenderer deferred(context(), kWidth, kHeight);
  deferred.setScene(scene);
  stereo::StereoParameters parameters;
  parameters.method = GetParam().cpp;
  (void)deferred.render(renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight),
                                                     {parameters.weaponDepthOffset, parameters.weaponDepthScale}));
  const stereo::SynthesisResult rendered =
      stereo::synthesizeTimed(context(), deferred.displayColor(), deferred.linearDepth(), parameters);
  s3d_stereo_frame_dispatch dispatch;
  s3d_default_stereo_frame_dispatch(&dispatch);
  dispatch.max_separation = parameters.maxSeparation;
  dispatch.zero_parallax_distance = parameters.zeroParallaxDistance;
  const stereo::StereoPair host = cEyes(deferred.readDisplayColor(), deferred.readLinearDepth(), dispatch);
  EXPECT_LE(largestChannelDifference(host.left, rendered.eyes.left), 1);  // within one level
  EXPECT_LE(largestChannelDifference(host.right, rendered.eyes.right), 1);
}

TEST_P(CApiStereoFrame, WithEyeViewsTheEyesAreTheViewsJobsSynthesisOfTheSameCenter) {
  // The TV pair's center (random texels over blocks of constant depth from 1 m to 50 m and sky), each eye through
  // s3d_stereo_frame_record with the views and through the CPU synthesis (stereo::synthesizeEyeForView) on
  // the shared center view the stereo frame needs.
  const SyntheticView view = makeBlockView(kWidth, kHeight, 5, 1.0f, 24, 9, false);
  const ImageRGBA8& color = view.color;
  const DepthImage& depth = view.depth;
  const stereo::ViewConfiguration views = tvPair();
  const stereo::CenterView center = stereo::sharedCenterView(views);
  const s3d_eye_views eyeViews = cViews(views);
  s3d_stereo_frame_dispatch dispatch;
  s3d_default_stereo_frame_dispatch(&dispatch);
  dispatch.eye_views = &eyeViews;
  const stereo::StereoPair host = cEyes(color, depth, dispatch);
  // Columns inside the crop (the eyes' outer m W columns are black) whose row is one depth as far as the largest
  // parallax reaches, and a pixel more: there every method shows the texels the views' mapping lands on; where
  // depths meet each resolves occlusion its own way.
  const float largest = stereo::eyeViewsParallax(views).maxSeparation * float(kWidth);
  const int reach = 1 + int(std::ceil(largest));
  auto oneDepthAround = [&](int x, int y) {
    for (int dx = -reach; dx <= reach; ++dx)
      if (depth.at(std::uint32_t(x + dx), std::uint32_t(y))[0] != depth.at(std::uint32_t(x), std::uint32_t(y))[0])
        return false;
    return true;
  };
  for (int eye = 0; eye < 2; ++eye) {
    const ImageRGBA8 expected = stereo::synthesizeEyeForView(color, depth, views, center, eye);
    const ImageRGBA8& got = eye == 0 ? host.left : host.right;
    int largestDifference = 0;
    std::size_t compared = 0;
    for (int y = 0; y < int(kHeight); ++y)
      for (int x = reach; x < int(kWidth) - reach; ++x) {
        if (!oneDepthAround(x, y)) continue;
        ++compared;
        for (int c = 0; c < 3; ++c)
          largestDifference = std::max(largestDifference, std::abs(int(got.at(std::uint32_t(x), std::uint32_t(y))[c]) -
                                                                   int(expected.at(std::uint32_t(x), std::uint32_t(y))[c])));
      }
    EXPECT_GT(compared, std::size_t(kWidth) * kHeight / 2);  // most of the eye
    EXPECT_LE(largestDifference, 1) << "eye " << eye;  // one level: both filter the same two texels, rounded apart
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, CApiStereoFrame, ::testing::ValuesIn(kMethods), methodLabel);

}  // namespace
}  // namespace s3d::test
