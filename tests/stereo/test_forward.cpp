// The forward (scatter) method: exact answers on a disparity ramp, a 40 px step edge, a sub-pixel shift and
// unknown depth, and the GPU pass held to the C++ implementation pixel by pixel, in both kernels (a row in
// shared memory; splat and resolve dispatches over key images) and on rows wider than shared memory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "s3d/stereo/forward.h"
#include "s3d/stereo/detail/eye_pair_pipeline.h"
#include "s3d/stereo/forward_pass.h"
#include "stereo_test_views.h"
#include "vulkan_test.h"

namespace s3d::stereo {
namespace {

using test::largestChannelDifference;

class ForwardPass : public test::VulkanTest {};

// Depth whose parallax is exactly `parallaxPx` pixels for maxSeparation m, zero-parallax distance 1, width w.
float depthForParallax(float parallaxPx, float m, std::uint32_t width) {
  return 1.0f / (1.0f - parallaxPx / (m * float(width)));
}

StereoParameters separation(float maxSeparation) {
  StereoParameters parameters;
  parameters.method = StereoMethod::Forward;
  parameters.maxSeparation = maxSeparation;
  parameters.zeroParallaxDistance = 1.0f;
  parameters.edgeCrop = 0.0f;
  return parameters;
}

// The expected value of a horizontal linear filter of one channel at texel position u.
int filtered(const ImageRGBA8& image, int y, float u, int channel) {
  const int x0 = int(std::floor(u));
  const float f = u - float(x0);
  const float a = image.at(std::uint32_t(x0), std::uint32_t(y))[channel];
  const float b = image.at(std::uint32_t(std::min(x0 + 1, int(image.width) - 1)), std::uint32_t(y))[channel];
  return int(std::lround(a * (1.0f - f) + b * f));
}

// Background (red < 128) at the sky, parallax 50 px; a foreground block (red >= 128), parallax 10 px, on
// columns [80, 120): 40 px of disparity between them. Unknown columns (NaN) are given by the caller.
constexpr std::uint32_t kStepWidth = 200, kStepHeight = 4, kBlockBegin = 80, kBlockEnd = 120;
test::SyntheticView makeStepView() {
  std::mt19937 random(3);
  test::SyntheticView view{ImageRGBA8(kStepWidth, kStepHeight), DepthImage(kStepWidth, kStepHeight, INFINITY)};
  for (std::uint32_t y = 0; y < kStepHeight; ++y)
    for (std::uint32_t x = 0; x < kStepWidth; ++x) {
      const bool block = x >= kBlockBegin && x < kBlockEnd;
      std::uint8_t* pixel = view.color.at(x, y);
      pixel[0] = std::uint8_t(block ? 128 + random() % 128 : random() % 128);
      pixel[1] = std::uint8_t(random() % 256);
      pixel[2] = std::uint8_t(random() % 256);
      pixel[3] = 255;
      if (block) *view.depth.at(x, y) = depthForParallax(10.0f, 0.25f, kStepWidth);
    }
  return view;
}

bool isForeground(const std::uint8_t* pixel) { return pixel[0] >= 128; }

TEST(ForwardReference, DisplacementBeyondTheKeyIsRejected) {
  EXPECT_THROW(makeForwardConstants(separation(0.25f), 8200, 4), std::invalid_argument);
  EXPECT_NO_THROW(makeForwardConstants(separation(0.25f), 1920, 4));
}

TEST(ForwardReference, TheNearerSurfaceWinsTheZBuffer) {
  const test::SyntheticView view = makeStepView();
  const gpu::ForwardConstants c = makeForwardConstants(separation(0.25f), kStepWidth, kStepHeight);
  const std::vector<std::uint32_t> keys = forwardSplatRow(view.depth, 0, 1.0f, c);
  // Left eye: the block lands on [70, 110); the background behind [80, 110) came from [130, 160).
  for (int x = 70; x < 110; ++x) EXPECT_EQ(gpu::forwardKeySource(keys[std::size_t(x)], x), x + 10) << x;
  for (int x = 30; x < 70; ++x) EXPECT_EQ(keys[std::size_t(x)], S3D_FORWARD_EMPTY) << x;  // the disocclusion
}

TEST_F(ForwardPass, ZeroSeparationIsTheCenterViewBitForBit) {
  const test::SyntheticView view = test::makeBlockView(96, 24, 7, 0.6f, 9, 3, true);
  const StereoPair eyes = synthesizeForwardOnGpu(context(), view.color, view.depth,
                                                 makeForwardConstants(separation(0.0f), 96, 24));
  EXPECT_EQ(eyes.left.pixels, view.color.pixels);
  EXPECT_EQ(eyes.right.pixels, view.color.pixels);
}

TEST_F(ForwardPass, GpuMatchesTheCppReference) {
  // Random blocks (sky, behind and in front of the screen) with some unknown pixels; alpha random too.
  test::SyntheticView view = test::makeBlockView(160, 48, 11, 0.6f, 9, 3, true);
  std::mt19937 random(2);
  for (int i = 0; i < 60; ++i) *view.depth.at(std::uint32_t(random() % 160), std::uint32_t(random() % 48)) = NAN;
  for (float m : {0.02f, 0.08f}) {
    StereoParameters parameters = separation(m);
    parameters.edgeCrop = -1.0f;  // the seed's crop
    const gpu::ForwardConstants c = makeForwardConstants(parameters, 160, 48);
    const StereoPair gpu = synthesizeForwardOnGpu(context(), view.color, view.depth, c);
    const StereoPair cpu = synthesizeForwardReference(view.color, view.depth, c);
    // 1 level: the GPU's unorm conversion of a filtered or averaged value may round the other way.
    EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << m;
    EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << m;
  }
}

TEST_F(ForwardPass, AStepEdgeKeepsEveryVisiblePixelAndNoForegroundInTheBackground) {
  const test::SyntheticView view = makeStepView();
  const StereoPair eyes = synthesizeForwardOnGpu(context(), view.color, view.depth,
                                                 makeForwardConstants(separation(0.25f), kStepWidth, kStepHeight));
  for (std::uint32_t y = 0; y < kStepHeight; ++y)
    for (int x = 0; x < int(kStepWidth); ++x) {
      const std::uint8_t* pixel = eyes.left.at(std::uint32_t(x), y);
      int source = -1;  // the visible source, or -1 where the left eye sees what the center did not
      if (x >= 70 && x < 110) source = x + 10;
      else if (x < 30 || (x >= 110 && x < 150)) source = x + 50;
      if (source < 0) {
        EXPECT_FALSE(isForeground(pixel)) << x << ", " << y;
        continue;
      }
      for (int channel = 0; channel < 4; ++channel)
        ASSERT_LE(std::abs(int(pixel[channel]) - int(view.color.at(std::uint32_t(source), y)[channel])), 1)
            << x << ", " << y << " channel " << channel;
    }
}

TEST_F(ForwardPass, AGapBetweenTwoOccludersShowsTheBackgroundNotAnOccluder) {
  // An occluder (parallax 10 px) on columns [80, 200) over the sky (60 px) with a 3-column gap at 130..132 (red
  // 20). The left eye's pixels 120..122 look through the gap at background the center never saw (180..182 is
  // occluder there): a hole between two occluder edges, to be filled with what the gap showed.
  constexpr std::uint32_t width = 240;
  ImageRGBA8 color(width, 1);
  DepthImage depth(width, 1, INFINITY);
  for (std::uint32_t x = 0; x < width; ++x) {
    const bool occluder = x >= 80 && x < 200 && (x < 130 || x >= 133);
    std::uint8_t* pixel = color.at(x, 0);
    pixel[0] = occluder ? 200 : (x >= 130 && x < 133 ? 20 : 90);
    pixel[1] = pixel[2] = 0;
    pixel[3] = 255;
    if (occluder) *depth.at(x, 0) = depthForParallax(10.0f, 0.25f, width);
  }
  const StereoPair eyes =
      synthesizeForwardOnGpu(context(), color, depth, makeForwardConstants(separation(0.25f), width, 1));
  for (std::uint32_t x = 120; x < 123; ++x) EXPECT_EQ(eyes.left.at(x, 0)[0], 20) << x;
}

TEST_F(ForwardPass, ADisparityRampIsResampledExactly) {
  // Parallax 5 + 0.1 x (a slanted surface): eye pixel t shows the center at u = (t + 5) / 0.9.
  constexpr std::uint32_t width = 160, height = 2;
  test::SyntheticView view = test::makeBlockView(width, height, 4, 0.6f, 9, 3, true);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) *view.depth.at(x, y) = depthForParallax(5.0f + 0.1f * float(x), 0.25f, width);
  const StereoPair eyes = synthesizeForwardOnGpu(context(), view.color, view.depth,
                                                 makeForwardConstants(separation(0.25f), width, height));
  for (std::uint32_t y = 0; y < height; ++y)
    for (int t = 0; t < 130; ++t) {
      const float u = (float(t) + 5.0f) / 0.9f;
      for (int channel = 0; channel < 4; ++channel)
        ASSERT_LE(std::abs(int(eyes.left.at(std::uint32_t(t), y)[channel]) - filtered(view.color, int(y), u, channel)), 1)
            << t << ", " << y;
    }
}

TEST_F(ForwardPass, ASubPixelParallaxMovesAnEdgeByItsFraction) {
  // A black | white edge at column 50, uniform parallax 0.25 px: the left eye's pixel 49 is a quarter white.
  constexpr std::uint32_t width = 100;
  ImageRGBA8 color(width, 1);
  for (std::uint32_t x = 0; x < width; ++x) {
    std::uint8_t* pixel = color.at(x, 0);
    pixel[0] = pixel[1] = pixel[2] = x < 50 ? 0 : 255;
    pixel[3] = 255;
  }
  const DepthImage depth(width, 1, depthForParallax(0.25f, 0.1f, width));
  const StereoPair eyes = synthesizeForwardOnGpu(context(), color, depth, makeForwardConstants(separation(0.1f), width, 1));
  EXPECT_EQ(eyes.left.at(48, 0)[0], 0);
  EXPECT_NEAR(eyes.left.at(49, 0)[0], 64, 1);  // 0.25 * 255
  EXPECT_EQ(eyes.left.at(50, 0)[0], 255);
  EXPECT_NEAR(eyes.right.at(50, 0)[0], 191, 1);  // the right eye moves it the other way
}

TEST_F(ForwardPass, AColumnOnAFootprintBoundaryGoesToTheSurfaceBesideTheDisocclusion) {
  // A block on columns [30, 45) at parallax exactly 10.5 px (depth 2) over the sky (21 px), width 84: its end
  // pixels' footprints end exactly on an eye column's center. The right eye's column 55 (pixel 44's right end,
  // a hole opening to its right) and the left eye's column 19 (pixel 30's left end, the mirror case) show the
  // block's edge pixel, not a fill; the next columns are holes filled from the sky.
  constexpr std::uint32_t width = 84;
  ImageRGBA8 color(width, 1);
  DepthImage depth(width, 1, INFINITY);
  for (std::uint32_t x = 0; x < width; ++x) {
    const bool block = x >= 30 && x < 45;
    std::uint8_t* pixel = color.at(x, 0);
    pixel[0] = std::uint8_t(block ? 130 + x : 2 * x % 128);
    pixel[1] = pixel[2] = 0;
    pixel[3] = 255;
    if (block) *depth.at(x, 0) = 2.0f;
  }
  const StereoPair eyes =
      synthesizeForwardOnGpu(context(), color, depth, makeForwardConstants(separation(0.25f), width, 1));
  EXPECT_EQ(eyes.right.at(55, 0)[0], color.at(44, 0)[0]);
  EXPECT_FALSE(isForeground(eyes.right.at(56, 0)));
  EXPECT_EQ(eyes.left.at(19, 0)[0], color.at(30, 0)[0]);
  EXPECT_FALSE(isForeground(eyes.left.at(18, 0)));
}

TEST_F(ForwardPass, UnknownDepthIsFilledFromTheBackgroundNotPlacedAtTheScreen) {
  // Two unknown columns (green 255, never otherwise used) beside the block, as a stereo matcher leaves them.
  test::SyntheticView view = makeStepView();
  for (std::uint32_t y = 0; y < kStepHeight; ++y)
    for (std::uint32_t x = 78; x < 80; ++x) {
      *view.depth.at(x, y) = NAN;
      view.color.at(x, y)[1] = 255;
    }
  for (std::uint32_t y = 0; y < kStepHeight; ++y)
    for (std::uint32_t x = 0; x < kStepWidth; ++x)
      if (x < 78 || x >= 80) view.color.at(x, y)[1] = std::min<std::uint8_t>(view.color.at(x, y)[1], 200);
  const StereoPair eyes = synthesizeForwardOnGpu(context(), view.color, view.depth,
                                                 makeForwardConstants(separation(0.25f), kStepWidth, kStepHeight));
  for (std::uint32_t y = 0; y < kStepHeight; ++y)
    for (std::uint32_t x = 0; x < kStepWidth; ++x) {
      EXPECT_LE(eyes.left.at(x, y)[1], 200) << x << ", " << y;
      EXPECT_LE(eyes.right.at(x, y)[1], 200) << x << ", " << y;
      if (x >= 28 && x < 70) {
        EXPECT_FALSE(isForeground(eyes.left.at(x, y))) << x << ", " << y;
      }
    }
}

// Random blocks (sky, behind and in front of the screen) with some unknown pixels: holes, gaps and edges.
test::SyntheticView makeNoisyBlockView(std::uint32_t width, std::uint32_t height) {
  test::SyntheticView view = test::makeBlockView(width, height, 5, 0.6f, 9, 3, true);
  std::mt19937 random(4);
  for (std::uint32_t i = 0; i < width * height / 50; ++i)
    *view.depth.at(std::uint32_t(random() % width), std::uint32_t(random() % height)) = NAN;
  return view;
}

// The widest row whose shared arrays fit the device (a multiple of the capacity step, less a few columns so the
// arrays hold more than the row), and the narrowest that does not.
std::uint32_t maxSharedBytes(const vk::Context& context) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  return properties.limits.maxComputeSharedMemorySize;
}
std::uint32_t widestFittingRow(const vk::Context& context) {
  const std::uint32_t columns = maxSharedBytes(context) / S3D_FORWARD_ROW_SHARED_BYTES_PER_COLUMN;
  return columns / S3D_FORWARD_ROW_CAPACITY_STEP * S3D_FORWARD_ROW_CAPACITY_STEP - 5;
}

