// The host's stereo frame (stereo_frame.h): every displacement method from the host's colour and depth buffer, each
// held to its C++ reference; the eyes as two images or as the two layers of one array image; bad descriptions and
// dispatches refused naming the field. Synchronization validation on (TestHost).
#include <gtest/gtest.h>

#include "array_image.h"
#include "host_pass_fixture.h"
#include "io_test_support.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/s3d.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/stereo_frame.h"
#include "s3d/stereo/synthesis.h"
#include "s3d/vk/check.h"
#include "vulkan_test.h"

namespace s3d::test {
namespace {

using stereo::StereoMethod;

class StereoFrameTest : public HostStereoPassTest {
 public:
  stereo::StereoFrameDesc desc(StereoMethod method) const {
    stereo::StereoFrameDesc d;
    d.width = kWidth;
    d.height = kHeight;
    d.colorFormat = VK_FORMAT_R8G8B8A8_SRGB;  // sampled through the hardware's sRGB decode
    d.depthFormat = VK_FORMAT_D32_SFLOAT;
    d.method = method;
    return d;
  }
  stereo::StereoFrameDispatch dispatch() const {
    stereo::StereoFrameDispatch d;
    d.projection = frame_.projection;
    d.maxSeparation = parameters_.maxSeparation;
    d.zeroParallaxDistance = parameters_.zeroParallaxDistance;
    return d;
  }
  stereo::StereoParameters parametersFor(StereoMethod method) const {
    stereo::StereoParameters p = parameters_;
    p.method = method;
    return p;
  }

  // Both eyes of one frame, in two images or in the two layers of one array image.
  stereo::StereoPair frameEyes(StereoMethod method, bool arrayEyes, DepthImage* expectedLinear) {
    const DepthUpload depth = hardwareDepth(view_.depth, VK_FORMAT_D32_SFLOAT, frame_);
    *expectedLinear = depth.expectedLinear;
    vk::Image color = uploaded(VK_FORMAT_R8G8B8A8_SRGB, colorBytes(view_.color, VK_FORMAT_R8G8B8A8_SRGB), kShaderRead);
    vk::Image depthImage =
        uploaded(VK_FORMAT_D32_SFLOAT, depth.bytes, kDepthWritten, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    stereo::StereoFrame frame(*context_, desc(method));
    stereo::StereoFrameDispatch d = dispatch();
    d.color = hostImage(color, kShaderRead);
    d.depth = hostImage(depthImage, kDepthWritten);
    std::optional<ArrayImage> array;
    vk::Image left, right;
    if (arrayEyes) {
      array = createArrayImage(*context_, frame.eyeFormat(), kWidth, kHeight,
                               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
      for (std::uint32_t layer = 0; layer < 2; ++layer) {
        stereo::HostImage& eye = layer == 0 ? d.left : d.right;
        eye = {array->image.image, array->views[layer], frame.eyeFormat(), kCopiedOut.layout, kCopiedOut.stage,
               kCopiedOut.access, layer};
        const vk::Image borrowed = array->layer(layer);
        context_->submitAndWait([&](VkCommandBuffer cmd) { vk::transition(cmd, borrowed, vk::kUndefined, kCopiedOut); });
      }
    } else {
      left = output(frame.eyeFormat(), kWidth, kHeight);
      right = output(frame.eyeFormat(), kWidth, kHeight);
      d.left = hostImage(left, kCopiedOut);
      d.right = hostImage(right, kCopiedOut);
    }
    runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, d); });
    auto read = [&](const stereo::HostImage& eye) {
      const vk::Image view = vk::borrowImage(eye.image, eye.view, eye.format, kWidth, kHeight, eye.layer);
      return toImage(vk::readbackImage(*context_, view, kCopiedOut), kWidth, kHeight);
    };
    return {read(d.left), read(d.right)};
  }

