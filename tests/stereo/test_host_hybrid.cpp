// The hybrid for a host's own renderer (stereo_frame.h, StereoMethod::Hybrid): s3d displaces and classifies and
// writes each eye's mask into a depth image; the host's raster (the test's own: flat-coloured triangles, dynamic
// rendering, an ordinary depth test) draws each eye from the eye camera with it, and only masked pixels change.
// Synchronization validation on (TestHost).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

// clang-format off
#include <s3d_spirv/host_raster_vert.h>
#include <s3d_spirv/host_raster_frag.h>
// clang-format on

#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_pass.h"
#include "s3d/stereo/stereo_frame.h"
#include "s3d/vk/pipeline.h"
#include "stereo_test_views.h"
#include "test_host.h"

namespace s3d::test {
namespace {

using stereo::HostImage;
using stereo::StereoMethod;

constexpr std::uint32_t kWidth = 96, kHeight = 64;
constexpr float kNear = 0.5f, kFar = 100.0f;
constexpr float kSeparation = 0.04f, kZeroParallax = 4.0f;

constexpr vk::ImageState kShaderRead{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
// The host's depth buffers between draws (the combined layout: no separateDepthStencilLayouts needed).
constexpr vk::ImageState kDepthTarget{VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                          VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};

HostImage hostImage(const vk::Image& image, const vk::ImageState& state) {
  return {image.image, image.view, image.format, state.layout, state.stage, state.access};
}

struct Vertex {
  glm::vec3 position;
  glm::vec4 color;
};

// An axis-aligned quad at depth z (world units down -z) as two triangles of one colour.
void quad(std::vector<Vertex>& out, glm::vec2 low, glm::vec2 high, float z, glm::vec4 color) {
  const glm::vec3 a{low.x, low.y, z}, b{high.x, low.y, z}, c{high.x, high.y, z}, d{low.x, high.y, z};
  for (const glm::vec3& p : {a, b, c, a, c, d}) out.push_back({p, color});
}

// A far wall covering every view, a near box (its front and both sides, which only the eyes see), a quad behind
// it and a sloped triangle: edges, disocclusions and surfaces turned toward one eye.
std::vector<Vertex> scene() {
  std::vector<Vertex> v;
  quad(v, {-40, -40}, {40, 40}, -30.0f, {0.5f, 0.5f, 0.5f, 1});
  quad(v, {-0.9f, -0.6f}, {-0.1f, 0.4f}, -2.0f, {1, 0, 0, 1});
  for (const float x : {-0.9f, -0.1f}) {
    const glm::vec4 side = x < -0.5f ? glm::vec4(1, 1, 0, 1) : glm::vec4(1, 0, 1, 1);
    const glm::vec3 a{x, -0.6f, -2.0f}, b{x, -0.6f, -2.8f}, c{x, 0.4f, -2.8f}, d{x, 0.4f, -2.0f};
    for (const glm::vec3& p : {a, b, c, a, c, d}) v.push_back({p, side});
  }
  quad(v, {0.2f, -1.5f}, {2.0f, 1.0f}, -5.0f, {0, 0.8f, 0.2f, 1});
  for (const glm::vec3& p : {glm::vec3(-2.5f, -1.8f, -3.5f), glm::vec3(-0.5f, -1.9f, -9.0f), glm::vec3(-1.8f, 1.6f, -6.0f)})
    v.push_back({p, {0.1f, 0.3f, 0.9f, 1}});
  return v;
}

// The center camera at the origin looking down -z; Vulkan clip space (y down), depth 0..1 or reversed.
glm::mat4 centerProjection(bool reversedZ) {
  glm::mat4 p = reversedZ ? glm::perspectiveRH_ZO(glm::radians(60.0f), float(kWidth) / float(kHeight), kFar, kNear)
                          : glm::perspectiveRH_ZO(glm::radians(60.0f), float(kWidth) / float(kHeight), kNear, kFar);
  p[1][1] = -p[1][1];
  return p;
}

// The host's own raster: the scene into a colour and a depth image, cleared or loaded.
class HostRaster {
 public:
  HostRaster(vk::Context& context, bool reversedZ)
      : layout_(vk::createPushDescriptorLayout(context, {}, sizeof(glm::mat4), VK_SHADER_STAGE_VERTEX_BIT)) {
    vk::GraphicsPipelineDesc desc;
    desc.vertexSpirv = spirv_host_raster_vert;
    desc.fragmentSpirv = spirv_host_raster_frag;
    desc.vertexBindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                             {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)}};
    desc.colorFormats = {VK_FORMAT_R8G8B8A8_UNORM};
    desc.depthFormat = VK_FORMAT_D32_SFLOAT;
    desc.depthTest = desc.depthWrite = true;
    desc.depthCompare = reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
    pipeline_ = vk::createGraphicsPipeline(context, layout_.layout, desc);
    const std::vector<Vertex> vertices = scene();
    count_ = std::uint32_t(vertices.size());
    const std::span<const std::byte> bytes = std::as_bytes(std::span(vertices));
    buffer_ = vk::createBuffer(context, bytes.size(), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               vk::MemoryLocation::Device);
    vk::uploadBuffer(context, buffer_, bytes);
  }