TEST_F(ForwardPass, BothKernelsMatchTheCppReference) {
  // 300 columns: not a multiple of the row group or the capacity step; the seed's crop on.
  constexpr std::uint32_t width = 300, height = 24;
  const test::SyntheticView view = makeNoisyBlockView(width, height);
  for (float m : {0.02f, 0.08f}) {
    StereoParameters parameters = separation(m);
    parameters.edgeCrop = -1.0f;
    const gpu::ForwardConstants c = makeForwardConstants(parameters, width, height);
    const StereoPair cpu = synthesizeForwardReference(view.color, view.depth, c);
    const StereoPair rows = synthesizeForwardOnGpu(context(), view.color, view.depth, c, StereoKernel::RowTiles);
    const StereoPair keyImages = synthesizeForwardOnGpu(context(), view.color, view.depth, c, StereoKernel::PerPixel);
    // 1 level: the GPU's unorm conversion of a filtered or averaged value may round the other way.
    EXPECT_LE(largestChannelDifference(rows.left, cpu.left), 1) << m;
    EXPECT_LE(largestChannelDifference(rows.right, cpu.right), 1) << m;
    EXPECT_LE(largestChannelDifference(keyImages.left, cpu.left), 1) << m;
    EXPECT_LE(largestChannelDifference(keyImages.right, cpu.right), 1) << m;
  }
}