  stereo::StereoPair reference(StereoMethod method, const DepthImage& linear) const {
    const stereo::StereoParameters p = parametersFor(method);
    if (method == StereoMethod::Iterative)
      return stereo::synthesizeIterativeReference(view_.color, linear, stereo::makeIterativeConstants(p, p.iterations, kWidth, kHeight));
    if (method == StereoMethod::Forward)
      return stereo::synthesizeForwardReference(view_.color, linear, stereo::makeForwardConstants(p, kWidth, kHeight));
    return stereo::synthesizeStereoReference(view_.color, linear, stereo::makeStereoConstants(p, kWidth, kHeight));
  }

};

TEST_F(StereoFrameTest, EveryMethodGivesItsReferenceEyesFromSrgbColourAndD32Depth) {
  for (StereoMethod method : {StereoMethod::Seed, StereoMethod::Search, StereoMethod::Iterative, StereoMethod::Forward}) {
    DepthImage linear;
    const stereo::StereoPair gpu = frameEyes(method, false, &linear);
    const stereo::StereoPair cpu = reference(method, linear);
    // 1 level: the GPU's unorm conversion of a filtered value may round the other way (as each method's own test).
    EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << stereo::methodName(method);
    EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << stereo::methodName(method);
  }
}

TEST_F(StereoFrameTest, TheEyesCanBeTheTwoLayersOfOneArrayImage) {
  for (StereoMethod method : {StereoMethod::Search, StereoMethod::Forward}) {
    DepthImage linear;
    const stereo::StereoPair layers = frameEyes(method, true, &linear);
    const stereo::StereoPair images = frameEyes(method, false, &linear);
    EXPECT_EQ(layers.left.pixels, images.left.pixels) << stereo::methodName(method);
    EXPECT_EQ(layers.right.pixels, images.right.pixels) << stereo::methodName(method);
  }
}

TEST_F(StereoFrameTest, BadDescriptionsAreRefusedNamingTheField) {
  stereo::StereoFrameDesc d = desc(StereoMethod::Hybrid);
  d.output = HostOutput::SideBySideHalf;  // the host draws the hybrid's pixels into eye images
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { stereo::StereoFrame(*context_, d); }).find("StereoFrameDesc.output"), std::string::npos);
  d = desc(StereoMethod::Forward);
  d.colorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { stereo::StereoFrame(*context_, d); }).find("HDR colour"), std::string::npos);
  d = desc(StereoMethod::Search);
  d.searchTaps = 0;
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { stereo::StereoFrame(*context_, d); }).find("StereoFrameDesc.searchTaps 0"), std::string::npos);
  d = desc(StereoMethod::Search);
  d.previousFrameFill = true;
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { stereo::StereoFrame(*context_, d); }).find("StereoFrameDesc.previousFrameFill"),
            std::string::npos);
  d = desc(StereoMethod::Search);
  d.colorFormat = VK_FORMAT_R8_UNORM;
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { stereo::StereoFrame(*context_, d); }).find("colour format"), std::string::npos);
}

TEST_F(StereoFrameTest, ADispatchThatDoesNotMatchTheDescriptionIsRefused) {
  stereo::StereoFrame frame(*context_, desc(StereoMethod::Forward));
  vk::Image color = output(VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight);  // not the description's sRGB format
  stereo::StereoFrameDispatch d = dispatch();
  d.color = d.depth = d.left = d.right = hostImage(color, kCopiedOut);
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, d); }); }).find("format"),
            std::string::npos);
  d.maxSeparation = -1.0f;
  EXPECT_NE(test::errorOf<std::invalid_argument>([&] { runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, d); }); }).find("maxSeparation"),
            std::string::npos);
}