  // color in kColorAttachment, depth in kDepthTarget, both ordered after their last use; clearDepth: clear both
  // first (black, that depth), else load what they hold.
  void draw(VkCommandBuffer cmd, const vk::Image& color, const vk::Image& depth, const glm::mat4& viewProjection,
            std::optional<float> clearDepth) const {
    const VkAttachmentLoadOp load = clearDepth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colorAttachment.imageView = color.view;
    colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colorAttachment.loadOp = load;
    colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colorAttachment.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = depth.view;
    depthAttachment.imageLayout = kDepthTarget.layout;
    depthAttachment.loadOp = load;
    depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depthAttachment.clearValue.depthStencil = {clearDepth.value_or(0.0f), 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {kWidth, kHeight}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &colorAttachment;
    info.pDepthAttachment = &depthAttachment;
    vkCmdBeginRendering(cmd, &info);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
    const VkViewport viewport{0.0f, 0.0f, float(kWidth), float(kHeight), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {kWidth, kHeight}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    const VkDeviceSize offset = 0;
    const VkBuffer buffer = buffer_.buffer;
    vkCmdBindVertexBuffers(cmd, 0, 1, &buffer, &offset);
    vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof viewProjection, &viewProjection);
    vkCmdDraw(cmd, count_, 1, 0, 0);
    vkCmdEndRendering(cmd);
  }

 private:
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;
  vk::Buffer buffer_;
  std::uint32_t count_ = 0;
};

ImageRGBA8 readColor(vk::Context& context, const vk::Image& image, const vk::ImageState& state) {
  const std::vector<std::byte> bytes = vk::readbackImage(context, image, state);
  ImageRGBA8 result(kWidth, kHeight);
  std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
  return result;
}

std::vector<float> readDepth(vk::Context& context, const vk::Image& image, const vk::ImageState& state) {
  const std::vector<std::byte> bytes = vk::readbackImage(context, image, state);
  std::vector<float> result(bytes.size() / sizeof(float));
  std::memcpy(result.data(), bytes.data(), bytes.size());
  return result;
}

bool samePixel(const ImageRGBA8& a, const ImageRGBA8& b, std::size_t i) {
  return std::memcmp(&a.pixels[4 * i], &b.pixels[4 * i], 4) == 0;
}

// One hybrid frame of the scene, with what the test compares: the eyes after step 1 (displaced), after the
// host's masked draw and step 2, the host's full render of each eye, and the masks as written.
struct HybridRun {
  std::array<ImageRGBA8, 2> displaced, drawn, full;
  std::array<std::vector<float>, 2> maskDepth;
  stereo::HybridEyeCameras cameras;
  gpu::HybridConstants constants{};
};

class HostHybridTest : public HostContextTest {
 protected:
  vk::Image image(VkFormat format, VkImageUsageFlags usage) {
    return vk::createImage(*context_, format, kWidth, kHeight, usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  }
  vk::Image colorTarget() { return image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT); }
  vk::Image depthTarget() { return image(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT); }