TEST_F(ForwardPass, HolesWiderThanTheFillReachMatchTheCppReferenceInBothKernels) {
  // Unknown bands make holes longer than c.fillSearchPx (whose middle sees no edge and whose ends see one
  // edge), holes at the image's edges and holes reaching into the crop: filled as the C++ twin fills them.
  test::SyntheticView view = makeStepView();
  for (std::uint32_t y = 0; y < kStepHeight; ++y)
    for (std::uint32_t x = 0; x < kStepWidth; ++x)
      if (x < 21 || (x >= 97 && x < 150 + y) || x >= 190) *view.depth.at(x, y) = NAN;
  for (float m : {0.02f, 0.08f}) {
    for (float edgeCrop : {0.0f, -1.0f}) {  // none, and the seed's crop
      StereoParameters parameters = separation(m);
      parameters.edgeCrop = edgeCrop;
      const gpu::ForwardConstants c = makeForwardConstants(parameters, kStepWidth, kStepHeight);
      ASSERT_LT(c.fillSearchPx, 50);
      const StereoPair cpu = synthesizeForwardReference(view.color, view.depth, c);
      for (StereoKernel kernel : {StereoKernel::RowTiles, StereoKernel::PerPixel}) {
        const StereoPair gpu = synthesizeForwardOnGpu(context(), view.color, view.depth, c, kernel);
        // 1 level: the GPU's unorm conversion of a filtered or averaged value may round the other way.
        EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << m << " " << edgeCrop;
        EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << m << " " << edgeCrop;
      }
    }
  }
}