TEST_F(StereoFrameTest, ThePreviousFrameFillWithoutTheHostsCameraIsRefused) {
  stereo::StereoFrameDesc d = desc(StereoMethod::Forward);
  d.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  d.depthFormat = VK_FORMAT_R32_SFLOAT;
  d.previousFrameFill = true;
  stereo::StereoFrame frame(*context_, d);
  vk::Image color = output(VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight), depth = output(VK_FORMAT_R32_SFLOAT, kWidth, kHeight);
  vk::Image left = output(frame.eyeFormat(), kWidth, kHeight), right = output(frame.eyeFormat(), kWidth, kHeight);
  stereo::StereoFrameDispatch dispatch = this->dispatch();  // centerView and centerProjection left at identity
  dispatch.color = hostImage(color, kCopiedOut);
  dispatch.depth = hostImage(depth, kCopiedOut);
  dispatch.left = hostImage(left, kCopiedOut);
  dispatch.right = hostImage(right, kCopiedOut);
  const std::string message = test::errorOf<std::invalid_argument>([&] { runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, dispatch); }); });
  EXPECT_NE(message.find("StereoFrameDispatch.centerView/centerProjection"), std::string::npos) << message;
}

TEST_F(StereoFrameTest, EyeViewsTheKernelsCannotReproduceAreRefusedNamingTheField) {
  // A headset's outward-turned frusta (samples/views/headset-pair.json's angles) at the frame's size.
  stereo::StereoFrameDesc description = desc(StereoMethod::Search);
  description.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  description.depthFormat = VK_FORMAT_R32_SFLOAT;
  stereo::StereoFrame frame(*context_, description);
  vk::Image color = output(VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight), depth = output(VK_FORMAT_R32_SFLOAT, kWidth, kHeight);
  vk::Image left = output(frame.eyeFormat(), kWidth, kHeight), right = output(frame.eyeFormat(), kWidth, kHeight);
  stereo::StereoFrameDispatch d = dispatch();
  d.color = hostImage(color, kCopiedOut);
  d.depth = hostImage(depth, kCopiedOut);
  d.left = hostImage(left, kCopiedOut);
  d.right = hostImage(right, kCopiedOut);
  d.eyeViews = stereo::ViewConfiguration{{stereo::EyeView{-0.0315, -0.7854, 0.6981, 0.7330, -0.8203, kWidth, kHeight},
                                          stereo::EyeView{0.0315, -0.6981, 0.7854, 0.7330, -0.8203, kWidth, kHeight}}};
  const std::string message = test::errorOf<std::invalid_argument>([&] { runOnHostQueue([&](VkCommandBuffer cmd) { frame.record(cmd, d); }); });
  EXPECT_NE(message.find("StereoFrameDispatch.eyeViews.eyes[0].angleLeft"), std::string::npos) << message;
}

// A host's eyes are `s3d render`'s eyes: the same rendered frame through the host's stereo frame and through the
// synthesis the render job runs (stereo::synthesizeTimed on the renderer's images), for every method.
class StereoFrameOnARenderedFrame : public VulkanTest {};