  stereo::StereoFrameDesc desc(StereoMethod method, float budget, VkFormat depthFormat = VK_FORMAT_D32_SFLOAT) const {
    stereo::StereoFrameDesc d;
    d.width = kWidth;
    d.height = kHeight;
    d.colorFormat = VK_FORMAT_R8G8B8A8_UNORM;
    d.depthFormat = depthFormat;
    d.method = method;
    d.hybridBudget = budget;
    return d;
  }
  stereo::StereoFrameDispatch dispatch(bool reversedZ) const {
    stereo::StereoFrameDispatch d;
    d.projection.nearPlane = kNear;
    d.projection.farPlane = kFar;
    d.projection.reversedZ = reversedZ;
    d.maxSeparation = kSeparation;
    d.zeroParallaxDistance = kZeroParallax;
    d.centerView = glm::mat4(1.0f);
    d.centerProjection = centerProjection(reversedZ);
    return d;
  }
  stereo::StereoParameters parameters(float budget) const {
    stereo::StereoParameters p;
    p.method = StereoMethod::Hybrid;
    p.hybridBase = StereoMethod::Search;
    p.hybridBudget = budget;
    p.maxSeparation = kSeparation;
    p.zeroParallaxDistance = kZeroParallax;
    return p;
  }

  // The host's center view: the scene drawn from the center camera (colour left for sampling, depth as drawn).
  void drawCenter(const HostRaster& raster, const vk::Image& color, const vk::Image& depth, bool reversedZ) {
    runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
      vk::transition(cmd, color, vk::kUndefined, vk::kColorAttachment);
      vk::transition(cmd, depth, vk::kUndefined, kDepthTarget);
      raster.draw(cmd, color, depth, centerProjection(reversedZ), reversedZ ? 0.0f : 1.0f);
      vk::transition(cmd, color, vk::kColorAttachment, kShaderRead);
    });
  }

  HybridRun run(float budget, bool reversedZ) {
    const HostRaster raster(*context_, reversedZ);
    const vk::Image color = colorTarget(), depth = depthTarget();
    drawCenter(raster, color, depth, reversedZ);
    stereo::StereoFrame frame(*context_, desc(StereoMethod::Hybrid, budget));
    const std::array<vk::Image, 2> eyes{colorTarget(), colorTarget()}, masks{depthTarget(), depthTarget()};
    stereo::StereoFrameDispatch d = dispatch(reversedZ);
    d.color = hostImage(color, kShaderRead);
    d.depth = hostImage(depth, kDepthTarget);
    d.left = hostImage(eyes[0], vk::kColorAttachment);
    d.right = hostImage(eyes[1], vk::kColorAttachment);
    d.leftMask = hostImage(masks[0], kDepthTarget);
    d.rightMask = hostImage(masks[1], kDepthTarget);
    HybridRun result;
    runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
      for (std::size_t e = 0; e < 2; ++e) {
        vk::transition(cmd, eyes[e], vk::kUndefined, vk::kColorAttachment);
        vk::transition(cmd, masks[e], vk::kUndefined, kDepthTarget);
      }
      result.cameras = frame.recordHybridMasks(cmd, d);
    });
    const std::array<stereo::EyeCamera, 2> cameras{result.cameras.left, result.cameras.right};
    for (std::size_t e = 0; e < 2; ++e) {
      result.displaced[e] = readColor(*context_, eyes[e], vk::kColorAttachment);
      result.maskDepth[e] = readDepth(*context_, masks[e], kDepthTarget);
    }
    // The host's draw: each eye from its camera, tested against its mask (nothing cleared), then step 2.
    runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
      for (std::size_t e = 0; e < 2; ++e)
        raster.draw(cmd, eyes[e], masks[e], cameras[e].projection * cameras[e].view, std::nullopt);
      frame.recordHybridComposite(cmd, d);
    });
    // The host's full render of each eye, for the masked pixels' expected colours.
    const vk::Image fullColor = colorTarget(), fullDepth = depthTarget();
    for (std::size_t e = 0; e < 2; ++e) {
      result.drawn[e] = readColor(*context_, eyes[e], vk::kColorAttachment);
      runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
        vk::transition(cmd, fullColor, vk::kUndefined, vk::kColorAttachment);
        vk::transition(cmd, fullDepth, vk::kUndefined, kDepthTarget);
        raster.draw(cmd, fullColor, fullDepth, cameras[e].projection * cameras[e].view, reversedZ ? 0.0f : 1.0f);
      });
      result.full[e] = readColor(*context_, fullColor, vk::kColorAttachment);
    }
    result.constants = stereo::makeHybridConstants(parameters(budget), kWidth, kHeight);
    return result;
  }
};