TEST_F(ForwardPass, TheRowKernelRunsWhenAskedForAndTheRowFitsSharedMemory) {
  const ForwardStereoPass automatic(context()), rows(context(), StereoKernel::RowTiles),
      keyImages(context(), StereoKernel::PerPixel);
  const int fitting = int(widestFittingRow(context()));
  EXPECT_FALSE(automatic.usesRowKernel(fitting));  // opt-in: slower than the key-image dispatches on a GPU
  EXPECT_TRUE(rows.usesRowKernel(fitting));
  EXPECT_FALSE(keyImages.usesRowKernel(fitting));
  const int tooWide = fitting + S3D_FORWARD_ROW_CAPACITY_STEP;
  EXPECT_GT(forwardRowSharedBytes(tooWide), maxSharedBytes(context()));
  EXPECT_FALSE(automatic.usesRowKernel(tooWide));
  EXPECT_FALSE(rows.usesRowKernel(tooWide));
}

TEST_F(ForwardPass, AWideRowThatFitsAndOneThatDoesNotBothMatchTheCppReference) {
  // The widest row the shared arrays hold runs the row kernel; 256 columns more falls back to the key images.
  for (std::uint32_t width : {widestFittingRow(context()), widestFittingRow(context()) + S3D_FORWARD_ROW_CAPACITY_STEP}) {
    const test::SyntheticView view = makeNoisyBlockView(width, 3);
    const gpu::ForwardConstants c = makeForwardConstants(separation(0.02f), width, 3);
    const StereoPair cpu = synthesizeForwardReference(view.color, view.depth, c);
    const StereoPair gpu = synthesizeForwardOnGpu(context(), view.color, view.depth, c, StereoKernel::RowTiles);
    EXPECT_LE(largestChannelDifference(gpu.left, cpu.left), 1) << width;  // 1 level: unorm rounding, as above
    EXPECT_LE(largestChannelDifference(gpu.right, cpu.right), 1) << width;
  }
}