TEST_F(StereoFrameOnARenderedFrame, AHostsEyesAreTheRenderJobsEyesForEveryMethod) {
  constexpr std::uint32_t width = 160, height = 90;
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  renderer::DeferredRenderer deferred(context(), width, height);
  deferred.setScene(scene);
  const stereo::StereoParameters defaults;
  (void)deferred.render(renderer::centerViewMatrices(scene, float(width) / float(height),
                                                     {defaults.weaponDepthOffset, defaults.weaponDepthScale}));
  const ImageRGBA8 center = deferred.readDisplayColor();
  const DepthImage depth = deferred.readLinearDepth();
  auto image = [&](VkFormat format, VkImageUsageFlags usage) {
    return vk::createImage(context(), format, width, height, usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  };
  const vk::Image color = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT);
  const vk::Image linear = image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT);
  const vk::Image left = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
  const vk::Image right = image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
  vk::uploadImage(context(), color, std::as_bytes(std::span(center.pixels)), vk::kComputeRead);
  vk::uploadImage(context(), linear, std::as_bytes(std::span(depth.pixels)), vk::kComputeRead);
  context().submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* eye : {&left, &right}) vk::transition(cmd, *eye, vk::kUndefined, vk::kComputeWrite);
  });
  auto host = [](const vk::Image& i) { return stereo::HostImage{i.image, i.view, i.format, VK_IMAGE_LAYOUT_GENERAL}; };
  for (StereoMethod method : {StereoMethod::Seed, StereoMethod::Search, StereoMethod::Iterative, StereoMethod::Forward}) {
    stereo::StereoParameters parameters;
    parameters.method = method;
    const stereo::SynthesisResult rendered =
        stereo::synthesizeTimed(context(), deferred.displayColor(), deferred.linearDepth(), parameters);
    stereo::StereoFrameDesc desc;
    desc.width = width;
    desc.height = height;
    desc.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
    desc.depthFormat = VK_FORMAT_R32_SFLOAT;
    desc.method = method;
    stereo::StereoFrame frame(context(), desc);
    stereo::StereoFrameDispatch dispatch;
    dispatch.color = host(color);
    dispatch.depth = host(linear);
    dispatch.left = host(left);
    dispatch.right = host(right);
    dispatch.maxSeparation = parameters.maxSeparation;
    dispatch.zeroParallaxDistance = parameters.zeroParallaxDistance;
    context().submitAndWait([&](VkCommandBuffer cmd) { frame.record(cmd, dispatch); });
    for (auto [eye, expected] : {std::pair{&left, &rendered.eyes.left}, std::pair{&right, &rendered.eyes.right}}) {
      const ImageRGBA8 got = toImage(vk::readbackImage(context(), *eye, vk::kComputeWrite), width, height);
      EXPECT_LE(largestChannelDifference(got, *expected), 1) << stereo::methodName(method);  // within one level
    }
  }
}

// The C API's stereo frame: the same eyes through the C structs, a host that binds C would get.
class CStereoFrameTest : public StereoFrameTest {
 public:
  void SetUp() override {
    StereoFrameTest::SetUp();
    s3d_host_device device{};
    device.instance = host().instance;
    device.physical_device = host().physicalDevice;
    device.device = host().device;
    device.queue_family = host().queueFamily;
    device.queue = host().queue;
    ASSERT_EQ(s3d_context_create(&device, &cContext_), S3D_SUCCESS) << s3d_last_error();
  }
  void TearDown() override {
    s3d_context_destroy(cContext_);
    StereoFrameTest::TearDown();
  }
  static s3d_host_image cImage(const vk::Image& image, const vk::ImageState& state) {
    return {image.image, image.view, image.format, state.layout, state.stage, state.access, 0};
  }
  s3d_stereo_frame_desc cDesc(s3d_method method) const {
    s3d_stereo_frame_desc d;
    s3d_default_stereo_frame_desc(&d);
    d.width = kWidth;
    d.height = kHeight;
    d.method = method;
    return d;
  }