// Every mask depth is exactly the far or the near value; returns the masked pixels (far) of one eye.
std::vector<std::uint8_t> masked(const std::vector<float>& maskDepth, bool reversedZ) {
  const float far = reversedZ ? 0.0f : 1.0f, near = reversedZ ? 1.0f : 0.0f;
  std::vector<std::uint8_t> result(maskDepth.size());
  for (std::size_t i = 0; i < maskDepth.size(); ++i) {
    EXPECT_TRUE(maskDepth[i] == far || maskDepth[i] == near) << "pixel " << i << ": " << maskDepth[i];
    result[i] = maskDepth[i] == far ? 1 : 0;
  }
  return result;
}

std::size_t count(const std::vector<std::uint8_t>& mask) { return std::size_t(std::count(mask.begin(), mask.end(), 1)); }

// Masked pixels take the host's raster colour, all others keep the displaced colour, bit for bit: the masked
// draw's fragments are the full render's (the far value is what a full render clears to).
void expectMaskedDraw(const HybridRun& run, bool reversedZ) {
  const std::uint64_t classified = std::uint64_t(run.constants.cropEnd - run.constants.cropBegin) * kHeight;
  for (std::size_t e = 0; e < 2; ++e) {
    const std::vector<std::uint8_t> mask = masked(run.maskDepth[e], reversedZ);
    EXPECT_GT(count(mask), 0u) << "eye " << e;
    EXPECT_LE(count(mask), run.constants.maskedPixelCap) << "eye " << e;
    EXPECT_LT(count(mask), classified) << "eye " << e;
    std::size_t keptWrong = 0, drawnWrong = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
      if (mask[i] != 0) drawnWrong += !samePixel(run.drawn[e], run.full[e], i);
      else keptWrong += !samePixel(run.drawn[e], run.displaced[e], i);
    }
    EXPECT_EQ(keptWrong, 0u) << "eye " << e << ": unmasked pixels the host's draw changed";
    EXPECT_EQ(drawnWrong, 0u) << "eye " << e << ": masked pixels without the raster's colour";
    EXPECT_GT(largestChannelDifference(run.displaced[e], run.drawn[e]), 0) << "eye " << e << ": the draw changed nothing";
  }
}

TEST_F(HostHybridTest, OnlyMaskedPixelsTakeTheHostsRaster) { expectMaskedDraw(run(0.1f, false), false); }

TEST_F(HostHybridTest, ReversedZMasksAreFarAtZero) { expectMaskedDraw(run(0.1f, true), true); }

// Budget 1 masks every classified pixel: inside the crop the eye is the host's full render of that eye (exactly:
// the same fragments), the cropped columns stay as the displacement blacked them.
TEST_F(HostHybridTest, FullBudgetIsTheHostsFullRender) {
  const HybridRun r = run(1.0f, false);
  for (std::size_t e = 0; e < 2; ++e) {
    const std::vector<std::uint8_t> mask = masked(r.maskDepth[e], false);
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const std::size_t i = std::size_t(y) * kWidth + x;
        const bool crop = int(x) >= r.constants.cropBegin && int(x) < r.constants.cropEnd;
        ASSERT_EQ(mask[i], crop ? 1 : 0) << "eye " << e << " pixel " << x << "," << y;
        ASSERT_TRUE(samePixel(r.drawn[e], crop ? r.full[e] : r.displaced[e], i)) << "eye " << e << " pixel " << x << "," << y;
      }
  }
}