TEST_F(ForwardPass, KeptZBuffersAreTheCppZBuffersInBothKernels) {
  // What a pass recorded after the forward pass (e.g. a previous-frame fill) reads to find the holes.
  constexpr std::uint32_t width = 200, height = 6;
  const test::SyntheticView view = makeNoisyBlockView(width, height);
  const gpu::ForwardConstants c = makeForwardConstants(separation(0.08f), width, height);
  constexpr vk::ImageState kKeysAfterThePass{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                             VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  for (StereoKernel kernel : {StereoKernel::RowTiles, StereoKernel::PerPixel}) {
    const ForwardStereoPass pass(context(), kernel, ForwardKeys::Kept);
    detail::runOnCpuImages(context(), pass, view.color, view.depth, c);
    for (auto [eye, direction] : {std::pair{Eye::Left, 1.0f}, std::pair{Eye::Right, -1.0f}}) {
      const std::vector<std::byte> bytes = vk::readbackImage(context(), pass.keys(eye), kKeysAfterThePass);
      std::vector<std::uint32_t> keys(width * height);
      std::memcpy(keys.data(), bytes.data(), bytes.size());
      for (int y = 0; y < int(height); ++y) {
        const std::vector<std::uint32_t> expected = forwardSplatRow(view.depth, y, direction, c);
        const std::vector<std::uint32_t> row(keys.begin() + y * int(width), keys.begin() + (y + 1) * int(width));
        EXPECT_EQ(row, expected) << kernelName(kernel) << " row " << y << " direction " << direction;
      }
    }
  }
}

TEST_F(ForwardPass, EachRecordSplatsIntoZBuffersTheRecordBeforeEmptied) {
  // The key-image kernel's resolve empties the other pair of z-buffers for the next record instead of a clear
  // dispatch: records of changing separations on one pass give exactly a fresh pass's eyes and the C++ keys.
  constexpr std::uint32_t width = 200, height = 6;
  const test::SyntheticView view = makeNoisyBlockView(width, height);
  constexpr vk::ImageState kKeysAfterThePass{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                             VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  const ForwardStereoPass pass(context(), StereoKernel::PerPixel, ForwardKeys::Kept);
  for (float m : {0.08f, 0.02f, 0.08f, 0.0f, 0.04f}) {  // a wide separation leaves keys a narrow one must not see
    const gpu::ForwardConstants c = makeForwardConstants(separation(m), width, height);
    const StereoPair eyes = detail::runOnCpuImages(context(), pass, view.color, view.depth, c);
    const StereoPair fresh = synthesizeForwardOnGpu(context(), view.color, view.depth, c, StereoKernel::PerPixel);
    EXPECT_EQ(eyes.left.pixels, fresh.left.pixels) << m;
    EXPECT_EQ(eyes.right.pixels, fresh.right.pixels) << m;
    for (auto [eye, direction] : {std::pair{Eye::Left, 1.0f}, std::pair{Eye::Right, -1.0f}}) {
      const std::vector<std::byte> bytes = vk::readbackImage(context(), pass.keys(eye), kKeysAfterThePass);
      std::vector<std::uint32_t> keys(width * height);
      std::memcpy(keys.data(), bytes.data(), bytes.size());
      for (int y = 0; y < int(height); ++y) {
        const std::vector<std::uint32_t> expected = forwardSplatRow(view.depth, y, direction, c);
        const std::vector<std::uint32_t> row(keys.begin() + y * int(width), keys.begin() + (y + 1) * int(width));
        EXPECT_EQ(row, expected) << m << " row " << y << " direction " << direction;
      }
    }
  }
}

TEST_F(ForwardPass, TheRowKernelStoresNoZBuffersUnlessAsked) {
  const test::SyntheticView view = makeNoisyBlockView(64, 2);
  const gpu::ForwardConstants c = makeForwardConstants(separation(0.08f), 64, 2);
  const ForwardStereoPass pass(context(), StereoKernel::RowTiles);
  EXPECT_THROW(pass.keys(Eye::Left), std::logic_error);  // nothing recorded
  detail::runOnCpuImages(context(), pass, view.color, view.depth, c);
  EXPECT_THROW(pass.keys(Eye::Left), std::logic_error);  // ForwardKeys::Discarded: shared memory only
}

}  // namespace
}  // namespace s3d::stereo