  stereo::StereoPair cEyes(s3d_method method, DepthImage* expectedLinear) {
    const DepthUpload depth = hardwareDepth(view_.depth, VK_FORMAT_D32_SFLOAT, frame_);
    *expectedLinear = depth.expectedLinear;
    vk::Image color = uploaded(VK_FORMAT_R8G8B8A8_SRGB, colorBytes(view_.color, VK_FORMAT_R8G8B8A8_SRGB), kShaderRead);
    vk::Image depthImage =
        uploaded(VK_FORMAT_D32_SFLOAT, depth.bytes, kDepthWritten, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    const s3d_stereo_frame_desc desc = cDesc(method);
    s3d_stereo_frame frame = nullptr;
    EXPECT_EQ(s3d_stereo_frame_create(cContext_, &desc, &frame), S3D_SUCCESS) << s3d_last_error();
    vk::Image left = output(s3d_stereo_frame_eye_format(frame), kWidth, kHeight);
    vk::Image right = output(s3d_stereo_frame_eye_format(frame), kWidth, kHeight);
    s3d_stereo_frame_dispatch d;
    s3d_default_stereo_frame_dispatch(&d);
    d.color = cImage(color, kShaderRead);
    d.depth = cImage(depthImage, kDepthWritten);
    d.left = cImage(left, kCopiedOut);
    d.right = cImage(right, kCopiedOut);
    d.projection.near_plane = frame_.projection.nearPlane;
    d.projection.far_plane = frame_.projection.farPlane;
    d.max_separation = parameters_.maxSeparation;
    d.zero_parallax_distance = parameters_.zeroParallaxDistance;
    runOnHostQueue([&](VkCommandBuffer cmd) {
      EXPECT_EQ(s3d_stereo_frame_record(frame, cmd, &d), S3D_SUCCESS) << s3d_last_error();
    });
    s3d_stereo_frame_destroy(frame);
    return {toImage(vk::readbackImage(*context_, left, kCopiedOut), kWidth, kHeight),
            toImage(vk::readbackImage(*context_, right, kCopiedOut), kWidth, kHeight)};
  }

  s3d_context cContext_ = nullptr;
};

TEST_F(CStereoFrameTest, EveryMethodThroughTheCApiGivesItsReferenceEyes) {
  const std::pair<s3d_method, StereoMethod> methods[] = {{S3D_METHOD_SEED, StereoMethod::Seed},
                                                         {S3D_METHOD_SEARCH, StereoMethod::Search},
                                                         {S3D_METHOD_ITERATIVE, StereoMethod::Iterative},
                                                         {S3D_METHOD_FORWARD, StereoMethod::Forward}};
  for (const auto& [cMethod, method] : methods) {
    DepthImage linear;
    const stereo::StereoPair gpu = cEyes(cMethod, &linear);
    const stereo::StereoPair cpu = reference(method, linear);
    EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << stereo::methodName(method);  // as above
    EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << stereo::methodName(method);
  }
}

TEST_F(CStereoFrameTest, BadDescriptionsAndDispatchesAreRefusedInTheCApisWords) {
  s3d_stereo_frame frame = nullptr;
  s3d_stereo_frame_desc desc = cDesc(S3D_METHOD_SEARCH);
  const std::int32_t notAMethod = 7;  // as a C caller may store it: C++ may not even form this enum value
  std::memcpy(&desc.method, &notAMethod, sizeof notAMethod);
  EXPECT_EQ(s3d_stereo_frame_create(cContext_, &desc, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("s3d_stereo_frame_desc.method"), std::string::npos) << s3d_last_error();
  desc = cDesc(S3D_METHOD_SEARCH);
  desc.previous_frame_fill = 1;
  EXPECT_EQ(s3d_stereo_frame_create(cContext_, &desc, &frame), S3D_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(s3d_last_error()).find("previous_frame_fill needs S3D_METHOD_FORWARD"), std::string::npos);
  desc = cDesc(S3D_METHOD_FORWARD);
  desc.previous_frame_fill = 1;
  ASSERT_EQ(s3d_stereo_frame_create(cContext_, &desc, &frame), S3D_SUCCESS) << s3d_last_error();
  vk::Image eye = output(s3d_stereo_frame_eye_format(frame), kWidth, kHeight);
  s3d_stereo_frame_dispatch d;
  s3d_default_stereo_frame_dispatch(&d);
  d.color = d.depth = d.left = d.right = cImage(eye, kCopiedOut);
  runOnHostQueue([&](VkCommandBuffer cmd) {
    EXPECT_EQ(s3d_stereo_frame_record(frame, cmd, &d), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("dispatch.color.format"), std::string::npos) << s3d_last_error();
    EXPECT_EQ(s3d_stereo_frame_record(frame, cmd, nullptr), S3D_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(s3d_last_error()).find("dispatch is NULL"), std::string::npos) << s3d_last_error();
  });
  s3d_stereo_frame_destroy(frame);
}

}  // namespace
}  // namespace s3d::test