// Budget 0 masks nothing: the host's draw changes no pixel, and the eyes are the search's.
TEST_F(HostHybridTest, EmptyBudgetChangesNothing) {
  const HybridRun r = run(0.0f, false);
  for (std::size_t e = 0; e < 2; ++e) {
    EXPECT_EQ(count(masked(r.maskDepth[e], false)), 0u) << "eye " << e;
    EXPECT_EQ(largestChannelDifference(r.drawn[e], r.displaced[e]), 0) << "eye " << e;
  }
  // The same inputs through the search method: its kernel is the host pass's own, the hybrid's the stereo pass's;
  // both are the search's math, so they agree bit for bit.
  const HostRaster raster(*context_, false);
  const vk::Image color = colorTarget(), depth = depthTarget(), left = colorTarget(), right = colorTarget();
  drawCenter(raster, color, depth, false);
  stereo::StereoFrame search(*context_, desc(StereoMethod::Search, 0.0f));
  stereo::StereoFrameDispatch d = dispatch(false);
  d.color = hostImage(color, kShaderRead);
  d.depth = hostImage(depth, kDepthTarget);
  d.left = hostImage(left, vk::kColorAttachment);
  d.right = hostImage(right, vk::kColorAttachment);
  runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
    for (const vk::Image* eye : {&left, &right}) vk::transition(cmd, *eye, vk::kUndefined, vk::kColorAttachment);
    search.record(cmd, d);
  });
  EXPECT_EQ(largestChannelDifference(readColor(*context_, left, vk::kColorAttachment), r.displaced[0]), 0);
  EXPECT_EQ(largestChannelDifference(readColor(*context_, right, vk::kColorAttachment), r.displaced[1]), 0);
}

// The masks are the built-in hybrid's (HybridPass on the same linear depth and constants), pixel for pixel: here
// from the host's linear depth (R32F), so both classify the same values.
TEST_F(HostHybridTest, MasksAreTheBuiltInHybridsMasks) {
  const HostRaster raster(*context_, false);
  const vk::Image color = colorTarget(), deviceDepth = depthTarget();
  drawCenter(raster, color, deviceDepth, false);
  stereo::StereoFrameDispatch d = dispatch(false);
  const gpu::LinearDepthParams params = stereo::linearDepthParams(d.projection, 1.0f, 1.0f);
  DepthImage linear(kWidth, kHeight);
  const std::vector<float> device = readDepth(*context_, deviceDepth, kDepthTarget);
  for (std::size_t i = 0; i < device.size(); ++i) linear.pixels[i] = gpu::stereoDepthFromDevice(params, device[i]);
  const vk::Image linearImage = image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  vk::uploadImage(*context_, linearImage, std::as_bytes(std::span(linear.pixels)), kShaderRead);

  constexpr float kBudget = 0.15f;
  stereo::StereoFrame frame(*context_, desc(StereoMethod::Hybrid, kBudget, VK_FORMAT_R32_SFLOAT));
  const std::array<vk::Image, 2> eyes{colorTarget(), colorTarget()}, masks{depthTarget(), depthTarget()};
  d.color = hostImage(color, kShaderRead);
  d.depth = hostImage(linearImage, kShaderRead);
  d.left = hostImage(eyes[0], vk::kColorAttachment);
  d.right = hostImage(eyes[1], vk::kColorAttachment);
  d.leftMask = hostImage(masks[0], kDepthTarget);
  d.rightMask = hostImage(masks[1], kDepthTarget);
  runOnHostQueue(host(), [&](VkCommandBuffer cmd) {
    for (std::size_t e = 0; e < 2; ++e) {
      vk::transition(cmd, eyes[e], vk::kUndefined, vk::kColorAttachment);
      vk::transition(cmd, masks[e], vk::kUndefined, kDepthTarget);
    }
    (void)frame.recordHybridMasks(cmd, d);
  });
  const stereo::HybridGpuResult builtIn =
      stereo::classifyHybridOnGpu(*context_, linear, stereo::makeHybridConstants(parameters(kBudget), kWidth, kHeight));
  const std::vector<std::uint8_t> left = masked(readDepth(*context_, masks[0], kDepthTarget), false);
  const std::vector<std::uint8_t> right = masked(readDepth(*context_, masks[1], kDepthTarget), false);
  EXPECT_GT(count(left), 0u);
  EXPECT_EQ(left, builtIn.leftMask);
  EXPECT_EQ(right, builtIn.rightMask);
}

// The eye cameras put a point at depth z the displacement's parallax, m (1 - zpp / z) of the width, away from its
// center position (left eye to the left), within 1e-4 px of float rounding.
TEST_F(HostHybridTest, EyeCamerasCarryTheDisplacementsParallax) {
  const HybridRun r = run(0.1f, false);
  const glm::vec4 point{0.3f, -0.2f, -7.0f, 1.0f};
  const auto columnOf = [](const glm::mat4& viewProjection, const glm::vec4& p) {
    const glm::vec4 clip = viewProjection * p;
    return (clip.x / clip.w * 0.5f + 0.5f) * float(kWidth);
  };
  const float center = columnOf(centerProjection(false), point);
  const float parallax = kSeparation * (1.0f - kZeroParallax / 7.0f) * float(kWidth);
  EXPECT_NEAR(columnOf(r.cameras.left.projection * r.cameras.left.view, point), center - parallax, 1e-4f);
  EXPECT_NEAR(columnOf(r.cameras.right.projection * r.cameras.right.view, point), center + parallax, 1e-4f);
}

// Bad input is refused naming the field: the masks, the output, the budget, and the wrong recording call.
TEST_F(HostHybridTest, RefusesMissingMasksNamingTheField) {
  const auto message = [](const std::function<void()>& call) {
    try {
      call();
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("(nothing thrown)");
  };
  const vk::Image color = colorTarget(), depth = depthTarget(), left = colorTarget(), right = colorTarget(),
                  mask = depthTarget();
  stereo::StereoFrame frame(*context_, desc(StereoMethod::Hybrid, 0.5f));
  stereo::StereoFrameDispatch d = dispatch(false);
  d.color = hostImage(color, kShaderRead);
  d.depth = hostImage(depth, kDepthTarget);
  d.left = hostImage(left, vk::kColorAttachment);
  d.right = hostImage(right, vk::kColorAttachment);
  // Refused before anything is recorded: the command buffer is never used.
  const VkCommandBuffer cmd = VK_NULL_HANDLE;
  EXPECT_NE(message([&] { (void)frame.recordHybridMasks(cmd, d); }).find("StereoFrameDispatch.leftMask"), std::string::npos);
  d.leftMask = hostImage(mask, kDepthTarget);
  EXPECT_NE(message([&] { (void)frame.recordHybridMasks(cmd, d); }).find("StereoFrameDispatch.rightMask"), std::string::npos);
  d.rightMask = hostImage(left, vk::kColorAttachment);
  EXPECT_NE(message([&] { (void)frame.recordHybridMasks(cmd, d); }).find("StereoFrameDispatch.rightMask.format"),
            std::string::npos);
  EXPECT_NE(message([&] { frame.record(cmd, d); }).find("recordHybridMasks"), std::string::npos);
  stereo::StereoFrame search(*context_, desc(StereoMethod::Search, 0.5f));
  EXPECT_NE(message([&] { (void)search.recordHybridMasks(cmd, d); }).find("StereoFrameDesc.method"), std::string::npos);
  stereo::StereoFrameDesc packed = desc(StereoMethod::Hybrid, 0.5f);
  packed.output = stereo::HostOutput::SideBySideFull;
  EXPECT_NE(message([&] { stereo::StereoFrame f(*context_, packed); }).find("StereoFrameDesc.output"), std::string::npos);
  EXPECT_NE(message([&] { stereo::StereoFrame f(*context_, desc(StereoMethod::Hybrid, 1.5f)); }).find("StereoFrameDesc.hybridBudget"),
            std::string::npos);
}

}  // namespace
}  // namespace s3d::test
